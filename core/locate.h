// Point location in a validated store: the visibility walk from a hint (or a grid start cell),
// decided by exact orientation predicates on the stored float positions (walk.cpp), the outer cells
// beyond the hull (outer_cells.h), and the exhaustive search that referees the walk and takes over
// outside the hull when neighbouring outer cells disagree (exhaustive_search.h).
#pragma once

#include "core/locate_kernel.h"
#include "core/store_impl.h"

namespace tetprobe {

// The query's position in the store's frame: world minus origin, rounded to float exactly as the
// stored positions were.
inline void local_position(const Store::Impl& store, const float world[3], float local[3]) {
    for (int k = 0; k < 3; ++k) local[k] = float(double(world[k]) - store.origin[k]);
}


// The cell decided over all cells (an inner cell that holds the point exactly, else the best outer
// cell), or over the outer cells alone (cell -1 when none holds it). O(cells); never allocates.
Location locate_exhaustive(const Store::Impl& store, const float local[3], bool outer_only);

}  // namespace tetprobe
