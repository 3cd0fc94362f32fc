// Leak control at query time: a cell whose probes include a pair that cannot see each other (a wall
// crosses the edge between them, found when the store was built with its scene) weighs down the
// probe on the far side of the wall from the query.
//
// Which side: each blocked pair stores, for each of its probes, the plane of the first surface the
// segment meets from that probe (core/leak_plane.h). A probe is hidden from the query by a pair when
// the query is not strictly in front of that probe's plane, decided exactly (the sign of N . q - offset
// with integer N: no rounding can move the plane). A probe on the query's side keeps its weight.
//
// How much: a's weight is multiplied by 1 - min(1, sum of w_b / reach_a(b)) over the blocked partners b
// in the cell with the query behind a's plane of the pair (a, b), where w_b is b's barycentric weight and
// reach_a(b) the fraction of the edge from a to that plane: the share of the query's weight held by the
// probes a cannot see, each measured against where its wall stands. On the edge itself the query is
// behind a's plane exactly when w_b >= reach_a(b), so a is dropped entirely there: the answer steps from
// a's value to b's at the wall. Inside the cell each term fades to nothing where w_b does: on the facet
// without b. So the weights are continuous
// across every facet (the facet's own probes and blocked pairs, and their planes, are the same on both
// sides; a pair with a probe off the facet changes nothing there), between a blocked cell and an
// unblocked one too, and jump only where the query crosses a wall's plane inside a cell that holds the
// wall's pair. Cells without a blocked pair
// are not touched at all (bit for bit); a query at a probe keeps weight exactly 1 there (a probe is
// strictly in front of its own planes, which the loader checks). The data is 24 bytes per blocked edge
// in the blob (32 more in memory: its two LeakPlanes, normals decoded on load, so that a query
// decodes nothing); the cost two exact side tests per blocked pair of the query's cell. (Per-probe
// depth maps, as DDGI keeps, would cost a store many times this size and change every cell's answers,
// walls or not.)
#pragma once

#include "core/store_impl.h"

namespace tetprobe {

// Share of the unmodified weights kept in a cell with a blocked pair, so that the renormalised weights
// never divide by zero when every probe of the cell is behind a wall from the query (they then fall
// back towards the plain barycentric weights, continuously).
constexpr double kLeakFloor = 1e-3;

// Fills store.leak_planes (two per leak edge, side 0 then side 1) from the blob's records. Called once on
// load, before check_leak_planes.
void decode_leak_planes(Store::Impl& store);

// Refuses (Error invalid_blob) a store whose wall planes do not separate their pair: each side's probe
// strictly in front of its plane, its partner strictly behind. Called once on load, after the positions
// are decoded and the leak lists are validated (store_validation.cpp).
void check_leak_planes(const Store::Impl& store);

// Fills store.leak_cells: which cells hold a blocked pair (so that a query in any other cell costs one
// byte read). Called once when a store with leak control is loaded, after its cell records.
void mark_blocked_cells(Store::Impl& store);

// Multiplies each probe's weight by its visibility from the query at `local` (the store's frame, as
// located) and renormalises to the same sum. Leaves loc untouched when no pair of its probes is
// blocked. The store must have leak control (leak_offsets non-null).
void weigh_by_visibility(const Store::Impl& store, const float local[3], Location& loc);

}  // namespace tetprobe
