// The walk (a visibility walk over cell adjacency, Cupisz 2012). An inner cell holds the query when
// no facet's orientation with the query is negative; each orientation's sign is exact (a filtered
// double evaluation, the exact one where the filter cannot decide), so the walk needs no tolerance:
// on a Delaunay tessellation a walk that only steps across facets the point lies strictly beyond
// terminates (Edelsbrunner's acyclicity theorem; TetGen's symbolic perturbation makes the
// tessellation of a degenerate set a regular one, to which it applies too), never steps straight
// back, and ends in a cell that holds the point. A flat cell (none was seen: TetGen is given the
// stored floats themselves) hands a point on its plane to a neighbour. The weights are the orientations divided by their sum, so a query exactly at
// a probe weighs that probe 1 and the others exactly 0. Outer cells solve their polynomial in double
// and judge the moved hull facet's weights; where their sweeps disagree far out, the outer cells are
// searched exhaustively.
#include "core/locate.h"

#include "core/orientation.h"
#include "core/plane_projection.h"
#include "core/polynomial_roots.h"
#include "core/tetrahedron_orientations.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tetprobe {

namespace {

constexpr uint32_t kNoCell = 0xFFFFFFFFu;
constexpr uint32_t kRecentOuterCells = 8;
// Roots of an outer cell's polynomial beyond this many times the query's distance from the facet
// are ignored (see view_outer_cell).
constexpr double kMaxRootRatio = 1e6;
// Bound of the 2D permanent below: 2 products of the largest |differences|, with room for the
// rounding of that bound itself (the 3D one is in tetrahedron_orientations.h).
constexpr double kOrient2dBoundScale = 2.000001 * kOrient2dErrorFactor;

// max without std::fmax's NaN rules (a libm call); the inputs here are never NaN.
inline double larger(double a, double b) { return a > b ? a : b; }

template <class Index>
constexpr uint32_t none_index() {
    return sizeof(Index) == 2 ? kNone16 : kNone32;
}

// Typed view of a store's cells.
template <class Index>
struct Cells {
    const Store::Impl& s;
    const CellRecord<Index>* records;
    explicit Cells(const Store::Impl& store) : s(store), records(static_cast<const CellRecord<Index>*>(store.cells)) {}

    uint32_t vertex(uint32_t cell, uint32_t slot) const { return records[cell].vertices[slot]; }
    uint32_t neighbour(uint32_t cell, uint32_t slot) const {
        const uint32_t n = records[cell].neighbours[slot];
        return n == none_index<Index>() ? kNoCell : n;
    }
    const float* position(uint32_t probe) const { return s.positions + 3 * size_t(probe); }
    const float* normal(uint32_t probe) const { return s.normals + 3 * size_t(probe); }

