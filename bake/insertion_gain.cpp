#include "bake/insertion_gain.h"

#include <algorithm>
#include <cmath>

namespace tetprobe {

namespace {

// Cells a cavity may grow to, and held-out candidates a gain reads (more are sampled evenly): both
// bound a round's cost on a coarse set over many candidates, where one insertion changes most cells.
constexpr size_t kMaxCavityCells = 4096;
constexpr size_t kMaxGainSamples = 512;

double volume(const double a[3], const double b[3], const double c[3], const double d[3]) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
}

void position_of(const Store& store, uint32_t stored, double out[3]) {
    const float* p = store.probe_position(stored);
    for (int a = 0; a < 3; ++a) out[a] = p[a];
}

// The noise two candidates' residuals share: the probes both interpolate, each weighed by both weights.
double shared_noise(const RoundState& s, uint32_t x, uint32_t i) {
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
        const float wx = s.weights[4 * size_t(x) + size_t(k)];
        if (wx == 0) continue;
        for (int l = 0; l < 4; ++l) {
            const float wi = s.weights[4 * size_t(i) + size_t(l)];
            if (wi != 0 && s.probes[4 * size_t(x) + size_t(k)] == s.probes[4 * size_t(i) + size_t(l)])
                sum += double(wx) * wi * s.probe_noise[s.probes[4 * size_t(i) + size_t(l)]];
        }
    }
    return sum;
}

// phi of candidate x when candidate i splits the cell both fall in: the least ratio of x's barycentric
// coordinate to i's over the probes i weighs (x's coordinate in the sub-cell that holds it).
double split_phi(const RoundState& s, uint32_t x, uint32_t i) {
    double phi = 1.0;
    for (int l = 0; l < 4; ++l) {
        const double mu = s.weights[4 * size_t(i) + size_t(l)];
        if (!(mu > 0)) continue;
        double lambda = 0;
        for (int k = 0; k < 4; ++k)
            if (s.probes[4 * size_t(x) + size_t(k)] == s.probes[4 * size_t(i) + size_t(l)])
                lambda = std::max(lambda, double(s.weights[4 * size_t(x) + size_t(k)]));
        phi = std::min(phi, lambda / mu);
    }
    return std::clamp(phi, 0.0, 1.0);
}

// A cavity cell as the walk below reads it: its vertices, neighbours, volume and the new probe's
// barycentric coordinates in it.
struct CavityCell {
    uint32_t id;
    uint32_t neighbours[4];
    double vertices[4][3];
    double volume;
    double p[4];
};

void barycentric(const CavityCell& c, const double x[3], double out[4]) {
    const double (*v)[3] = c.vertices;
    out[0] = volume(x, v[1], v[2], v[3]) / c.volume;
    out[1] = volume(v[0], x, v[2], v[3]) / c.volume;
    out[2] = volume(v[0], v[1], x, v[3]) / c.volume;
    out[3] = volume(v[0], v[1], v[2], x) / c.volume;
}

// phi of a point x of cavity cell `at`: the ray from p through x leaves the cavity at p + (1 + S)(x - p),
// walked cell by cell (barycentric coordinates are affine along the ray), and phi = S / (1 + S).
double cone_phi(const std::vector<CavityCell>& cavity, size_t at, const double x[3]) {
    double travelled = 0;  // S so far
    for (int steps = 0; steps < 256; ++steps) {
        const CavityCell& c = cavity[at];
        double lx[4];
        barycentric(c, x, lx);
        int exit = -1;
        double step = INFINITY;
        for (int k = 0; k < 4; ++k) {
            const double along = lx[k] - c.p[k];                          // d(lambda_k)/dS
            const double here = (1.0 + travelled) * lx[k] - travelled * c.p[k];  // lambda_k at the walk's point
            if (along < 0) {
                const double s = std::max(0.0, -here / along);
                if (s < step) step = s, exit = k;
            }
        }
        if (exit < 0) return 0.0;
        travelled += step;
        size_t next = cavity.size();
        for (size_t q = 0; q < cavity.size(); ++q)
            if (cavity[q].id == c.neighbours[exit]) next = q;
        if (next == cavity.size()) return travelled / (1.0 + travelled);
        at = next;
    }
    return 0.0;
}

