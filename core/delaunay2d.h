// The exact Delaunay triangulation of a flat probe set in its stored plane coordinates (the two
// coordinates other than the store's axis): the triangles TetGen 1.5 gives the baker for the same
// points in the same order under an apex (bake/flat_delaunay.cpp), degenerate sets included. Exact
// predicates (orientation.h, insphere.h), ties broken by TetGen's perturbation by point index as it
// reaches the plane (incircle_perturbed); Bowyer-Watson insertion in the given order with triangles
// outside the hull sharing a point at infinity. A point on the line of a hull edge joins that edge's
// outside exactly when the triangle behind the edge is in conflict with it, as in TetGen.
#pragma once

#include "core/simplex_mesh.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

// Triangulates count probes (3 floats each, finite) in the coordinates other than axis (0 x, 1 y,
// 2 z), increasing order: pairwise distinct there, not all collinear. Returns a dimension-2 mesh of
// counter-clockwise triangles in canonical form (canonical_cells.h), neighbours kNone32 across hull
// edges, in unspecified order. Throws Error(Status::degenerate) for fewer than 3 probes or a set
// without area, and Error(Status::invalid_argument) for two probes at the same plane coordinates.
SimplexMesh delaunay_cells_2d(const float* positions, uint32_t count, uint32_t axis);

// The same, inserting the probes in the given order (a permutation of 0..count-1) instead of the
// given one: the triangulation does not depend on it.
SimplexMesh delaunay_cells_2d(const float* positions, uint32_t count, uint32_t axis, const std::vector<uint32_t>& insertion_order);

}  // namespace tetprobe
