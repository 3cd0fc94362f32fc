// The exhaustive search: the walk's referee, and its fallback beyond the hull where neighbouring
// outer cells' sweeps disagree. O(cells) exact decisions; never allocates.
#pragma once

#include "core/store_impl.h"

#include <cstdint>

namespace tetprobe {

// The exhaustive search examines at most *budget cells (each view of a cell counts, so a pass over
// the outer cells costs one per outer cell) and subtracts what it used; with the budget spent it
// gives up: status invalid_blob, cell -1 (only a corrupt or forged store's query gets there: see
// search_budget). Unlimited: a budget of UINT64_MAX.
template <class Index>
Location search(const Store::Impl& s, const float q[3], bool outer_only, uint64_t* budget);

// What one query's search may examine, whatever the blob (see search_budget in exhaustive_search.cpp).
uint64_t search_budget(const Store::Impl& s);

}  // namespace tetprobe
