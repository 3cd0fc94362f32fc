// Delaunay tetrahedralization of a general (3D) point set by TetGen 1.5.
#pragma once

#include "core/simplex_mesh.h"

#include <Eigen/Core>

#include <vector>

namespace tetprobe {

// Tetrahedralizes points (at least 4, finite, pairwise distinct, not all coplanar: the caller's
// dimension detection and merging guarantee it, because TetGen aborts the process otherwise).
// Returns a dimension-3 mesh; TetGen may leave a point unused, which the caller checks. Calls into
// TetGen are serialised process-wide (its predicates keep global state); its int throws become
// Error(Status::tetgen).
SimplexMesh delaunay_tetrahedralize(const std::vector<Eigen::Vector3d>& points);

}  // namespace tetprobe
