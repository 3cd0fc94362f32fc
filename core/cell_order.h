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

// Where the cells to order are: inner cells 0..inner-1 and outer cells inner..cells-1, 4 slots each,
// in two arrays that need not be one (the rebuild's mesh and its outer cells, so that the cells are
// copied once, into their ordered places).
struct CellSource {
    const uint32_t* inner_vertices;
    const uint32_t* inner_neighbours;
    const uint32_t* outer_vertices;
    const uint32_t* outer_neighbours;
    uint32_t inner, cells;
    const uint32_t* vertices(uint32_t c) const {
        return c < inner ? inner_vertices + size_t(c) * 4 : outer_vertices + size_t(c - inner) * 4;
    }
    const uint32_t* neighbours(uint32_t c) const {
        return c < inner ? inner_neighbours + size_t(c) * 4 : outer_neighbours + size_t(c - inner) * 4;
    }
};

// The same order, reading the cells from source and writing them, ordered, to data's inner_cell_count,
// cell_vertices and cell_neighbours (data's positions and bounds as above; source must not point into
// data's cell arrays).
void order_cells_for_locality(StoreData& data, const CellSource& source);

// 63-bit Morton code of p quantised over [lo, hi] (21 bits per axis, x lowest).
uint64_t morton_code(const double p[3], const double lo[3], const double hi[3]);

}  // namespace tetprobe
