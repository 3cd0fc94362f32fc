// Ordering for memory locality: a walk touches cells (and their probes) that are near each other in
// space, so they should be near each other in the blob. Both orders follow a space-filling curve
// (Morton), and both depend only on the positions, never on the order the caller gave them in.
#pragma once

#include "core/store_data.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace tetprobe {

// The canonical order of distinct points: by the Morton code of each point over [lo, hi], ties broken
// by the coordinates (x, then y, then z) and last by the index (only equal points tie that far).
// Returns the indices of points in that order.
std::vector<uint32_t> curve_order(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi);

// Reorders data's cells in place: inner cells by the Morton code of their centroid, then the inner
// cell whose centroid is nearest the centre of the probes' bounds swapped into slot 0 (the start of
// hint-less walks); outer cells after all inner cells, Morton-ordered by the centroid of their probes.
// Cells with equal codes (and equally near the centre) go by their vertex slots, so the order
// depends only on which cells there are, not on the order they came in: TetGen's cells and core's
// for the same probes end up identical. Neighbour links follow. Needs positions, bounds and cells.
void order_cells_for_locality(StoreData& data);

// 63-bit Morton code of p quantised over [lo, hi] (21 bits per axis, x lowest).
uint64_t morton_code(const double p[3], const double lo[3], const double hi[3]);

}  // namespace tetprobe
