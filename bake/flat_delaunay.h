// 2D Delaunay triangulation of a flat probe set, obtained from TetGen: the plane points plus one apex
// above them are tetrahedralized, and every tetrahedron is then the apex over a Delaunay triangle
// (a sphere through the apex and a, b, c meets the plane in the circumcircle of a, b, c, so "empty
// sphere" and "empty circumcircle" coincide).
#pragma once

#include "core/simplex_mesh.h"

#include <Eigen/Core>

#include <vector>

namespace tetprobe {

// Triangulates points given in plane coordinates (u, v); at least 3, pairwise distinct, not all
// collinear. Returns a dimension-2 mesh (slots 0..2), neighbours across the edge opposite each vertex.
SimplexMesh delaunay_triangulate_plane(const std::vector<Eigen::Vector2d>& uv);

}  // namespace tetprobe
