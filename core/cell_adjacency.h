// Neighbours from vertices: what loading a compact blob (which stores no neighbours) rebuilds.
#pragma once

#include "core/store_impl.h"

#include <cstdint>

namespace tetprobe {

// Fills the neighbour slots of count cell records from their vertex slots (dimension d): two cells
// are neighbours across the facet they share (an outer cell's facet with the kOuter marker counts as
// a facet of the outer cells around a hull edge); a facet of one cell only has kNone. Throws
// Error(Status::invalid_blob) when a facet is shared by more than two cells. Allocates (once, on load).
template <class Index>
void rebuild_neighbours(CellRecord<Index>* records, uint32_t count, uint32_t dimension);

}  // namespace tetprobe
