#include "core/cell_rebuild.h"

#include "core/cell_order.h"
#include "core/delaunay2d.h"
#include "core/delaunay3d.h"
#include "core/error.h"
#include "core/hull_cells.h"
#include "core/line_segments.h"
#include "core/start_grid.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace tetprobe {

SimplexMesh inner_cells(const float* positions, uint32_t probe_count, uint32_t dimension, uint32_t axis,
                        uint64_t max_cells) {
    if (axis > 2 || ((dimension == 0 || dimension == 3) && axis != 0))
        throw Error(Status::invalid_argument, "axis " + std::to_string(axis) + " does not fit dimension " + std::to_string(dimension));
    switch (dimension) {
        case 0: {
            if (probe_count != 1) throw Error(Status::degenerate, "a point set holds exactly one probe");
            SimplexMesh mesh;
            mesh.dimension = 0;
            mesh.add_cell({0, kNone32, kNone32, kNone32}, kNoSlots);
            return mesh;
        }
        case 1: return line_segments(positions, probe_count, axis);
        case 2: return delaunay_cells_2d(positions, probe_count, axis);
        case 3: return delaunay_cells_3d(positions, probe_count, max_cells);
        default: throw Error(Status::invalid_argument, "dimension must be 0 to 3");
    }
}

namespace {

// The outer cells over mesh's hull, linked to it, unless data does not extrapolate.
OuterCells outer_cells_over(SimplexMesh& mesh, const StoreData& data) {
    if (!(data.flags & kFlagNoExtrapolation) && mesh.dimension >= 1) return build_outer_cells(mesh, find_hull_facets(mesh));
    return OuterCells{};
}

static_assert(sizeof(CellSlots) == 4 * sizeof(uint32_t), "cells are read as 4 packed slots");
const uint32_t* packed_slots(const std::vector<CellSlots>& cells) {
    return cells.empty() ? nullptr : cells.front().data();
}

}  // namespace

void store_cells(SimplexMesh mesh, StoreData& data) {
    const OuterCells outer = outer_cells_over(mesh, data);
    const size_t inner = mesh.cell_count(), cells = inner + outer.vertices.size();
    data.inner_cell_count = uint32_t(inner);
    data.cell_vertices.resize(cells * 4);
    data.cell_neighbours.resize(cells * 4);
    for (size_t c = 0; c < inner; ++c) {
        std::copy_n(mesh.vertices[c].begin(), 4, &data.cell_vertices[c * 4]);
        std::copy_n(mesh.neighbours[c].begin(), 4, &data.cell_neighbours[c * 4]);
    }
    for (size_t c = 0, at = inner * 4; c < outer.vertices.size(); ++c, at += 4) {
        std::copy_n(outer.vertices[c].begin(), 4, &data.cell_vertices[at]);
        std::copy_n(outer.neighbours[c].begin(), 4, &data.cell_neighbours[at]);
    }
}

void store_cells_in_locality_order(SimplexMesh mesh, StoreData& data) {
    const OuterCells outer = outer_cells_over(mesh, data);
    const CellSource source{packed_slots(mesh.vertices), packed_slots(mesh.neighbours), packed_slots(outer.vertices),
                            packed_slots(outer.neighbours), uint32_t(mesh.cell_count()),
                            uint32_t(mesh.cell_count() + outer.vertices.size())};
    order_cells_for_locality(data, source);
}

RebuiltCells rebuild_cells(const float* positions, uint32_t probe_count, uint32_t dimension, uint32_t axis,
                           bool extrapolate, const float bounds_min[3], const float bounds_max[3],
                           const uint32_t grid[3], uint64_t max_cells) {
    for (int a = 0; a < 3; ++a)
        if (!(std::isfinite(bounds_min[a]) && std::isfinite(bounds_max[a]) && bounds_min[a] <= bounds_max[a]))
            throw Error(Status::invalid_argument, "the bounds are not finite and ordered");
    StoreData data;
    data.flags = extrapolate ? 0u : kFlagNoExtrapolation;
    data.dimension = dimension;
    data.axis = axis;
    data.positions.assign(positions, positions + size_t(probe_count) * 3);
    for (int a = 0; a < 3; ++a) {
        data.bounds_min[a] = bounds_min[a];
        data.bounds_max[a] = bounds_max[a];
        data.grid[a] = grid[a];
    }
    store_cells_in_locality_order(inner_cells(positions, probe_count, dimension, axis, max_cells), data);
    fill_start_grid(data);
    RebuiltCells out;
    out.inner_cell_count = data.inner_cell_count;
    out.cell_vertices = std::move(data.cell_vertices);
    out.cell_neighbours = std::move(data.cell_neighbours);
    for (int a = 0; a < 3; ++a) out.grid[a] = data.grid[a];
    out.grid_cells = std::move(data.grid_cells);
    return out;
}

}  // namespace tetprobe
