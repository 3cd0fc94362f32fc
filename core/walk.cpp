// The walk (a visibility walk over cell adjacency, Cupisz 2012). An inner cell holds the query when
// no facet's orientation with the query is negative; each orientation's sign is exact (a filtered
// double evaluation, the exact one where the filter cannot decide), so the walk needs no tolerance:
// on a Delaunay tessellation a walk that only steps across facets the point lies strictly beyond
// terminates (Edelsbrunner's acyclicity theorem; TetGen's symbolic perturbation makes the
// tessellation of a degenerate set a regular one, to which it applies too), never steps straight
// back, and ends in a cell that holds the point. A flat cell (none was seen: TetGen is given the
// stored floats themselves) hands a point on its plane to a neighbour. The weights are the
// orientations divided by their sum, so a query exactly at a probe weighs that probe 1 and the
// others exactly 0. Beyond the hull the walk moves through the outer cells (outer_cells.h); where
// their sweeps disagree far out, the outer cells are searched exhaustively (exhaustive_search.h).
//
// Each walk is compiled for an index width, a dimension and an instruction set; a store picks its
// own once, at load (choose_locate_kernel).
#include "core/locate.h"

#include "core/cell_view.h"
#include "core/exhaustive_search.h"
#include "core/half.h"
#include "core/outer_cells.h"

#include <cstdint>
#include <cstdlib>