    uint32_t start_cell(const float p[3]) const {
        const StoreHeader& h = s.header;
        size_t slot = 0;
        for (int k = 2; k >= 0; --k) {
            const double extent = double(h.bounds_max[k]) - double(h.bounds_min[k]);
            uint32_t index = 0;
            if (extent > 0) {
                const double f = (double(p[k]) - double(h.bounds_min[k])) / extent * double(h.grid[k]);
                if (f >= double(h.grid[k]))
                    index = h.grid[k] - 1;
                else if (f > 0)
                    index = uint32_t(f);
            }
            slot = slot * h.grid[k] + index;
        }
        return static_cast<const Index*>(s.grid_cells)[slot];
    }
};

// An inner cell seen from the query: the orientations D[k] of the query with the facet opposite
// slot k (the cell with vertex k replaced by the query), their exact signs, and the verdict.
struct InnerView {
    enum Verdict { holds, flat, leaves } verdict;
    int exit = -1;     // leaves: the slot of the most negative orientation
    double D[4] = {0, 0, 0, 0};
    int sign[4] = {0, 0, 0, 0};
};

template <class Index>
inline __attribute__((always_inline)) InnerView view_inner_cell(const Cells<Index>& cells, uint32_t cell, const float q[3]) {
    const Store::Impl& s = cells.s;
    const uint32_t d = s.dimension;
    InnerView v;
    const float* P[4];
    for (uint32_t k = 0; k <= d; ++k) P[k] = cells.position(cells.vertex(cell, k));
    if (d == 3) {
        const Orientations o = ScalarOrientations::of(P, q);
        const double bound = o.bound;
        for (int k = 0; k < 4; ++k) v.D[k] = o.D[k];
        if ((v.D[0] > bound) & (v.D[1] > bound) & (v.D[2] > bound) & (v.D[3] > bound)) {  // the common case
            v.sign[0] = v.sign[1] = v.sign[2] = v.sign[3] = 1;
            v.verdict = InnerView::holds;
            return v;
        }
        bool uncertain = false;
        for (int k = 0; k < 4; ++k) {
            if (v.D[k] > bound) {
                v.sign[k] = 1;
            } else if (v.D[k] < -bound) {
                v.sign[k] = -1;
            } else {
                const float* w[4] = {P[0], P[1], P[2], P[3]};
                w[k] = q;
                v.sign[k] = orient3d_exact(w[0], w[1], w[2], w[3]);
                uncertain = true;
            }
        }
        // A held point the filter could not decide (on or near a facet, or in a sliver): its weights
        // from exact orientations, so that they keep double precision however thin the cell.
        if (uncertain && v.sign[0] >= 0 && v.sign[1] >= 0 && v.sign[2] >= 0 && v.sign[3] >= 0) {
            for (int k = 0; k < 4; ++k) {
                const float* w[4] = {P[0], P[1], P[2], P[3]};
                w[k] = q;
                v.D[k] = v.sign[k] > 0 ? orient3d_exact_value(w[0], w[1], w[2], w[3]) : 0.0;
            }
        }
    } else if (d == 2) {
        float uv[3][2], quv[2];
        project_to_plane(q, s.axis, quv);
        double a[3][2];
        double mu = 0, mv = 0;
        for (int i = 0; i < 3; ++i) {
            project_to_plane(P[i], s.axis, uv[i]);
            a[i][0] = double(uv[i][0]) - double(quv[0]);
            a[i][1] = double(uv[i][1]) - double(quv[1]);
            mu = larger(mu, std::fabs(a[i][0]));
            mv = larger(mv, std::fabs(a[i][1]));
        }
        auto cross = [&](int i, int j) { return a[i][0] * a[j][1] - a[j][0] * a[i][1]; };
        v.D[0] = cross(1, 2);
        v.D[1] = cross(2, 0);
        v.D[2] = cross(0, 1);
        const double bound = kOrient2dBoundScale * (mu * mv);
        bool uncertain = false;
        for (int k = 0; k < 3; ++k) {
            if (v.D[k] > bound) {
                v.sign[k] = 1;
            } else if (v.D[k] < -bound) {
                v.sign[k] = -1;
            } else {
                const float* w[3] = {uv[0], uv[1], uv[2]};
                w[k] = quv;
                v.sign[k] = orient2d_exact(w[0], w[1], w[2]);
                uncertain = true;
            }
        }
        if (uncertain && v.sign[0] >= 0 && v.sign[1] >= 0 && v.sign[2] >= 0) {
            for (int k = 0; k < 3; ++k) {
                const float* w[3] = {uv[0], uv[1], uv[2]};
                w[k] = quv;
                v.D[k] = v.sign[k] > 0 ? orient2d_exact_value(w[0], w[1], w[2]) : 0.0;
            }
        }
    } else if (d == 1) {
        // The difference of two floats in double has the exact sign.
        v.D[0] = double(P[1][s.axis]) - double(q[s.axis]);
        v.D[1] = double(q[s.axis]) - double(P[0][s.axis]);
        for (int k = 0; k < 2; ++k) v.sign[k] = v.D[k] > 0 ? 1 : (v.D[k] < 0 ? -1 : 0);
    } else {
        v.D[0] = 1;
        v.sign[0] = 1;
    }
    bool inside = true, any_positive = false;
    double most_negative = std::numeric_limits<double>::infinity();
    for (uint32_t k = 0; k <= d; ++k) {
        if (v.sign[k] < 0) {
            inside = false;
            // The most negative computed value among the exactly negative ones (any would do).
            if (v.exit < 0 || v.D[k] < most_negative) most_negative = v.D[k], v.exit = int(k);
        }
        any_positive |= v.sign[k] > 0;
    }
    v.verdict = inside ? (any_positive ? InnerView::holds : InnerView::flat) : InnerView::leaves;
    return v;
}

// Weights of a held point: the orientations over their sum, those of exact sign 0 exactly 0.
template <class Index>
inline __attribute__((always_inline)) void set_inner_weights(const Cells<Index>& cells, uint32_t cell, const InnerView& v, Location& loc) {
    const uint32_t used = cells.s.dimension + 1;
    double w[4] = {0, 0, 0, 0}, sum = 0;
    for (uint32_t k = 0; k < used; ++k) {
        w[k] = v.sign[k] > 0 ? larger(v.D[k], 0.0) : 0.0;
        sum += w[k];
    }
    if (!(sum > 0)) {  // every positive orientation rounded to zero: share equally among them
        sum = 0;
        for (uint32_t k = 0; k < used; ++k) sum += w[k] = v.sign[k] > 0 ? 1.0 : 0.0;
    }
    const double scale = 1.0 / sum;
    for (uint32_t k = 0; k < 4; ++k) {
        loc.probes[k] = cells.vertex(cell, k < used ? k : 0);
        loc.weights[k] = k < used ? float(w[k] * scale) : 0.0f;
    }
    loc.cell = int32_t(cell);
    loc.kind = CellKind::inner;
}

struct Vec3 {
    double x, y, z;
};
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double det(Vec3 a, Vec3 b, Vec3 c) { return dot(a, cross(b, c)); }
double cross2(Vec3 a, Vec3 b) { return a.x * b.y - a.y * b.x; }

// Barycentric weights of p on a segment (projected onto its line); NaN if degenerate.
void segment_weights(Vec3 a, Vec3 b, Vec3 p, double w[2]) {
    const Vec3 e = b - a;
    const double length2 = dot(e, e);
    w[1] = length2 > 0 ? dot(p - a, e) / length2 : std::numeric_limits<double>::quiet_NaN();
    w[0] = 1.0 - w[1];
}

// Barycentric weights of p on a triangle (projected onto its plane); NaN if degenerate.
void triangle_weights(Vec3 a, Vec3 b, Vec3 c, Vec3 p, double w[3]) {
    const Vec3 n = cross(b - a, c - a);
    const double n2 = dot(n, n);
    if (!(n2 > 0)) {
        w[0] = w[1] = w[2] = std::numeric_limits<double>::quiet_NaN();
        return;
    }
    w[0] = dot(n, cross(b - p, c - p)) / n2;
    w[1] = dot(n, cross(c - p, a - p)) / n2;
    w[2] = 1.0 - w[0] - w[1];
}

double minimum(const double* w, uint32_t n) {
    double m = w[0];
    for (uint32_t k = 1; k < n; ++k) m = w[k] < m ? w[k] : m;
    return m;
}

bool all_finite(const double* w, uint32_t n) {
    for (uint32_t k = 0; k < n; ++k)
        if (!std::isfinite(w[k])) return false;
    return true;
}

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

// The point in the frame the outer cells are judged in: the store's local frame, or for a flat
// set its plane coordinates (z = 0), where the inner cells are decided too.
template <class Index>
Vec3 judged_point(const Cells<Index>& cells, const float p[3]) {
    if (cells.s.dimension != 2) return {p[0], p[1], p[2]};
    float uv[2];
    project_to_plane(p, cells.s.axis, uv);
    return {uv[0], uv[1], 0.0};
}

// Distance from the query to the centroid of an outer cell's hull facet: roughly the t of its
// moved facet (probes move at unit speed along their normals).
template <class Index>
double facet_distance(const Cells<Index>& cells, uint32_t cell, const float q[3]) {
    const uint32_t d = cells.s.dimension;
    Vec3 centroid{0, 0, 0};
    for (uint32_t k = 0; k < d; ++k) {
        const float* p = cells.position(cells.vertex(cell, k));
        centroid = centroid + Vec3{p[0], p[1], p[2]};
    }
    const Vec3 offset = Vec3{q[0], q[1], q[2]} - (1.0 / double(d)) * centroid;
    return std::sqrt(dot(offset, offset));
}

// guess_t (>= 0, or negative for none): where to judge the query when no t >= 0 exists, only to
// choose the way out.
template <class Index>
OuterView view_outer_cell(const Cells<Index>& cells, uint32_t cell, const float q[3], double guess_t) {
    const Store::Impl& s = cells.s;
    const uint32_t d = s.dimension;
    OuterView v;
    const uint32_t first = cells.vertex(cell, 0);
    if (d == 1) {
        const float end = cells.position(first)[s.axis], direction = cells.normal(first)[s.axis];
        v.beyond = direction > 0 ? q[s.axis] > end : (direction < 0 && q[s.axis] < end);
        v.holds = v.judged = v.beyond;
        v.t = v.beyond ? (double(q[s.axis]) - double(end)) / double(direction) : 0.0;
        v.weights[0] = 1.0;
        return v;
    }
    const Vec3 p = judged_point(cells, q);
    Vec3 corner[3], normal[3], A[3];
    for (uint32_t k = 0; k < d; ++k) {
        const uint32_t probe = cells.vertex(cell, k);
        corner[k] = judged_point(cells, cells.position(probe));
        const Vec3 n3 = {cells.normal(probe)[0], cells.normal(probe)[1], cells.normal(probe)[2]};
        normal[k] = n3;
        if (d == 2) {
            float n[3] = {float(n3.x), float(n3.y), float(n3.z)}, uv[2];
            project_to_plane(n, s.axis, uv);
            normal[k] = {uv[0], uv[1], 0.0};
        }
        A[k] = corner[k] - p;
    }
    // f(t): the orientation of the moved facet with the query; f(0) > 0 strictly beyond the facet.
    double c[4];
    if (d == 3) {
        const float* P[3] = {cells.position(cells.vertex(cell, 0)), cells.position(cells.vertex(cell, 1)),
                             cells.position(cells.vertex(cell, 2))};
        v.beyond = orient3d(P[0], P[1], P[2], q) > 0;
        c[0] = -det(normal[0], normal[1], normal[2]);
        c[1] = -(det(normal[0], normal[1], A[2]) + det(normal[0], A[1], normal[2]) + det(A[0], normal[1], normal[2]));
        c[2] = -(det(normal[0], A[1], A[2]) + det(A[0], normal[1], A[2]) + det(A[0], A[1], normal[2]));
        c[3] = -det(A[0], A[1], A[2]);
    } else {
        float uv[3][2];
        project_to_plane(cells.position(cells.vertex(cell, 0)), s.axis, uv[0]);
        project_to_plane(cells.position(cells.vertex(cell, 1)), s.axis, uv[1]);
        project_to_plane(q, s.axis, uv[2]);
        v.beyond = orient2d(uv[0], uv[1], uv[2]) > 0;
        c[0] = 0;
        c[1] = cross2(normal[0], normal[1]);
        c[2] = cross2(normal[0], A[1]) + cross2(A[0], normal[1]);
        c[3] = cross2(A[0], A[1]);
    }
    if (!v.beyond) return v;
    double candidates[3];
    int count = 0;
    double roots[3];
    const int n = cubic_real_roots(c[0], c[1], c[2], c[3], roots);
    // A root a million times farther out than the query is from the facet is the rounding of a
    // nearly vanishing leading coefficient (nearly parallel normals), not where the sweep meets it.
    const double farthest = kMaxRootRatio * facet_distance(cells, cell, q);
    for (int i = 0; i < n; ++i)
        if (roots[i] >= 0 && roots[i] <= farthest) candidates[count++] = roots[i];
    v.holds = count > 0;
    if (!v.holds) {
        if (!(guess_t >= 0)) return v;
        candidates[count++] = guess_t;  // the moving facet never meets the query: judge near where it should
    }
    double best_score = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; ++i) {
        const double t = candidates[i];
        double w[3];
        if (d == 2)
            segment_weights(corner[0] + t * normal[0], corner[1] + t * normal[1], p, w);
        else
            triangle_weights(corner[0] + t * normal[0], corner[1] + t * normal[1], corner[2] + t * normal[2], p, w);
        if (!all_finite(w, d)) continue;
        // A moved facet that has turned over (a sliver's, whose probes' normals diverge) holds
        // nothing there: its weights would mirror the facet's.
        bool kept = true;
        if (d == 3) {
            const Vec3 facet = cross(corner[1] - corner[0], corner[2] - corner[0]);
            const Vec3 moved = cross((corner[1] + t * normal[1]) - (corner[0] + t * normal[0]),
                                     (corner[2] + t * normal[2]) - (corner[0] + t * normal[0]));
            kept = dot(moved, facet) > 0;
        } else {
            kept = dot((corner[1] + t * normal[1]) - (corner[0] + t * normal[0]), corner[1] - corner[0]) > 0;
        }
        const double score = kept ? minimum(w, d) : -std::numeric_limits<double>::infinity();
        if (!v.judged || score > best_score) {
            best_score = score;
            v.judged = true;
            v.t = t;
            for (uint32_t k = 0; k < d; ++k) v.weights[k] = w[k];
            v.turned_over = !kept;
        }
    }
    v.holds = v.holds && v.judged && !v.turned_over;
    return v;
}

