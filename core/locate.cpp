// The walk (a visibility walk over cell adjacency, Cupisz 2012). Inner cells decide in float from
// their barycentric matrices, in the store's local frame; outer cells solve their cubic and
// weigh the moved hull triangle in double. The walk never steps straight back to the cell it came
// from, and after a step cap it hands the decision to an exhaustive search in double.
#include "core/locate.h"

#include "core/polynomial_roots.h"

#include <cmath>
#include <limits>

namespace tetprobe {

namespace {

constexpr uint32_t kNoCell = 0xFFFFFFFFu;
constexpr uint32_t kRecentCells = 8;
constexpr double kInsideToleranceD = double(kInsideTolerance);
// 32 float steps (2^-24 each) of a barycentric's terms: the rows' own rounding, the products and the
// sums, with room to spare.
constexpr double kRowRounding = 32.0 / 16777216.0;

template <class Index>
struct IndexTraits;
template <>
struct IndexTraits<uint16_t> {
    static constexpr uint32_t none = kNone16;
};
template <>
struct IndexTraits<uint32_t> {
    static constexpr uint32_t none = kNone32;
};

// Typed views of a store's cell arrays.
template <class Index>
struct CellView {
    const Store::Impl& s;
    const Index* vertices;
    const Index* neighbours;
    explicit CellView(const Store::Impl& store)
        : s(store),
          vertices(static_cast<const Index*>(store.cell_vertices)),
          neighbours(static_cast<const Index*>(store.cell_neighbours)) {}

