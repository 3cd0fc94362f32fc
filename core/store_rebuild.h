// The rebuilt layout's cells at load: a blob of that layout stores no cells, no neighbours and no start
// grid; the loader rebuilds them from the stored probes with core's tessellation (cell_rebuild.h), the
// same steps the builder ran, so the store walks exactly the cells the other layouts store.
#pragma once

#include "core/store_impl.h"

#include <cstdint>

namespace tetprobe {

// The most cells a rebuilt-layout blob may claim per probe (header check): a Delaunay tessellation of n
// probes in general position has about 6.5 n; sets with many more (probes on two skew lines make n^2/4)
// are refused by the builder for this layout and by the loader, which bounds the rebuild's work by the
// header's counts.
constexpr uint64_t kMaxRebuiltCellsPerProbe = 16;
constexpr uint64_t kRebuiltCellSlack = 64;

// The rebuild's cap on live cells while tessellating: the header's cells and room for the intermediate
// tessellations of insertion (a valid blob never reaches it; the builder checks with the same cap).
inline uint64_t rebuilt_cell_budget(uint64_t cell_count) { return 4 * cell_count + 1024; }

// Fills s.cells and s.grid_cells (owned by s) from s.positions and the header (dimension, axis, bounds,
// start grid dimensions, extrapolation). Throws Error(Status::invalid_blob) naming what differs when the
// probes do not tessellate into the header's inner and outer cell counts, or cannot be tessellated at
// all (degenerate, coincident, over the budget).
void rebuild_store_cells(Store::Impl& s);

}  // namespace tetprobe