// Weights of an outer cell: negatives clamped to zero, renormalised to sum 1.
template <class Index>
void set_outer_weights(const Cells<Index>& cells, uint32_t cell, const OuterView& o, Location& loc) {
    const uint32_t used = cells.s.dimension;
    double clamped[3] = {0, 0, 0}, sum = 0;
    for (uint32_t k = 0; k < used; ++k) sum += clamped[k] = o.weights[k] > 0 ? o.weights[k] : 0.0;
    if (!(sum > 0) || !std::isfinite(sum)) {
        clamped[0] = sum = 1.0;
        for (uint32_t k = 1; k < used; ++k) clamped[k] = 0.0;
    }
    for (uint32_t k = 0; k < 4; ++k) {
        loc.probes[k] = cells.vertex(cell, k < used ? k : 0);
        loc.weights[k] = k < used ? float(std::fmin(clamped[k] / sum, 1.0)) : 0.0f;
    }
    loc.cell = int32_t(cell);
    loc.kind = CellKind::outer;
    loc.t = float(o.t);
}

// The slot to leave an outer cell through: the most negative weight whose neighbour is not the cell
// we came from (going back only when there is no other way). -1 when there is no neighbour at all.
template <class Index>
int outer_exit_slot(const Cells<Index>& cells, uint32_t cell, const double* w, uint32_t previous) {
    int best = -1, back = -1;
    double best_value = std::numeric_limits<double>::infinity();
    for (uint32_t k = 0; k < cells.s.dimension; ++k) {
        const uint32_t n = cells.neighbour(cell, k);
        if (n == kNoCell) continue;
        if (n == previous)
            back = int(k);
        else if (w[k] < best_value)
            best_value = w[k], best = int(k);
    }
    return best >= 0 ? best : back;
}

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
OuterChoice choose_outer(const Cells<Index>& cells, const uint32_t* candidates, uint32_t count, const float q[3]) {
    const uint32_t d = cells.s.dimension;
    OuterView views[4];
    double first_t = std::numeric_limits<double>::infinity();
    for (uint32_t i = 0; i < count; ++i) {
        views[i] = view_outer_cell(cells, candidates[i], q, -1.0);
        const OuterView& v = views[i];
        if (v.beyond && v.holds && minimum(v.weights, d) >= -kOuterWeightTolerance && v.t < first_t) first_t = v.t;
    }
    OuterChoice best;
    for (uint32_t i = 0; i < count; ++i) {
        const OuterView& v = views[i];
        if (!v.beyond || !v.holds || v.t > 2 * first_t + 1e-300) continue;
        const double score = minimum(v.weights, d);
        if (score < -kOuterWeightTolerance) continue;
        const uint32_t cell = candidates[i];
        if (score > best.score || (score == best.score && cell < best.cell)) best.cell = cell, best.view = v, best.score = score;
    }
    return best;
}