    uint32_t vertex(uint32_t cell, uint32_t slot) const { return vertices[4 * size_t(cell) + slot]; }
    uint32_t neighbour(uint32_t cell, uint32_t slot) const {
        const uint32_t n = neighbours[4 * size_t(cell) + slot];
        return n == IndexTraits<Index>::none ? kNoCell : n;
    }
    uint32_t start_cell(const double p[3]) const {
        const StoreHeader& h = s.header;
        uint32_t index[3];
        for (int k = 0; k < 3; ++k) {
            const double extent = double(h.bounds_max[k]) - double(h.bounds_min[k]);
            index[k] = 0;
            if (extent > 0) {
                const double f = (p[k] - double(h.bounds_min[k])) / extent * double(h.grid[k]);
                if (f >= double(h.grid[k]))
                    index[k] = h.grid[k] - 1;
                else if (f > 0)
                    index[k] = uint32_t(f);  // NaN fails both tests and stays 0
            }
        }
        const size_t slot = (size_t(index[2]) * h.grid[1] + index[1]) * h.grid[0] + index[0];
        return static_cast<const Index*>(s.grid_cells)[slot];
    }
};

struct Vec3 {
    double x, y, z;
};
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

Vec3 probe_position(const Store::Impl& s, uint32_t probe) {
    const float* p = s.positions + 3 * size_t(probe);
    return {p[0], p[1], p[2]};
}
Vec3 probe_normal(const Store::Impl& s, uint32_t probe) {
    const float* n = s.normals + 3 * size_t(probe);
    return {n[0], n[1], n[2]};
}

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

// Barycentric weights of p in a tetrahedron; NaN if degenerate.
void tetrahedron_weights(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 p, double w[4]) {
    const Vec3 e1 = b - a, e2 = c - a, e3 = d - a, q = p - a;
    const double volume = dot(e1, cross(e2, e3));
    if (volume == 0.0) {
        w[0] = w[1] = w[2] = w[3] = std::numeric_limits<double>::quiet_NaN();
        return;
    }
    w[1] = dot(q, cross(e2, e3)) / volume;
    w[2] = dot(e1, cross(q, e3)) / volume;
    w[3] = dot(e1, cross(e2, q)) / volume;
    w[0] = 1.0 - w[1] - w[2] - w[3];
}

double minimum(const double* w, int n) {
    double m = w[0];
    for (int k = 1; k < n; ++k) m = w[k] < m ? w[k] : m;
    return m;
}

bool all_finite(const double* w, int n) {
    for (int k = 0; k < n; ++k)
        if (!std::isfinite(w[k])) return false;
    return true;
}

// An outer cell seen from p: the polynomial's coefficients, and the moved hull simplex that holds p.
struct OuterView {
    bool finite = true;
    double f0 = 0;        // f(0) = c3: > 0 strictly beyond the hull facet
    bool holds = false;   // a parameter t >= 0 puts p in the plane (line) of the moved facet
    bool judged = false;  // weights are available (at that t, or at the guess when no t exists)
    double t = 0;
    double weights[3] = {0, 0, 0};  // over slots 0..d-1
};

// came_from_base: the walk arrived from the inner cell below, so a point on (or numerically just
// inside) the hull facet is judged here at t = 0 instead of being sent back. guess_t (>= 0, or
// negative for none): where to judge p when no t >= 0 exists, only to choose the way out.
template <class Index>
OuterView view_outer_cell(const CellView<Index>& cells, uint32_t cell, Vec3 p, bool came_from_base, double guess_t) {
    const Store::Impl& s = cells.s;
    const uint32_t d = s.dimension;
    const float* m = s.outer_matrices + 16 * size_t(cell - s.inner_cell_count);
    const Vec3 q = p - probe_position(s, cells.vertex(cell, 0));  // rows are relative to slot 0
    double c[4];
    for (int r = 0; r < 4; ++r) c[r] = m[4 * r] * q.x + m[4 * r + 1] * q.y + m[4 * r + 2] * q.z + double(m[4 * r + 3]);
    OuterView v;
    v.finite = all_finite(c, 4);
    v.f0 = c[3];
    if (!v.finite || (c[3] <= 0 && !came_from_base)) return v;  // not beyond the facet: the inner cell decides
    if (d == 1) {
        v.holds = v.judged = true;
        v.t = c[3] > 0 ? c[3] : 0.0;
        v.weights[0] = 1.0;
        return v;
    }
    double candidates[3];
    int count = 0;
    if (c[3] <= 0) {
        candidates[count++] = 0.0;
    } else {
        double roots[3];
        const int n = cubic_real_roots(c[0], c[1], c[2], c[3], roots);
        for (int i = 0; i < n; ++i)
            if (roots[i] >= 0) candidates[count++] = roots[i];
    }
    v.holds = count > 0;
    if (!v.holds) {
        if (!(guess_t >= 0)) return v;
        candidates[count++] = guess_t;  // the moving facet never meets p: judge near where it should
    }
    Vec3 corner[3], normal[3];
    for (uint32_t k = 0; k < d; ++k) {
        const uint32_t probe = cells.vertex(cell, k);
        corner[k] = probe_position(s, probe);
        normal[k] = probe_normal(s, probe);
    }
    double best_score = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < count; ++i) {
        const double t = candidates[i];
        double w[3];
        if (d == 2)
            segment_weights(corner[0] + t * normal[0], corner[1] + t * normal[1], p, w);
        else
            triangle_weights(corner[0] + t * normal[0], corner[1] + t * normal[1], corner[2] + t * normal[2], p, w);
        if (!all_finite(w, int(d))) continue;
        const double score = minimum(w, int(d));
        if (score > best_score) {
            best_score = score;
            v.judged = true;
            v.t = t;
            for (uint32_t k = 0; k < d; ++k) v.weights[k] = w[k];
        }
    }
    v.holds = v.holds && v.judged;
    return v;
}

// Distance from p to the centroid of an outer cell's hull facet: roughly the t of p's moved facet
// (probes move at unit speed along their normals).
template <class Index>
double facet_distance(const CellView<Index>& cells, uint32_t cell, Vec3 p) {
    const uint32_t d = cells.s.dimension;
    Vec3 centroid{0, 0, 0};
    for (uint32_t k = 0; k < d; ++k) centroid = centroid + probe_position(cells.s, cells.vertex(cell, k));
    const Vec3 offset = p - (1.0 / double(d)) * centroid;
    return std::sqrt(dot(offset, offset));
}

// Fills the probes and weights of a location: negatives clamped to zero, renormalised to sum 1,
// unused slots repeating slot 0 with weight 0.
template <class Index>
void set_weights(const CellView<Index>& cells, uint32_t cell, uint32_t used, const double* w, Location& loc) {
    double clamped[4] = {0, 0, 0, 0};
    double sum = 0;
    for (uint32_t k = 0; k < used; ++k) {
        clamped[k] = w[k] > 0 ? w[k] : 0.0;  // NaN becomes 0 too
        sum += clamped[k];
    }
    if (!(sum > 0) || !std::isfinite(sum)) {
        clamped[0] = 1.0;
        for (uint32_t k = 1; k < used; ++k) clamped[k] = 0.0;
        sum = 1.0;
    }
    for (uint32_t k = 0; k < 4; ++k) {
        if (k < used) {
            const double weight = clamped[k] / sum;
            loc.probes[k] = cells.vertex(cell, k);
            loc.weights[k] = float(weight < 1.0 ? weight : 1.0);
        } else {
            loc.probes[k] = cells.vertex(cell, 0);
            loc.weights[k] = 0.0f;
        }
    }
}

// Two cells may disagree by rounding about which side of their shared face p is on; within this
// tolerance the walk stops on the face instead of going back.
constexpr double kSharedFaceTolerance = 1e-4;

// The slot to leave a cell through: the most negative weight whose neighbour is not the cell we came
// from (with may_stop, only weights below -kInsideTolerance count). Returns -1 to stop here: with
// may_stop, when the only way out leads straight back by less than kSharedFaceTolerance, or when
// there is no neighbour at all.
template <class Index>
int exit_slot(const CellView<Index>& cells, uint32_t cell, const double* w, uint32_t slots, uint32_t previous,
              bool may_stop) {
    int best = -1, back = -1;
    double best_value = may_stop ? -kInsideToleranceD : std::numeric_limits<double>::infinity();
    double back_value = std::numeric_limits<double>::infinity();
    for (uint32_t k = 0; k < slots; ++k) {
        const uint32_t n = cells.neighbour(cell, k);
        if (n == kNoCell) continue;
        if (n == previous) {
            if (w[k] < back_value) back_value = w[k], back = int(k);
        } else if (w[k] < best_value) {
            best_value = w[k], best = int(k);
        }
    }
    if (best >= 0) return best;
    if (back < 0) return -1;
    if (may_stop && back_value >= -kSharedFaceTolerance) return -1;
    return back;  // a real disagreement: going back lets the step cap and the exhaustive search settle it
}

// The exhaustive search over cells [first_cell, cell_count): all cells, or (first_cell =
// inner_cell_count) only the outer cells, for a point known to be outside the hull. Returns false,
// leaving loc alone, when no cell of the range holds the point.
template <class Index>
bool locate_exhaustive_from(const Store::Impl& s, const double local[3], uint32_t first_cell, Location& out) {
    const CellView<Index> cells(s);
    const Vec3 p{local[0], local[1], local[2]};
    const uint32_t d = s.dimension;
    double best_score = -std::numeric_limits<double>::infinity();
    uint32_t best_cell = kNoCell;
    double best_weights[4] = {1, 0, 0, 0};
    double best_t = 0;
    for (uint32_t cell = first_cell; cell < s.cell_count; ++cell) {
        double w[4] = {0, 0, 0, 0};
        double t = 0;
        uint32_t used;
        if (cell < s.inner_cell_count) {
            if (!s.zero_volume.empty() && s.zero_volume[cell]) continue;  // holds no point
            used = d + 1;
            Vec3 v[4];
            for (uint32_t k = 0; k <= d; ++k) v[k] = probe_position(s, cells.vertex(cell, k));
            if (d == 0)
                w[0] = 1.0;
            else if (d == 1)
                segment_weights(v[0], v[1], p, w);
            else if (d == 2)
                triangle_weights(v[0], v[1], v[2], p, w);
            else
                tetrahedron_weights(v[0], v[1], v[2], v[3], p, w);
        } else {
            used = d;
            const OuterView o = view_outer_cell(cells, cell, p, false, -1.0);
            if (!o.finite || !o.holds || !(o.f0 > 0)) continue;
            t = o.t;
            for (uint32_t k = 0; k < d; ++k) w[k] = o.weights[k];
        }
        if (!all_finite(w, int(used))) continue;
        const double score = minimum(w, int(used));
        if (score > best_score) {
            best_score = score;
            best_cell = cell;
            best_t = t;
            for (int k = 0; k < 4; ++k) best_weights[k] = w[k];
        }
    }
    if (best_cell == kNoCell) {
        if (first_cell > 0) return false;
        best_cell = 0;  // nothing finite anywhere: the first cell, as good as any
    }
    Location loc;
    loc.fallback = true;
    loc.cell = int32_t(best_cell);
    const bool outer = best_cell >= s.inner_cell_count;
    loc.kind = outer ? TP_CELL_OUTER : TP_CELL_INNER;
    if (s.cell_count == s.inner_cell_count && (s.header.flags & kFlagNoExtrapolation) && d > 0 &&
        !(best_score >= -kInsideToleranceD)) {
        loc.status = TP_ERROR_OUTSIDE;
        out = loc;
        return true;
    }
    loc.t = float(best_t);
    set_weights(cells, best_cell, outer ? d : d + 1, best_weights, loc);
    out = loc;
    return true;
}

template <class Index>
Location locate_exhaustive_typed(const Store::Impl& s, const double local[3]) {
    Location loc;
    locate_exhaustive_from<Index>(s, local, 0, loc);
    return loc;
}

// local: the position in the store's frame in double, local_f the same rounded to float (the
// frame of the stored positions and matrices).
template <class Index>
Location walk_cells(const Store::Impl& s, const double local[3], const float local_f[3], int32_t hint) {
    const CellView<Index> cells(s);
    const Vec3 p{local[0], local[1], local[2]};
    const uint32_t d = s.dimension;
    uint32_t cell = (hint >= 0 && uint32_t(hint) < s.cell_count) ? uint32_t(hint) : cells.start_cell(local);
    uint32_t previous = kNoCell;
    double last_t = -1.0;  // t of the last outer cell that held p's moved facet
    bool beyond_hull = false;  // an outer cell found p strictly beyond its hull facet
    // The last few cells: a walk that comes back to one of them is cycling, which a consistent
    // walk never does, so the exhaustive search takes over at once.
    uint32_t recent[kRecentCells];
    for (uint32_t& r : recent) r = kNoCell;
    uint32_t steps = 0;
    for (; steps <= s.step_cap; ++steps) {
        if (steps > 0) {
            bool cycling = false;
            for (uint32_t r : recent) cycling |= r == cell;
            if (cycling) break;
        }
        recent[steps % kRecentCells] = cell;
        Location loc;
        loc.cell = int32_t(cell);
        loc.steps = steps;
        double w[4] = {0, 0, 0, 0};
        int slot;
        if (cell < s.inner_cell_count) {
            const float* m = s.inner_matrices + 12 * size_t(cell);
            // Rows are relative to the slot-d probe: the difference is exact near it (Sterbenz).
            const float* anchor = s.positions + 3 * size_t(cells.vertex(cell, d));
            const float q[3] = {local_f[0] - anchor[0], local_f[1] - anchor[1], local_f[2] - anchor[2]};
            float sum = 0.0f, bound[4] = {0, 0, 0, 0};
            for (uint32_t k = 0; k < d; ++k) {
                const float* r = m + 4 * k;
                const float b = r[0] * q[0] + r[1] * q[1] + r[2] * q[2] + r[3];
                w[k] = b;
                sum += b;
                bound[k] = std::fabs(r[0] * q[0]) + std::fabs(r[1] * q[1]) + std::fabs(r[2] * q[2]) + std::fabs(r[3]);
                bound[d] += bound[k];
            }
            w[d] = 1.0f - sum;
            // Inside up to the rounding of the float rows and of their evaluation (a few float steps
            // of the terms' sizes), and never more than kInsideTolerance: the fixed tolerance alone is
            // relative to the cell, and in a cell a million times wider than a neighbouring gap it
            // would swallow the probe across that gap.
            bool inside = true;
            for (uint32_t k = 0; k <= d; ++k)
                inside &= w[k] >= -std::fmin(kInsideToleranceD, kRowRounding * double(bound[k]));  // false for NaN
            const bool flat = !s.zero_volume.empty() && s.zero_volume[cell];
            if (inside && !flat) {
                set_weights(cells, cell, d + 1, w, loc);
                return loc;
            }
            if (!all_finite(w, int(d + 1))) break;
            // Beyond a hull facet (a store without outer cells): outside, by convexity of the hull.
            for (uint32_t k = 0; k <= d; ++k) {
                if (w[k] < -kInsideToleranceD && cells.neighbour(cell, k) == kNoCell) {
                    loc.status = TP_ERROR_OUTSIDE;
                    return loc;
                }
            }
            // A zero-volume cell ignores the direction across its plane, so it must hand p on.
            slot = exit_slot(cells, cell, w, d + 1, previous, !flat);
            if (slot < 0) {
                if (flat) break;
                set_weights(cells, cell, d + 1, w, loc);
                return loc;
            }
        } else {
            const uint32_t base = cells.neighbour(cell, d);
            const double guess_t = last_t >= 0 ? last_t : facet_distance(cells, cell, p);
            const OuterView o = view_outer_cell(cells, cell, p, base == previous, guess_t);
            if (!o.finite) break;
            beyond_hull = beyond_hull || o.f0 > 0;
            if (o.f0 <= 0 && base != previous) {
                previous = cell;
                cell = base;
                continue;
            }
            if (!o.judged) break;
            loc.kind = TP_CELL_OUTER;
            loc.t = float(o.t);
            if (o.holds) {
                last_t = o.t;
                if (minimum(o.weights, int(d)) >= -kInsideToleranceD) {
                    set_weights(cells, cell, d, o.weights, loc);
                    return loc;
                }
            }
            slot = exit_slot(cells, cell, o.weights, d, previous, o.holds);
            if (slot < 0) {
                if (!o.holds) break;  // p is not in this cell and there is nowhere to go
                set_weights(cells, cell, d, o.weights, loc);
                return loc;
            }
        }
        previous = cell;
        cell = cells.neighbour(cell, uint32_t(slot));
    }
    // Lost (a cycle, the step cap, or an undecidable cell): decide in double over all cells, or over
    // the outer cells alone (a few hundred, not hundreds of thousands) for a point beyond a hull
    // facet, hence outside the hull (which peeled slivers leave non-convex by at most their depth,
    // 1e-5 of their length), where far out neighbouring outer cells' sweeps can disagree.
    Location loc;
    if (!beyond_hull || !locate_exhaustive_from<Index>(s, local, s.inner_cell_count, loc))
        locate_exhaustive_from<Index>(s, local, 0, loc);
    loc.steps = steps;
    return loc;
}

// A query at a probe's own stored position answers that probe alone, whatever cell (inner, or outer
// at t = 0) holds it: a zero-volume cell (TetGen keeps some where rounding makes four probes
// coplanar) has no meaningful barycentrics there, an outer cell's root is only float-accurate, and
// exactness at probes must not depend on which cell the walk ends in.
template <class Index>
Location walk(const Store::Impl& s, const float world[3], int32_t hint) {
    double local[3];
    float local_f[3];
    for (int k = 0; k < 3; ++k) {
        local[k] = double(world[k]) - s.origin[k];
        local_f[k] = float(local[k]);
    }
    Location loc = walk_cells<Index>(s, local, local_f, hint);
    if (loc.status != TP_OK) return loc;
    // An outer cell's probes are its slots below d (a hull probe is often reached through one).
    const uint32_t probes = loc.kind == TP_CELL_INNER ? s.dimension + 1 : s.dimension;
    for (uint32_t k = 0; k < probes; ++k) {
        const uint32_t probe = loc.probes[k];
        const float* v = s.positions + 3 * size_t(probe);
        if (v[0] == local_f[0] && v[1] == local_f[1] && v[2] == local_f[2]) {
            for (uint32_t j = 0; j < 4; ++j) loc.weights[j] = j == k ? 1.0f : 0.0f;
            loc.t = 0.0f;  // a hull probe sits on its own ray at t = 0
            break;
        }
    }
    return loc;
}

template <class Index>
void mark_zero_volume_typed(Store::Impl& s) {
    const CellView<Index> cells(s);
    s.zero_volume.assign(s.inner_cell_count, 0);
    for (uint32_t cell = 0; cell < s.inner_cell_count; ++cell) {
        const Vec3 last = probe_position(s, cells.vertex(cell, 3));
        const Vec3 e0 = probe_position(s, cells.vertex(cell, 0)) - last;
        const Vec3 e1 = probe_position(s, cells.vertex(cell, 1)) - last;
        const Vec3 e2 = probe_position(s, cells.vertex(cell, 2)) - last;
        const double scale = std::sqrt(dot(e0, e0) * dot(e1, e1) * dot(e2, e2));
        s.zero_volume[cell] = std::fabs(dot(e0, cross(e1, e2))) <= 1e-12 * scale;
    }
}

}  // namespace

void mark_zero_volume_cells(Store::Impl& store) {
    if (store.dimension != 3) return;
    if (store.index32)
        mark_zero_volume_typed<uint32_t>(store);
    else
        mark_zero_volume_typed<uint16_t>(store);
}

LocateFunction locate_function(bool index32) { return index32 ? &walk<uint32_t> : &walk<uint16_t>; }

bool locate_exhaustive_outer(const Store::Impl& store, const double local_position[3], Location& out) {
    return store.index32 ? locate_exhaustive_from<uint32_t>(store, local_position, store.inner_cell_count, out)
                         : locate_exhaustive_from<uint16_t>(store, local_position, store.inner_cell_count, out);
}

Location locate_exhaustive(const Store::Impl& store, const double local_position[3]) {
    return store.index32 ? locate_exhaustive_typed<uint32_t>(store, local_position)
                         : locate_exhaustive_typed<uint16_t>(store, local_position);
}

}  // namespace tetprobe