namespace tetprobe {

namespace {

constexpr uint32_t kRecentOuterCells = 8;

// What one walk may step, whatever the blob. The loader cannot prove a tessellation Delaunay, so a
// forged one may send walks round in circles. A walk on a valid store never visits a cell twice, so
// it stops after cell_count + 64 steps (a long walk, from a far hint or along a line, is legitimate:
// the cap never cuts one short) and hands the query to the capped exhaustive search
// (exhaustive_search.cpp).
inline uint32_t walk_step_cap(const Store::Impl& s) { return s.cell_count + 64; }

// The general walk from cell, steps already taken: every cell kind, every dimension, the fallback.
// loc may hold an earlier answer: it is reset here, on the rare path, so that a batch need not reset
// its Locations (answers are written in place: a copied Location costs store-forwarding stalls on the
// common path).
template <class Index, uint32_t D, bool Avx2>
void walk_general(const Store::Impl& s, const float q[3], uint32_t cell, uint32_t steps, Location& loc);

#define TP_WALK_CLEAR_NAME walk_clear_portable
#define TP_WALK_CLEAR_KERNEL ScalarOrientations
#define TP_WALK_TARGET
#include "core/walk_clear.inl"
#undef TP_WALK_CLEAR_NAME
#undef TP_WALK_CLEAR_KERNEL
#undef TP_WALK_TARGET
#ifdef TETPROBE_X86_64
#pragma GCC push_options
#pragma GCC target("avx2")
#define TP_WALK_CLEAR_NAME walk_clear_avx2
#define TP_WALK_CLEAR_KERNEL Avx2Orientations
#define TP_WALK_TARGET __attribute__((target("avx2")))  // clang has no target pragma
#include "core/walk_clear.inl"
#undef TP_WALK_CLEAR_NAME
#undef TP_WALK_CLEAR_KERNEL
#undef TP_WALK_TARGET
#pragma GCC pop_options
#endif

template <class Index, uint32_t D, bool Avx2>
void walk_general(const Store::Impl& s, const float q[3], uint32_t cell, uint32_t steps, Location& loc) {
    loc = Location();
    const Cells<Index> cells(s);
    const uint32_t step_cap = walk_step_cap(s);
    uint32_t previous = kNoCell;
    double last_t = -1.0;       // t of the last outer cell that held the query's moved facet
    bool beyond_hull = false;   // an outer cell found the query strictly beyond its hull facet
    uint32_t recent[kRecentOuterCells];
    uint32_t outer_visits = 0;
    for (; steps <= step_cap; ++steps) {
        uint32_t next;
        if (cell < s.inner_cell_count) {
            const InnerView v = view_inner_cell(cells, cell, q, D);
            if (v.verdict == InnerView::holds) {
                set_inner_weights(cells, cell, v, loc, D);
                loc.steps = steps;
                return;
            }
            if (v.verdict == InnerView::flat) {
                // A zero-volume cell holds no point: hand the query (on its plane) to a neighbour.
                next = kNoCell;
                for (uint32_t k = 0; k <= D && next == kNoCell; ++k) {
                    const uint32_t n = cells.neighbour(cell, k);
                    if (n != previous) next = n;
                }
                if (next == kNoCell) break;
            } else {
                next = cells.neighbour(cell, uint32_t(v.exit));
                if (next == kNoCell) {  // strictly beyond a facet of the convex hull
                    loc.status = Status::outside;
                    loc.cell = int32_t(cell);
                    loc.steps = steps;
                    return;
                }
            }
        } else {
            bool cycling = false;
            for (uint32_t i = 0; i < outer_visits && i < kRecentOuterCells; ++i) cycling |= recent[i] == cell;
            if (cycling) break;
            recent[outer_visits++ % kRecentOuterCells] = cell;
            const double guess_t = last_t >= 0 ? last_t : facet_distance(cells, cell, q);
            const OuterView o = view_outer_cell(cells, cell, q, guess_t);
            if (!o.beyond) {
                next = cells.neighbour(cell, D);  // the inner cell it rests on decides
            } else {
                beyond_hull = true;
                if (!o.judged) break;
                if (o.holds) {
                    last_t = o.t;
                    const double score = minimum(o.weights, D);
                    if (score >= 0) {  // holds it: on a shared edge, the neighbour's weights are the same
                        set_outer_weights(cells, cell, o, loc);
                        loc.steps = steps;
                        return;
                    }
                    if (score >= -kOuterWeightTolerance) {  // in a gap between sweeps, within the tolerance
                        settle_outer_cell(cells, cell, o, q, loc);
                        loc.steps = steps;
                        return;
                    }
                }
                const int slot = outer_exit_slot(cells, cell, o.weights, previous);
                if (slot < 0) {
                    if (!o.holds) break;
                    settle_outer_cell(cells, cell, o, q, loc);
                    loc.steps = steps;
                    return;
                }
                next = cells.neighbour(cell, uint32_t(slot));
            }
        }
        previous = cell;
        cell = next;
    }
    // Lost among outer cells whose sweeps disagree far out (or a corrupt tessellation): decide over
    // the outer cells alone when the query is beyond the hull, else over every cell.
    uint64_t budget = search_budget(s);
    loc = search<Index>(s, q, beyond_hull, &budget);
    // Beyond the hull no inner cell holds the point either: searching all cells would end the same.
    if (loc.cell < 0 && loc.status == Status::ok) answer_first_outer_cell(cells, loc);
    loc.steps = steps;
    return;
}

template <class Index, uint32_t D, bool Avx2>
void walk(const Store::Impl& s, const float q[3], int32_t hint, Location& loc) {
    const Cells<Index> cells(s);
    uint32_t cell = (hint >= 0 && uint32_t(hint) < s.cell_count) ? uint32_t(hint) : cells.start_cell(q);
    uint32_t steps = 0;
    if (D == 3) {
#ifdef TETPROBE_X86_64
        if (Avx2 ? walk_clear_avx2(cells, &cell, q, &steps, walk_step_cap(s), loc)
                 : walk_clear_portable(cells, &cell, q, &steps, walk_step_cap(s), loc))
            return;
#else
        if (walk_clear_portable(cells, &cell, q, &steps, walk_step_cap(s), loc)) return;
#endif
    }
    walk_general<Index, D, Avx2>(s, q, cell, steps, loc);
}

// A batch is the single walk, query after query, with each query's dependent loads asked for ahead:
// its hint's cell record kRecordAhead queries before it runs, then (the record has arrived) that
// cell's vertex positions kPositionsAhead before; walk_clear asks for the SH of its start cell itself.
// The queries are independent, so the CPU overlaps them out of order. An 8-lane structure-of-arrays
// walk (four queries' cells per AVX2 call) measured no faster than this loop: one cell's four
// orientations already fill a vector, and a coherent query rarely takes a step.
template <class Index, uint32_t D, bool Avx2>
void locate_batch(const Store::Impl& s, size_t count, const float (*q)[3], const int32_t* hints, Location* out) {
    constexpr size_t kRecordAhead = 16, kPositionsAhead = 8;
    const Cells<Index> cells(s);
    const auto hinted_cell = [&](size_t i) {
        const int32_t hint = hints[i];
        return hint >= 0 && uint32_t(hint) < s.inner_cell_count ? uint32_t(hint) : kNoCell;
    };
    if (D == 3)
        for (size_t i = 0; i < count && i < kRecordAhead; ++i)
            if (hinted_cell(i) != kNoCell) __builtin_prefetch(&cells.records[hinted_cell(i)]);
    for (size_t i = 0; i < count; ++i) {
        if (D == 3) {
            if (i + kRecordAhead < count && hinted_cell(i + kRecordAhead) != kNoCell)
                __builtin_prefetch(&cells.records[hinted_cell(i + kRecordAhead)]);
            const uint32_t ahead = i + kPositionsAhead < count ? hinted_cell(i + kPositionsAhead) : kNoCell;
            if (ahead != kNoCell)
                for (uint32_t k = 0; k < 4; ++k) __builtin_prefetch(cells.position(cells.vertex(ahead, k)));
        }
        walk<Index, D, Avx2>(s, q[i], hints[i], out[i]);
    }
}

template <class Index, uint32_t D, bool Avx2>
LocateKernel kernel_of(InstructionSet instruction_set) {
    return {walk<Index, D, Avx2>, locate_batch<Index, D, Avx2>, instruction_set};
}

template <class Index>
LocateKernel kernel_for_dimension(uint32_t dimension, InstructionSet instruction_set) {
    const bool avx2 = instruction_set == InstructionSet::avx2;
    switch (dimension) {
        case 0: return kernel_of<Index, 0, false>(InstructionSet::portable);
        case 1: return kernel_of<Index, 1, false>(InstructionSet::portable);
        case 2: return kernel_of<Index, 2, false>(InstructionSet::portable);
        default:
            return avx2 ? kernel_of<Index, 3, true>(instruction_set) : kernel_of<Index, 3, false>(instruction_set);
    }
}

}  // namespace

InstructionSet detect_instruction_set() {
    return half_simd_available() && !std::getenv("TP_NO_AVX2") ? InstructionSet::avx2 : InstructionSet::portable;
}

LocateKernel choose_locate_kernel(const Store::Impl& store, InstructionSet instruction_set) {
    return store.index32 ? kernel_for_dimension<uint32_t>(store.dimension, instruction_set)
                         : kernel_for_dimension<uint16_t>(store.dimension, instruction_set);
}

}  // namespace tetprobe
