// The cold-start grid: a coarse grid over the probes' bounds whose entries name an inner cell to
// start a hint-less walk from, so a new or teleported object's first walk is short.
#pragma once

#include "core/store_data.h"

#include <cstdint>

namespace tetprobe {

constexpr uint32_t kMaxStartGridCells = 1u << 22;

// Inner cells per grid entry the builder aims at. A stored grid costs bytes only, so it is fine; the
// rebuilt layout's is filled at load, a walk per entry (a sizeable part of the rebuild), so it is
// coarser there: half the entries, at the cost of a cold query walking a little further from its
// entry (coarser still saved little more load time and cost a larger share of a cold query).
constexpr uint32_t kStoredStartGridCellsPerEntry = 4;
constexpr uint32_t kRebuiltStartGridCellsPerEntry = 8;

// Grid dimensions over the extents: proportional to them, about (inner_cells / cells_per_entry)^(1/3)
// per axis for a cube, each >= 1, product <= kMaxStartGridCells; a flat extent gets 1.
void start_grid_dimensions(const float lo[3], const float hi[3], uint32_t inner_cells, uint32_t cells_per_entry,
                           uint32_t out[3]);

// Fills data.grid_cells for the dimensions in data.grid: each entry is the inner cell containing the
// grid cell's centre rounded to float (found by a walk with the run time's exact orientation
// predicates over the finished inner cells, from the previous entry's cell), or, for a centre outside
// the hull, the last inner cell that walk reached on the hull. Plain IEEE arithmetic and exact signs:
// the same cells and dimensions give the same grid on every platform. Throws Error
// (Status::invalid_argument) for dimensions out of range.
void fill_start_grid(StoreData& data);

// data.grid from start_grid_dimensions at the layout's cells per entry (std::pow may round differently
// on another platform: a loader takes the dimensions the store holds), then fill_start_grid.
void build_start_grid(StoreData& data);

}  // namespace tetprobe
