// Leak control at query time: a cell whose probes include a pair that cannot see each other (a wall
// crosses the edge between them, found when the store was built with its scene) weighs down the
// probe on the far side of the wall from the query.
//
// Why this shape: each probe a of the cell gets a visibility from t_a, the share of the query's
// weights held by the probes a cannot see (0 at a, 1 on the far side), through a smoothstep over
// their ramps [start, end] (the wall crossing of each blocked edge, widened, averaged with the same
// weights). On an edge this is exactly where the query crosses the wall; inside a cell cut by a wall
// it measures how far the query is from a's side. A probe whose blocked partners all have zero
// weight keeps visibility 1, and the blocked partners' weights vanish on every facet that does not
// hold them, so the weights stay continuous across every facet, between a blocked cell and an
// unblocked one too; cells without a blocked pair are not touched at all (bit for bit); a query at a
// probe keeps weight exactly 1 there. The data is a few bytes per blocked edge, the cost a short list
// scan per probe of the cell. (Per-probe depth maps, as DDGI keeps, would cost a store many times
// this size and change every cell's answers, walls or not.)
#pragma once

#include "core/store_impl.h"

namespace tetprobe {

// Share of the unmodified weights kept in a cell with a blocked pair, so that the renormalised weights
// never divide by zero when every probe of the cell is behind a wall from the query (they then fall
// back towards the plain barycentric weights, continuously).
constexpr double kLeakFloor = 1e-3;

// Fills store.leak_cells: which cells hold a blocked pair (so that a query in any other cell costs one
// byte read). Called once when a store with leak control is loaded, after its cell records.
void mark_blocked_cells(Store::Impl& store);

// Multiplies each probe's weight by its visibility from the query and renormalises to the same sum. Leaves loc untouched when no pair of its probes is
// blocked. The store must have leak control (leak_offsets non-null).
void weigh_by_visibility(const Store::Impl& store, Location& loc);

}  // namespace tetprobe
