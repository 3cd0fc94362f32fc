// The exact Delaunay tetrahedralization of float32 points: the cells TetGen 1.5 builds for the same
// points in the same order, degenerate sets included. Every decision is an exact predicate
// (orientation.h, insphere.h); ties (five points on one sphere, a new hull point in the plane of a hull
// side) are broken by TetGen's symbolic perturbation by point index, which makes the tessellation
// unique, so inserting in any order gives it. Bowyer-Watson insertion in the given order (the store's
// space-filling-curve order keeps each point-location walk short), with cells outside the hull that
// share a point at infinity; a point in the plane of a hull side joins the hull exactly when the
// inner cell behind that side is in conflict with it, as in TetGen.
#pragma once

#include "core/simplex_mesh.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

// Tetrahedralizes count points (3 floats each, finite, pairwise distinct, not all coplanar). Returns a
// dimension-3 mesh of positively oriented cells in canonical form (canonical_cells.h), neighbours
// kNone32 across hull facets; the cells' order is unspecified (the store orders them afterwards).
// Throws Error(Status::degenerate) for fewer than 4 points or a set without volume, and
// Error(Status::invalid_argument) for two equal points.
SimplexMesh delaunay_cells_3d(const float* positions, uint32_t count);

// The same, inserting the points in the given order (a permutation of 0..count-1) instead of the
// function's own: the tessellation does not depend on it (the tests check that it does not).
SimplexMesh delaunay_cells_3d(const float* positions, uint32_t count, const std::vector<uint32_t>& insertion_order);

}  // namespace tetprobe
