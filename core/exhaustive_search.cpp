// The exhaustive search (exhaustive_search.h): every inner cell by exact orientations, then the outer
// cells in two passes (the sweep that reaches the query first, then the cell holding it best).
#include "core/exhaustive_search.h"

#include "core/cell_view.h"
#include "core/locate.h"
#include "core/outer_cells.h"

#include <algorithm>
#include <limits>

namespace tetprobe {

template <class Index>
Location search(const Store::Impl& s, const float q[3], bool outer_only, uint64_t* budget) {
    const Cells<Index> cells(s);
    Location loc;
    loc.fallback = true;
    const uint64_t available = *budget;
    auto spend = [&] {
        if (*budget == 0) return false;
        --*budget;
        ++loc.searched;
        return true;
    };
    auto give_up = [&] {
        Location capped;
        capped.fallback = true;
        capped.status = Status::invalid_blob;
        capped.searched = uint32_t(std::min<uint64_t>(available, UINT32_MAX));
        return capped;
    };
    if (!outer_only) {
        for (uint32_t cell = 0; cell < s.inner_cell_count; ++cell) {
            if (!spend()) return give_up();
            const InnerView v = view_inner_cell(cells, cell, q, s.dimension);
            if (v.verdict == InnerView::holds) {
                set_inner_weights(cells, cell, v, loc, s.dimension);
                return loc;
            }
        }
        if (s.cell_count == s.inner_cell_count) {  // outside a store without extrapolation
            loc.status = s.dimension == 0 ? Status::ok : Status::outside;
            if (s.dimension == 0) set_inner_weights(cells, 0, view_inner_cell(cells, 0, q, 0), loc, 0);
            return loc;
        }
    }
    // Cells holding the query within the tolerance decide (choose_outer); failing those, the cell
    // holding it best.
    OuterChoice best;
    {
        double first_t = std::numeric_limits<double>::infinity();
        for (int pass = 0; pass < 2 && best.cell == 0xFFFFFFFFu; ++pass) {
            for (uint32_t cell = s.inner_cell_count; cell < s.cell_count; ++cell) {
                if (!spend()) return give_up();
                const OuterView o = view_outer_cell(cells, cell, q, -1.0);
                if (!o.beyond || !o.holds) continue;
                const double score = minimum(o.weights, s.dimension);
                if (score < -kOuterWeightTolerance) continue;
                if (pass == 0) {
                    first_t = o.t < first_t ? o.t : first_t;
                    continue;
                }
                if (o.t > 2 * first_t + 1e-300) continue;
                if (score > best.score) best.cell = cell, best.view = o, best.score = score;
            }
            if (pass == 0 && first_t == std::numeric_limits<double>::infinity()) break;
        }
    }
    if (best.cell != 0xFFFFFFFFu) {
        set_outer_weights(cells, best.cell, best.view, loc);
    } else {
        double best_score = -std::numeric_limits<double>::infinity();
        for (uint32_t cell = s.inner_cell_count; cell < s.cell_count; ++cell) {
            if (!spend()) return give_up();
            const OuterView o = view_outer_cell(cells, cell, q, -1.0);
            if (!o.beyond || !o.holds) continue;
            const double score = minimum(o.weights, s.dimension);
            if (score > best_score) {
                best_score = score;
                set_outer_weights(cells, cell, o, loc);
            }
        }
    }
    if (loc.cell < 0 && !outer_only) answer_first_outer_cell(cells, loc);
    return loc;
}

// What one query may examine, whatever the blob. The loader cannot prove a tessellation Delaunay, so
// a forged one may send walks round in circles and every query into the exhaustive search (the walk
// bounds its own steps: walk.cpp). The search may view every outer cell three times (its passes:
// what a valid store's fallback beyond the hull needs, so no valid query reaches the cap) plus
// kSearchCells more (inside the hull a valid store never searches); past that the query gives up
// with status invalid_blob.
constexpr uint64_t kSearchCells = 4096;

uint64_t search_budget(const Store::Impl& s) { return 3 * uint64_t(s.cell_count - s.inner_cell_count) + kSearchCells; }

template Location search<uint16_t>(const Store::Impl&, const float[3], bool, uint64_t*);
template Location search<uint32_t>(const Store::Impl&, const float[3], bool, uint64_t*);

Location locate_exhaustive(const Store::Impl& store, const float local[3], bool outer_only) {
    uint64_t unlimited = UINT64_MAX;
    return store.index32 ? search<uint32_t>(store, local, outer_only, &unlimited)
                         : search<uint16_t>(store, local, outer_only, &unlimited);
}

}  // namespace tetprobe