bool in_sphere(const RoundState& s, uint32_t cell, const double p[3]) {
    const double* sphere = &s.spheres[4 * size_t(cell)];
    if (!(sphere[3] >= 0)) return false;
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (p[a] - sphere[a]) * (p[a] - sphere[a]);
    return d2 < sphere[3] * (1.0 - 1e-9);  // cospherical points (a lattice has many) stay out
}

}  // namespace

void prepare_round(RoundState& s) {
    const StoreHeader& h = s.store->header();
    const size_t count = s.cell.size();
    s.cell_start.assign(size_t(h.cell_count) + 1, 0);
    for (size_t i = 0; i < count; ++i)
        if (s.active[i]) ++s.cell_start[size_t(s.cell[i]) + 1];
    for (size_t c = 0; c < h.cell_count; ++c) s.cell_start[c + 1] += s.cell_start[c];
    s.cell_members.assign(s.cell_start.back(), 0);
    std::vector<uint32_t> fill(s.cell_start.begin(), s.cell_start.end() - 1);
    for (size_t i = 0; i < count; ++i)
        if (s.active[i]) s.cell_members[fill[size_t(s.cell[i])]++] = uint32_t(i);

    s.spheres.assign(4 * size_t(h.inner_cell_count), -1.0);
    if (h.dimension != 3) return;
    for (uint32_t c = 0; c < h.inner_cell_count; ++c) {
        uint32_t v[4], n[4];
        s.store->cell(c, v, n);
        double p[4][3];
        for (int k = 0; k < 4; ++k) position_of(*s.store, v[k], p[k]);
        // The centre x - p0 solves (pk - p0) . x = |pk - p0|^2 / 2 for k = 1..3 (Cramer's rule).
        double m[3][3], r[3];
        for (int k = 0; k < 3; ++k) {
            double q = 0;
            for (int a = 0; a < 3; ++a) m[k][a] = p[k + 1][a] - p[0][a], q += m[k][a] * m[k][a];
            r[k] = 0.5 * q;
        }
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        if (!(std::fabs(det) > 0)) continue;
        double x[3];
        for (int a = 0; a < 3; ++a) {
            double t[3][3];
            for (int row = 0; row < 3; ++row)
                for (int col = 0; col < 3; ++col) t[row][col] = col == a ? r[row] : m[row][col];
            x[a] = (t[0][0] * (t[1][1] * t[2][2] - t[1][2] * t[2][1]) - t[0][1] * (t[1][0] * t[2][2] - t[1][2] * t[2][0]) +
                    t[0][2] * (t[1][0] * t[2][1] - t[1][1] * t[2][0])) / det;
        }
        double* sphere = &s.spheres[4 * size_t(c)];
        for (int a = 0; a < 3; ++a) sphere[a] = p[0][a] + x[a];
        sphere[3] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    }
}

