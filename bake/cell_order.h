// Cell ordering for memory locality: a walk touches cells that are near each other in space, so
// they should be near each other in the blob.
#pragma once

#include "core/store_data.h"

namespace tetprobe {

// Reorders data's cells in place: inner cells by the Morton code of their centroid, then the inner
// cell whose centroid is nearest the probes' mean swapped into slot 0 (the start of hint-less walks);
// outer cells after all inner cells, Morton-ordered by the centroid of their probes. Neighbour links
// and matrices follow. Needs positions, bounds, cells and matrices filled.
void order_cells_for_locality(StoreData& data);

// 63-bit Morton code of p quantised over [lo, hi] (21 bits per axis, x lowest).
uint64_t morton_code(const float p[3], const float lo[3], const float hi[3]);

}  // namespace tetprobe
