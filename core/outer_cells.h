// The outer cells beyond the hull: each is swept by its hull facet moving along its probes' normals;
// a query is judged by the parameter t at which the moved facet reaches it (a cubic solved in double)
// and the facet's barycentric weights there. Shared by the walk and the exhaustive search.
#pragma once

#include "core/cell_view.h"

namespace tetprobe {

// Moved-facet weights of an outer cell within this tolerance below zero still hold a point: the
// outer cells alone are judged after a root solve, in double.
constexpr double kOuterWeightTolerance = 1e-5;

// An outer cell seen from the query: whether the query is strictly beyond its hull facet (exact),
// and the moved facet that holds it.
struct OuterView {
    bool beyond = false;  // strictly beyond the hull facet (exact sign)
    bool holds = false;   // a parameter t >= 0 puts the query in the plane (line) of the moved facet
    bool judged = false;  // weights are available (at that t, or at the guess when no t exists)
    double t = 0;
    double weights[3] = {0, 0, 0};  // over slots 0..d-1
    bool turned_over = false;       // the moved facet at t is mirrored
};

// The smallest of n weights.
inline double minimum(const double* w, uint32_t n) {
    double m = w[0];
    for (uint32_t k = 1; k < n; ++k) m = w[k] < m ? w[k] : m;
    return m;
}

// Distance from the query to the centroid of an outer cell's hull facet: roughly the t of its
// moved facet (probes move at unit speed along their normals).
template <class Index>
double facet_distance(const Cells<Index>& cells, uint32_t cell, const float q[3]);

// guess_t (>= 0, or negative for none): where to judge the query when no t >= 0 exists, only to
// choose the way out.
template <class Index>
OuterView view_outer_cell(const Cells<Index>& cells, uint32_t cell, const float q[3], double guess_t);

// Weights of an outer cell: negatives clamped to zero, renormalised to sum 1.
template <class Index>
void set_outer_weights(const Cells<Index>& cells, uint32_t cell, const OuterView& o, Location& loc);

// The slot to leave an outer cell through: the most negative weight whose neighbour is not the cell
// we came from (going back only when there is no other way). -1 when there is no neighbour at all.
template <class Index>
int outer_exit_slot(const Cells<Index>& cells, uint32_t cell, const double* w, uint32_t previous);

// Choosing among outer cells that hold the query (within the tolerance): the sweep that reaches it
// first, give or take a factor 2 in t (a degenerate cubic can also put the query inside a moved
// facet at an absurd t, such as 1e15), and among those the one holding it best (largest smallest
// weight), ties to the lower index. The walk applies it to a cell it accepted only within the
// tolerance and that cell's outer neighbours, the exhaustive search to every outer cell, so that in
// a gap between neighbouring sweeps the answer does not depend on the start. (Where sweeps overlap,
// which only converging normals make, the walk answers with the first cell that holds the query.)
struct OuterChoice {
    uint32_t cell = 0xFFFFFFFFu;
    OuterView view;
    double score = -std::numeric_limits<double>::infinity();
};

template <class Index>
OuterChoice choose_outer(const Cells<Index>& cells, const uint32_t* candidates, uint32_t count, const float q[3]);

// A cell the walk accepted within the tolerance, judged together with its outer neighbours.
template <class Index>
void settle_outer_cell(const Cells<Index>& cells, uint32_t cell, const OuterView& o, const float q[3], Location& loc);

// Nothing holds the point (only a store whose outer cells leave gaps): the first outer cell.
template <class Index>
void answer_first_outer_cell(const Cells<Index>& cells, Location& loc);

}  // namespace tetprobe