template <class Index>
void settle_outer_cell(const Cells<Index>& cells, uint32_t cell, const OuterView& o, const float q[3], Location& loc) {
    uint32_t candidates[4] = {cell};
    uint32_t count = 1;
    for (uint32_t k = 0; k < cells.s.dimension; ++k) {
        const uint32_t n = cells.neighbour(cell, k);
        if (n != kNoCell && n >= cells.s.inner_cell_count) candidates[count++] = n;
    }
    const OuterChoice best = choose_outer(cells, candidates, count, q);
    if (best.cell == 0xFFFFFFFFu)
        set_outer_weights(cells, cell, o, loc);  // accepted by the walk on its own weights
    else
        set_outer_weights(cells, best.cell, best.view, loc);
}

// Nothing holds the point (only a store whose outer cells leave gaps): the first outer cell.
template <class Index>
void answer_first_outer_cell(const Cells<Index>& cells, Location& loc) {
    OuterView o;
    o.weights[0] = 1;
    set_outer_weights(cells, cells.s.inner_cell_count, o, loc);
}

// The exhaustive search examines at most *budget cells (each view of a cell counts, so a pass over
// the outer cells costs one per outer cell) and subtracts what it used; with the budget spent it
// gives up: status invalid_blob, cell -1 (only a corrupt or forged store's query gets there: see
// search_budget). Unlimited: a budget of UINT64_MAX.
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
            const InnerView v = view_inner_cell(cells, cell, q);
            if (v.verdict == InnerView::holds) {
                set_inner_weights(cells, cell, v, loc);
                return loc;
            }
        }
        if (s.cell_count == s.inner_cell_count) {  // outside a store without extrapolation
            loc.status = s.dimension == 0 ? Status::ok : Status::outside;
            if (s.dimension == 0) set_inner_weights(cells, 0, view_inner_cell(cells, 0, q), loc);
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

template <class Index>
Location walk(const Store::Impl& s, const float q[3], int32_t hint);

#define TP_WALK_CLEAR_NAME walk_clear_portable
#define TP_LOCATE_GROUP_NAME locate_group_portable
#define TP_WALK_CLEAR_KERNEL ScalarOrientations
#include "core/walk_clear.inl"
#undef TP_WALK_CLEAR_NAME
#undef TP_LOCATE_GROUP_NAME
#undef TP_WALK_CLEAR_KERNEL
#ifdef TETPROBE_X86_64
#pragma GCC push_options
#pragma GCC target("avx2")
#define TP_WALK_CLEAR_NAME walk_clear_avx2
#define TP_LOCATE_GROUP_NAME locate_group_avx2
#define TP_WALK_CLEAR_KERNEL Avx2Orientations
#include "core/walk_clear.inl"
#undef TP_WALK_CLEAR_NAME
#undef TP_LOCATE_GROUP_NAME
#undef TP_WALK_CLEAR_KERNEL
#pragma GCC pop_options
#endif

template <class Index>
bool walk_clear(const Cells<Index>& cells, uint32_t* cell, const float q[3], uint32_t* steps, uint32_t step_cap,
                Location& loc) {
#ifdef TETPROBE_X86_64
    if (cells.s.avx2) return walk_clear_avx2(cells, cell, q, steps, step_cap, loc);
#endif
    return walk_clear_portable(cells, cell, q, steps, step_cap, loc);
}

// What one query may examine, whatever the blob. The loader cannot prove a tessellation Delaunay, so
// a forged one may send walks round in circles and every query into the exhaustive search. A walk on
// a valid store never visits a cell twice, so it stops after cell_count + 64 steps (a long walk, from
// a far hint or along a line, is legitimate: the cap never cuts one short). The search may then view
// every outer cell three times (its passes: what a valid store's fallback beyond the hull needs, so
// no valid query reaches the cap) plus kSearchCells more (inside the hull a valid store never
// searches); past that the query gives up with status invalid_blob. So a query on any blob costs at
// most about as many cell views as the store has cells, like the costliest valid query.
constexpr uint64_t kSearchCells = 4096;

uint64_t search_budget(const Store::Impl& s) { return 3 * uint64_t(s.cell_count - s.inner_cell_count) + kSearchCells; }

template <class Index>
Location walk(const Store::Impl& s, const float q[3], int32_t hint) {
    const Cells<Index> cells(s);
    uint32_t cell = (hint >= 0 && uint32_t(hint) < s.cell_count) ? uint32_t(hint) : cells.start_cell(q);
    const uint32_t step_cap = s.cell_count + 64;
    uint32_t steps = 0;
    Location loc;
    if (s.dimension == 3 && walk_clear(cells, &cell, q, &steps, step_cap, loc)) return loc;
    uint32_t previous = kNoCell;
    double last_t = -1.0;       // t of the last outer cell that held the query's moved facet
    bool beyond_hull = false;   // an outer cell found the query strictly beyond its hull facet
    uint32_t recent[kRecentOuterCells];
    uint32_t outer_visits = 0;
    for (; steps <= step_cap; ++steps) {
        uint32_t next;
        if (cell < s.inner_cell_count) {
            const InnerView v = view_inner_cell(cells, cell, q);
            if (v.verdict == InnerView::holds) {
                set_inner_weights(cells, cell, v, loc);
                loc.steps = steps;
                return loc;
            }
            if (v.verdict == InnerView::flat) {
                // A zero-volume cell holds no point: hand the query (on its plane) to a neighbour.
                next = kNoCell;
                for (uint32_t k = 0; k <= s.dimension && next == kNoCell; ++k) {
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
                    return loc;
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
                next = cells.neighbour(cell, s.dimension);  // the inner cell it rests on decides
            } else {
                beyond_hull = true;
                if (!o.judged) break;
                if (o.holds) {
                    last_t = o.t;
                    const double score = minimum(o.weights, s.dimension);
                    if (score >= 0) {  // holds it: on a shared edge, the neighbour's weights are the same
                        set_outer_weights(cells, cell, o, loc);
                        loc.steps = steps;
                        return loc;
                    }
                    if (score >= -kOuterWeightTolerance) {  // in a gap between sweeps, within the tolerance
                        settle_outer_cell(cells, cell, o, q, loc);
                        loc.steps = steps;
                        return loc;
                    }
                }
                const int slot = outer_exit_slot(cells, cell, o.weights, previous);
                if (slot < 0) {
                    if (!o.holds) break;
                    settle_outer_cell(cells, cell, o, q, loc);
                    loc.steps = steps;
                    return loc;
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
    return loc;
}

}  // namespace

namespace {
template <class Index>
void locate_group_typed(const Store::Impl& s, size_t count, const float (*q)[3], const int32_t* hints,
                        Location* out) {
    const Cells<Index> cells(s);
    if (s.dimension != 3) {
        for (size_t i = 0; i < count; ++i) out[i] = walk<Index>(s, q[i], hints[i]);
        return;
    }
#ifdef TETPROBE_X86_64
    if (s.avx2) return locate_group_avx2(cells, count, q, hints, out);
#endif
    locate_group_portable(cells, count, q, hints, out);
}
}  // namespace

void locate_group(const Store::Impl& store, size_t count, const float (*local)[3], const int32_t* hints,
                  Location* out) {
    if (store.index32)
        locate_group_typed<uint32_t>(store, count, local, hints, out);
    else
        locate_group_typed<uint16_t>(store, count, local, hints, out);
}

Location locate_local(const Store::Impl& store, const float local[3], int32_t hint) {
    return store.index32 ? walk<uint32_t>(store, local, hint) : walk<uint16_t>(store, local, hint);
}

namespace {
template <class Index>
void prefetch_cell_typed(const Store::Impl& s, uint32_t cell) {
    const CellRecord<Index>& r = static_cast<const CellRecord<Index>*>(s.cells)[cell];
    for (int k = 0; k < 4; ++k) {
        const uint32_t v = r.vertices[k];
        if (v < s.probe_count) __builtin_prefetch(s.positions + 3 * size_t(v));
    }
}
}  // namespace

void prefetch_cell(const Store::Impl& store, int32_t cell) {
    if (cell < 0 || uint32_t(cell) >= store.cell_count) return;
    if (store.index32)
        prefetch_cell_typed<uint32_t>(store, uint32_t(cell));
    else
        prefetch_cell_typed<uint16_t>(store, uint32_t(cell));
}

Location locate_exhaustive(const Store::Impl& store, const float local[3], bool outer_only) {
    uint64_t unlimited = UINT64_MAX;
    return store.index32 ? search<uint32_t>(store, local, outer_only, &unlimited)
                         : search<uint16_t>(store, local, outer_only, &unlimited);
}

}  // namespace tetprobe
