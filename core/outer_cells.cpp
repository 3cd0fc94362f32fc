// The outer cells (outer_cells.h): the sweep's polynomial, its roots and the moved facet's weights.
#include "core/outer_cells.h"

#include "core/polynomial_roots.h"

#include <cmath>
#include <limits>

namespace tetprobe {

namespace {

// Roots of an outer cell's polynomial beyond this many times the query's distance from the facet
// are ignored (see view_outer_cell).
constexpr double kMaxRootRatio = 1e6;

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


bool all_finite(const double* w, uint32_t n) {
    for (uint32_t k = 0; k < n; ++k)
        if (!std::isfinite(w[k])) return false;
    return true;
}


// The point in the frame the outer cells are judged in: the store's local frame, or for a flat
// set its plane coordinates (z = 0), where the inner cells are decided too.
template <class Index>
Vec3 judged_point(const Cells<Index>& cells, const float p[3]) {
    if (cells.s.dimension != 2) return {p[0], p[1], p[2]};
    float uv[2];
    project_to_plane(p, cells.s.axis, uv);
    return {uv[0], uv[1], 0.0};
}

}  // namespace

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

template <class Index>
void answer_first_outer_cell(const Cells<Index>& cells, Location& loc) {
    OuterView o;
    o.weights[0] = 1;
    set_outer_weights(cells, cells.s.inner_cell_count, o, loc);
}
#define TP_OUTER_CELLS_INSTANTIATE(Index)                                                                    \
    template double facet_distance(const Cells<Index>&, uint32_t, const float[3]);                          \
    template OuterView view_outer_cell(const Cells<Index>&, uint32_t, const float[3], double);              \
    template void set_outer_weights(const Cells<Index>&, uint32_t, const OuterView&, Location&);            \
    template int outer_exit_slot(const Cells<Index>&, uint32_t, const double*, uint32_t);                   \
    template OuterChoice choose_outer(const Cells<Index>&, const uint32_t*, uint32_t, const float[3]);      \
    template void settle_outer_cell(const Cells<Index>&, uint32_t, const OuterView&, const float[3], Location&); \
    template void answer_first_outer_cell(const Cells<Index>&, Location&);
TP_OUTER_CELLS_INSTANTIATE(uint16_t)
TP_OUTER_CELLS_INSTANTIATE(uint32_t)
#undef TP_OUTER_CELLS_INSTANTIATE

}  // namespace tetprobe
