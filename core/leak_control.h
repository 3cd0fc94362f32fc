// Leak control at query time: a cell whose probes include a pair that cannot see each other (a wall
// crosses the edge between them, found when the store was built with its scene) weighs down the
// probe on the far side of the wall from the query.
//
// Why this shape: the factor of a blocked pair (a, b) depends only on where the query projects onto
// the edge a-b in the cell's own barycentrics, t = w_b / (w_a + w_b), through a smoothstep over the
// stored ramp [start, end] (the wall crossing, widened). On a facet that does not hold b, w_b = 0, so
// t = 0 and a keeps its factor 1 (b's weight is 0 anyway); the neighbour across that facet, without
// b, sees the same weights. So the weights stay continuous across every facet, between a blocked
// cell and an unblocked one too; cells without a blocked pair are not touched at all (bit for bit);
// a query at a probe keeps weight exactly 1 there. The data is a few bytes per blocked edge, the cost
// a short list scan per probe of the cell.
#pragma once

#include "core/store_impl.h"

namespace tetprobe {

// Share of the unmodified weights kept in a cell with a blocked pair, so that the renormalised weights
// never divide by zero when every probe of the cell is behind a wall from the query (they then fall
// back towards the plain barycentric weights, continuously).
constexpr double kLeakFloor = 1e-3;

// Multiplies each probe's weight by its visibility from the query (the product over its blocked pairs
// in the cell) and renormalises to the same sum. Leaves loc untouched when no pair of its probes is
// blocked. The store must have leak control (leak_offsets non-null).
void weigh_by_visibility(const Store::Impl& store, Location& loc);

}  // namespace tetprobe
