// Peeling of slivers off the hull: nearly coplanar (or, in a flat set, nearly collinear) probes on
// the hull make Delaunay cells of almost no volume there, whose barycentric matrices are huge and
// whose float evaluation is noise. Removing them leaves a hull that is non-convex by at most their
// thickness, and the outer cells extrapolate over the peeled region instead.
#pragma once

#include "bake/set_dimension.h"
#include "bake/simplex_mesh.h"

#include <Eigen/Core>

#include <vector>

namespace tetprobe {

// Cells thinner than this (signed volume / longest edge^3 in 3D, area / longest edge^2 in 2D) are slivers.
constexpr double kSliverThickness = 1e-5;

// Repeatedly removes hull cells (d = 2, 3) thinner than kSliverThickness while the boundary stays a
// manifold, every probe keeps a cell, and no probe ends farther than kSliverThickness x the cell's
// longest edge beyond a facet the removal exposes; renumbers the remaining cells. Returns how many
// were removed.
size_t peel_hull_slivers(SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& positions, const SetShape& shape);

// Thickness of a cell as above (1 for dimensions below 2).
double cell_thickness(const SimplexMesh& mesh, size_t cell, const std::vector<Eigen::Vector3d>& positions,
                      const SetShape& shape);

}  // namespace tetprobe