InsertionGain insertion_gain(const RoundState& s, uint32_t i) {
    InsertionGain g;
    const StoreHeader& h = s.store->header();
    const uint32_t home = uint32_t(s.cell[i]);
    const bool cone = h.dimension == 3 && home < h.inner_cell_count;
    double p[3];
    for (int a = 0; a < 3; ++a) p[a] = s.local[3 * size_t(i) + size_t(a)];

    // The cavity: cells whose circumsphere holds p, connected to p's own cell.
    g.cavity.push_back(home);
    std::vector<CavityCell> cells;
    if (cone) {
        for (size_t q = 0; q < g.cavity.size() && g.cavity.size() < kMaxCavityCells; ++q) {
            uint32_t v[4], n[4];
            s.store->cell(g.cavity[q], v, n);
            for (int k = 0; k < 4; ++k)
                if (n[k] < h.inner_cell_count && std::find(g.cavity.begin(), g.cavity.end(), n[k]) == g.cavity.end() &&
                    in_sphere(s, n[k], p))
                    g.cavity.push_back(n[k]);
        }
        for (uint32_t q : g.cavity) {
            CavityCell c;
            uint32_t v[4];
            c.id = q;
            s.store->cell(q, v, c.neighbours);
            for (int k = 0; k < 4; ++k) position_of(*s.store, v[k], c.vertices[k]);
            c.volume = volume(c.vertices[0], c.vertices[1], c.vertices[2], c.vertices[3]);
            if (!(std::fabs(c.volume) > 0)) c.volume = 1e-300;
            barycentric(c, p, c.p);
            cells.push_back(c);
        }
    }

    // Beyond the hull: the points between the outer cell's facet and the new probe fall in the new cell
    // from the facet to it, where its coordinate is their height over its own (see above).
    double facet[3][3], beyond = 0;
    if (h.dimension == 3 && home >= h.inner_cell_count) {
        uint32_t v[4], n[4];
        s.store->cell(home, v, n);
        if (v[3] == kOuter32 && v[0] < h.probe_count && v[1] < h.probe_count && v[2] < h.probe_count) {
            for (int k = 0; k < 3; ++k) position_of(*s.store, v[k], facet[k]);
            beyond = volume(facet[0], facet[1], facet[2], p);  // same sign as every point of the cell
            if (!std::isfinite(beyond)) beyond = 0;
        }
    }

    size_t members = 0;
    for (uint32_t q : g.cavity) members += s.cell_start[q + 1] - s.cell_start[q];
    const size_t stride = std::max<size_t>(1, (members + kMaxGainSamples - 1) / kMaxGainSamples);
    const double weight = double(stride);
    const double* ri = &s.residual[kSignalSize * size_t(i)];
    double rr = 0;
    for (int k = 0; k < kSignalSize; ++k) rr += ri[k] * ri[k];
    const double si = s.noise[i], ti = std::max(0.0, rr - si);
    double phi_squares = 0;
    auto add = [&](uint32_t x, double phi, double w) {
        if (!(phi > 0)) return;
        const double* rx = &s.residual[kSignalSize * size_t(x)];
        double dot = 0, xx = 0;
        for (int k = 0; k < kSignalSize; ++k) dot += rx[k] * ri[k], xx += rx[k] * rx[k];
        const double shared = x == i ? si : shared_noise(s, x, i);
        g.gain += w * (2.0 * phi * (dot - shared) - phi * phi * (rr - si));
        const double sx = s.noise[x], tx = std::max(0.0, xx - sx);
        g.deviation += w * 4.0 * phi * phi * (tx * si + ti * sx + si * sx) / kSignalSize;
        g.coverage += w * phi;
        phi_squares += w * phi * phi;
    };
    add(i, 1.0, 1.0);
    size_t seen = 0;
    for (size_t at = 0; at < g.cavity.size(); ++at)
        for (uint32_t m = s.cell_start[g.cavity[at]]; m < s.cell_start[g.cavity[at] + 1]; ++m, ++seen) {
            const uint32_t x = s.cell_members[m];
            if (x == i || seen % stride != 0) continue;
            double phi;
            if (cone) {
                double xl[3];
                for (int a = 0; a < 3; ++a) xl[a] = s.local[3 * size_t(x) + size_t(a)];
                phi = cone_phi(cells, at, xl);
            } else {
                phi = split_phi(s, x, i);
                if (beyond != 0) {
                    double xl[3];
                    for (int a = 0; a < 3; ++a) xl[a] = s.local[3 * size_t(x) + size_t(a)];
                    phi = std::min(phi, std::clamp(volume(facet[0], facet[1], facet[2], xl) / beyond, 0.0, 1.0));
                }
            }
            add(x, phi, weight);
        }
    // The |r_i|^2 term is shared by every point: its noise adds coherently.
    g.deviation += phi_squares * phi_squares * (2.0 * si * si + 4.0 * ti * si) / kSignalSize;
    g.deviation = std::sqrt(std::max(0.0, g.deviation));
    return g;
}

}  // namespace tetprobe
