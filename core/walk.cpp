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
#include "core/lane_orientations.h"
#include "core/outer_cells.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>

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

// The cell a query starts in: its hint when that is a cell, else the start grid's cell.
template <class Index>
inline uint32_t start_of(const Cells<Index>& cells, const float q[3], int32_t hint) {
    return hint >= 0 && uint32_t(hint) < cells.s.cell_count ? uint32_t(hint) : cells.start_cell(q);
}

// A batch's loads asked for ahead (walk_clear.inl): the hinted cell records of its first queries, then
// at query i the record of query i + kRecordAhead and the vertex positions of query i + kPositionsAhead.
constexpr size_t kRecordAhead = 16, kPositionsAhead = 8;
template <class Index>
inline uint32_t hinted_inner_cell(const Cells<Index>& cells, const int32_t* hints, size_t i) {
    const int32_t hint = hints[i];
    return hint >= 0 && uint32_t(hint) < cells.s.inner_cell_count ? uint32_t(hint) : kNoCell;
}
template <class Index>
inline void prefetch_first(const Cells<Index>& cells, size_t count, const int32_t* hints) {
    for (size_t i = 0; i < count && i < kRecordAhead; ++i) {
        const uint32_t cell = hinted_inner_cell(cells, hints, i);
        if (cell != kNoCell) __builtin_prefetch(&cells.records[cell]);
    }
}
template <class Index>
inline void prefetch_ahead(const Cells<Index>& cells, size_t i, size_t count, const int32_t* hints) {
    const uint32_t record = i + kRecordAhead < count ? hinted_inner_cell(cells, hints, i + kRecordAhead) : kNoCell;
    if (record != kNoCell) __builtin_prefetch(&cells.records[record]);
    const uint32_t ahead = i + kPositionsAhead < count ? hinted_inner_cell(cells, hints, i + kPositionsAhead) : kNoCell;
    if (ahead != kNoCell)
        for (uint32_t k = 0; k < 4; ++k) __builtin_prefetch(cells.position(cells.vertex(ahead, k)));
}

#define TP_WALK_ISA(name) name##_portable
#define TP_WALK_CLEAR_KERNEL ScalarOrientations
#define TP_WALK_AVX2 false
#define TP_WALK_TARGET
#define TP_LANE_KERNEL ScalarLaneOrientations
#include "core/walk_clear.inl"
#include "core/walk_lanes.inl"
#undef TP_LANE_KERNEL
#undef TP_WALK_ISA
#undef TP_WALK_CLEAR_KERNEL
#undef TP_WALK_AVX2
#undef TP_WALK_TARGET
#ifdef TETPROBE_X86_64
#pragma GCC push_options
#pragma GCC target("avx2")
#define TP_WALK_ISA(name) name##_avx2
#define TP_WALK_CLEAR_KERNEL Avx2Orientations
#define TP_WALK_AVX2 true
#define TP_WALK_TARGET __attribute__((target("avx2")))  // clang has no target pragma
#define TP_LANE_KERNEL Avx2LaneOrientations
#include "core/walk_clear.inl"
#include "core/walk_lanes.inl"
#undef TP_LANE_KERNEL
#undef TP_WALK_ISA
#undef TP_WALK_CLEAR_KERNEL
#undef TP_WALK_AVX2
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

// The kernels of a store of dimension 0 to 2: the general walk alone.
template <class Index, uint32_t D>
void locate_low(const Store::Impl& s, const float q[3], int32_t hint, Location& loc) {
    const Cells<Index> cells(s);
    walk_general<Index, D, false>(s, q, start_of(cells, q, hint), 0, loc);
}

template <class Index, uint32_t D>
void locate_batch_low(const Store::Impl& s, size_t count, const float (*q)[3], const int32_t* hints, Location* out) {
    for (size_t i = 0; i < count; ++i) locate_low<Index, D>(s, q[i], hints[i], out[i]);
}

template <class Index, uint32_t D>
Status interpolate_low(const Store::Impl& s, const float q[3], int32_t* hint, float out_sh[27]) {
    Location loc;
    locate_low<Index, D>(s, q, *hint, loc);
    *hint = loc.cell;
    return answer_sh(s, loc, out_sh, nullptr);
}

template <class Index, uint32_t D>
void interpolate_batch_low(const Store::Impl& s, size_t count, const float (*q)[3], int32_t* hints, float* const* out_sh,
                           Status* status) {
    for (size_t i = 0; i < count; ++i) status[i] = interpolate_low<Index, D>(s, q[i], &hints[i], out_sh[i]);
}

template <class Index, uint32_t D>
LocateKernel kernel_low() {
    return {locate_low<Index, D>, locate_batch_low<Index, D>, interpolate_low<Index, D>, interpolate_batch_low<Index, D>,
            InstructionSet::portable, BatchKernel::loop};
}

template <class Index>
LocateKernel kernel_3d(InstructionSet instruction_set, BatchKernel batch) {
    const bool lanes = batch == BatchKernel::lanes;
#ifdef TETPROBE_X86_64
    if (instruction_set == InstructionSet::avx2)
        return {locate_avx2<Index>, locate_batch_avx2<Index>, interpolate_avx2<Index>,
                lanes ? interpolate_batch_lanes_avx2<Index> : interpolate_batch_avx2<Index>, instruction_set, batch};
#endif
    return {locate_portable<Index>, locate_batch_portable<Index>, interpolate_portable<Index>,
            lanes ? interpolate_batch_lanes_portable<Index> : interpolate_batch_portable<Index>, InstructionSet::portable,
            batch};
}

template <class Index>
LocateKernel kernel_for_dimension(uint32_t dimension, InstructionSet instruction_set, BatchKernel batch) {
    switch (dimension) {
        case 0: return kernel_low<Index, 0>();
        case 1: return kernel_low<Index, 1>();
        case 2: return kernel_low<Index, 2>();
        default: return kernel_3d<Index>(instruction_set, batch);
    }
}

}  // namespace

InstructionSet detect_instruction_set() {
    return half_simd_available() && !std::getenv("TP_NO_AVX2") ? InstructionSet::avx2 : InstructionSet::portable;
}

// The lanes unless the environment says otherwise: level with the loop on small stores, faster on large ones,
// where the lanes' loads of different queries overlap (tetprobe_bench store --queries, TP_BATCH_KERNEL=loop).
BatchKernel detect_batch_kernel() {
    const char* chosen = std::getenv("TP_BATCH_KERNEL");
    if (chosen && std::strcmp(chosen, "loop") == 0) return BatchKernel::loop;
    if (chosen && std::strcmp(chosen, "lanes") == 0) return BatchKernel::lanes;
    return BatchKernel::lanes;
}

LocateKernel choose_locate_kernel(const Store::Impl& store, InstructionSet instruction_set) {
    const BatchKernel batch = detect_batch_kernel();
    LocateKernel kernel = store.index32 ? kernel_for_dimension<uint32_t>(store.dimension, instruction_set, batch)
                                        : kernel_for_dimension<uint16_t>(store.dimension, instruction_set, batch);
    return kernel;
}

}  // namespace tetprobe
