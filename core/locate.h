// Point location in a validated store: the visibility walk from a hint (or a grid start cell),
// decided by exact orientation predicates on the stored float positions, and the exhaustive search
// that referees it (and takes over outside the hull when neighbouring outer cells disagree).
#pragma once

#include "core/store_impl.h"

namespace tetprobe {

// Moved-facet weights of an outer cell within this tolerance below zero still hold a point: the
// outer cells alone are judged after a root solve, in double.
constexpr double kOuterWeightTolerance = 1e-5;

// The query's position in the store's frame: world minus origin, rounded to float exactly as the
// stored positions were.
inline void local_position(const Store::Impl& store, const float world[3], float local[3]) {
    for (int k = 0; k < 3; ++k) local[k] = float(double(world[k]) - store.origin[k]);
}

// Finds the cell holding a local position, starting from hint (-1 or out of range: the grid).
Location locate_local(const Store::Impl& store, const float local[3], int32_t hint);

// Up to kMaxGroup queries at once (a batch's): the same answers as locate_local on each, their
// first tests overlapped.
constexpr size_t kMaxGroup = 8;
void locate_group(const Store::Impl& store, size_t count, const float (*local)[3], const int32_t* hints,
                  Location* out);

// Asks the memory system early for what a walk from cell will read first: the cell's record and its
// vertices' positions (a batch calls it a few queries ahead, so that queries overlap their misses).
void prefetch_cell(const Store::Impl& store, int32_t cell);

// The cell decided over all cells (an inner cell that holds the point exactly, else the best outer
// cell), or over the outer cells alone (cell -1 when none holds it). O(cells); never allocates.
Location locate_exhaustive(const Store::Impl& store, const float local[3], bool outer_only);

}  // namespace tetprobe
