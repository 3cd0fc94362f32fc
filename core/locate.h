// Point location in a validated store: the walk from a hint (or a grid start cell) across inner and
// outer cells, and the exhaustive double-precision decision it falls back to when it seems lost.
#pragma once

#include "core/store_impl.h"

namespace tetprobe {

// Barycentric coordinates within this tolerance below zero still count as inside a cell.
constexpr float kInsideTolerance = 1e-5f;

// The walk for the given index width (chosen once, when a store is loaded).
LocateFunction locate_function(bool index32);

// Finds the inner cells of zero volume (by the builder's own test, in double on the stored
// positions) and records them in store.zero_volume. Called once when a store is loaded.
void mark_zero_volume_cells(Store::Impl& store);

// The cell of a local position decided over all cells in double precision: the cell whose smallest
// barycentric coordinate (or, for outer cells, moved-triangle weight) is largest. O(cells); the
// walk's fallback, and a referee for tests. Never allocates.
Location locate_exhaustive(const Store::Impl& store, const double local_position[3]);

// The same over the outer cells alone, for a point beyond a hull facet (then outside the hull, up to
// the depth of peeled slivers, so an outer cell answers it): O(outer cells). Returns false, leaving
// out alone, when none holds it.
bool locate_exhaustive_outer(const Store::Impl& store, const double local_position[3], Location& out);

}  // namespace tetprobe
