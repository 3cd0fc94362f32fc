// A slow, independent reference for the builder's output: given a StoreData and a local point, it
// finds the probes and weights by brute force over every cell, in double, from the probe positions
// and normals alone. It judges the point the run time judges: the query's float local position
// (local_point below, float(double(world) - origin)), and for a flat set (d = 2) the two stored
// coordinates other than StoreData::axis (a line, d = 1: coordinate axis alone). Inner cells:
// barycentric coordinates from signed volumes (3D) or signed areas in the plane's coordinates (2D),
// the position along the axis (1D). Outer cells: the moved hull facet P_k + t N_k is found by sampling
// its plane (line) equation f(t) in t and bisecting every sign change, then the root that puts p
// inside it is kept.
#pragma once

#include "core/store_data.h"
#include "core/store_format.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

namespace reference {

using tetprobe::StoreData;
using Vec = Eigen::Vector3d;

inline Vec position(const StoreData& d, uint32_t probe) {
    return Vec(d.positions[3 * size_t(probe)], d.positions[3 * size_t(probe) + 1], d.positions[3 * size_t(probe) + 2]);
}
inline Vec normal(const StoreData& d, uint32_t probe) {
    return Vec(d.normals[3 * size_t(probe)], d.normals[3 * size_t(probe) + 1], d.normals[3 * size_t(probe) + 2]);
}
inline uint32_t vertex(const StoreData& d, uint32_t cell, uint32_t slot) { return d.cell_vertices[4 * size_t(cell) + slot]; }

// The float local position of a float world position, as the run time forms it, in double.
inline Vec local_point(const StoreData& d, const float world[3]) {
    Vec p;
    for (int k = 0; k < 3; ++k) {
        // volatile: keep the rounding to float (GCC's SLP vectorizer was seen to fold it away).
        volatile float local = float(double(world[k]) - d.origin[k]);
        p[k] = double(local);
    }
    return p;
}

struct Answer {
    bool outside = false;       // beyond the hull of a store without outer cells
    bool outer = false;         // decided by an outer cell
    uint32_t cell = 0;
    double score = -1e300;      // smallest barycentric coordinate in the chosen cell
    double t = 0;
    std::map<uint32_t, double> weights;  // stored probe -> weight (zero weights dropped)

    double blend(const std::vector<double>& values) const {
        double sum = 0;
        for (const auto& w : weights) sum += w.second * values[w.first];
        return sum;
    }
    Vec blend_positions(const StoreData& d) const {
        Vec sum = Vec::Zero();
        for (const auto& w : weights) sum += w.second * position(d, w.first);
        return sum;
    }
};

// The frame a store decides in: all three coordinates (d = 3, 0), the two coordinates other than
// axis (d = 2, as (u, v, 0)), or coordinate axis alone (d = 1, as (x, 0, 0)).
struct Frame {
    uint32_t dimension = 3;
    uint32_t axis = 0;
    Vec project(const Vec& p) const {
        if (dimension == 2) return Vec(p[axis == 0 ? 1 : 0], p[axis == 2 ? 1 : 2], 0.0);
        if (dimension == 1) return Vec(p[axis], 0.0, 0.0);
        return p;
    }
    // The unit direction a flat set ignores (the dropped axis); zero otherwise.
    Vec ignored() const { return dimension == 2 ? Vec(Vec::Unit(axis)) : Vec(Vec::Zero()); }
};

inline Frame frame_of(const StoreData& d) {
    Frame f;
    f.dimension = d.dimension;
    f.axis = d.axis;
    return f;
}

// Barycentric coordinates of p in inner cell c (slots 0..d), in the store's frame.
inline void inner_barycentrics(const StoreData& d, const Frame& f, uint32_t c, const Vec& point, double w[4]) {
    const uint32_t dim = d.dimension;
    Vec v[4];
    for (uint32_t k = 0; k <= dim; ++k) v[k] = f.project(position(d, vertex(d, c, k)));
    const Vec p = f.project(point);
    if (dim == 0) {
        w[0] = 1;
    } else if (dim == 1) {
        w[0] = (p.x() - v[1].x()) / (v[0].x() - v[1].x());
        w[1] = 1 - w[0];
    } else if (dim == 2) {
        // Linear in p relative to a vertex (no cancellation of large products for far points).
        const Vec e0 = v[0] - v[2], e1 = v[1] - v[2], q = p - v[2];
        const double area = e0.x() * e1.y() - e0.y() * e1.x();
        w[0] = (q.x() * e1.y() - q.y() * e1.x()) / area;
        w[1] = (e0.x() * q.y() - e0.y() * q.x()) / area;
        w[2] = 1 - w[0] - w[1];
    } else {
        const Vec e0 = v[0] - v[3], e1 = v[1] - v[3], e2 = v[2] - v[3], q = p - v[3];
        const double volume = e0.cross(e1).dot(e2);
        w[0] = q.cross(e1).dot(e2) / volume;
        w[1] = e0.cross(q).dot(e2) / volume;
        w[2] = e0.cross(e1).dot(q) / volume;
        w[3] = 1 - w[0] - w[1] - w[2];
    }
}

// f(t) of an outer cell (P, N and p already in the store's frame): the orientation of the moved
// facet with p, positive at t = 0 exactly when p is beyond the facet.
// (Plain arithmetic: the root search calls it thousands of times, and unoptimised Eigen in the
// sanitizer build would dominate the test time.)
inline double moved_facet_equation(const Vec* P, const Vec* N, uint32_t dim, const Vec& p, double t) {
    double a[3], u[3], v[3];
    for (int i = 0; i < 3; ++i) {
        a[i] = P[0][i] + t * N[0][i];
        u[i] = P[1][i] + t * N[1][i] - a[i];
        v[i] = dim == 3 ? P[2][i] + t * N[2][i] - a[i] : p[i] - a[i];
    }
    if (dim == 2) return u[0] * v[1] - u[1] * v[0];
    const double w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    return (u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1] + (u[0] * v[1] - u[1] * v[0]) * w[2];
}

// Weights of p in the moved facet at t (triangle projected on its plane, segment on its line).
inline void moved_facet_weights(const Vec* P, const Vec* N, uint32_t dim, const Vec& p, double t, double w[3]) {
    if (dim == 3) {
        const Vec a = P[0] + t * N[0], b = P[1] + t * N[1], c = P[2] + t * N[2];
        const Vec e0 = a - c, e1 = b - c, q = p - c;
        const Vec n = e0.cross(e1);
        const double n2 = n.squaredNorm();
        w[0] = q.cross(e1).dot(n) / n2;
        w[1] = e0.cross(q).dot(n) / n2;
        w[2] = 1 - w[0] - w[1];
    } else {
        const Vec a = P[0] + t * N[0], b = P[1] + t * N[1];
        w[1] = (p - a).dot(b - a) / (b - a).squaredNorm();
        w[0] = 1 - w[1];
    }
}

// Roots of f in [0, t_max] by dense sampling (denser near 0) and bisection of each sign change.
template <class F>
std::vector<double> sampled_roots(const F& f, double t_max, int samples = 120) {
    std::vector<double> roots;
    double t0 = 0, f0 = f(0.0);
    if (f0 == 0) roots.push_back(0);
    for (int i = 1; i <= samples; ++i) {
        const double s = double(i) / samples;
        const double t1 = t_max * s * s * s;
        const double f1 = f(t1);
        if (f1 == 0) {
            roots.push_back(t1);
        } else if ((f0 < 0 && f1 > 0) || (f0 > 0 && f1 < 0)) {
            double lo = t0, hi = t1, flo = f0;
            for (int k = 0; k < 200 && hi - lo > 1e-15 * std::max(1.0, hi); ++k) {
                const double mid = 0.5 * (lo + hi), fm = f(mid);
                if ((fm < 0) == (flo < 0)) {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            roots.push_back(0.5 * (lo + hi));
        }
        t0 = t1;
        f0 = f1;
    }
    return roots;
}

inline double set_diagonal(const StoreData& d) {
    double s = 0;
    for (int a = 0; a < 3; ++a) s += double(d.bounds_max[a] - d.bounds_min[a]) * double(d.bounds_max[a] - d.bounds_min[a]);
    return std::sqrt(s);
}

// The weights cell c gives p, and its score (smallest weight; -inf when c cannot hold p: an outer
// cell with p not beyond its facet, or a degenerate cell).
inline Answer cell_answer(const StoreData& d, const Frame& f, uint32_t c, const Vec& point) {
    const uint32_t dim = d.dimension;
    Answer a;
    a.cell = c;
    a.score = -std::numeric_limits<double>::infinity();
    if (c < d.inner_cell_count) {
        double w[4] = {0, 0, 0, 0};
        inner_barycentrics(d, f, c, point, w);
        double score = w[0];
        for (uint32_t k = 0; k <= dim; ++k) {
            if (!std::isfinite(w[k])) return a;
            score = std::min(score, w[k]);
        }
        a.score = score;
        for (uint32_t k = 0; k <= dim; ++k)
            if (w[k] != 0) a.weights[vertex(d, c, k)] += w[k];
        return a;
    }
    a.outer = true;
    const Vec p = f.project(point);
    Vec P[3], N[3];
    for (uint32_t k = 0; k < dim; ++k) {
        P[k] = f.project(position(d, vertex(d, c, k)));
        N[k] = f.project(normal(d, vertex(d, c, k)));
    }
    if (dim == 1) {
        if (N[0].x() != 0 && (p.x() - P[0].x()) * N[0].x() > 0) {
            a.score = 1;
            a.t = (p.x() - P[0].x()) / N[0].x();
            a.weights = {{vertex(d, c, 0), 1.0}};
        }
        return a;
    }
    if (!(moved_facet_equation(P, N, dim, p, 0) > 0)) return a;
    const double reach = 4 * ((p - P[0]).norm() + set_diagonal(d)) + 1;
    const auto roots = sampled_roots([&](double t) { return moved_facet_equation(P, N, dim, p, t); }, reach);
    for (double t : roots) {
        double w[3];
        moved_facet_weights(P, N, dim, p, t, w);
        double score = w[0];
        for (uint32_t k = 1; k < dim; ++k) score = std::min(score, w[k]);
        if (!std::isfinite(score) || score <= a.score) continue;
        a.score = score;
        a.t = t;
        a.weights.clear();
        for (uint32_t k = 0; k < dim; ++k)
            if (w[k] != 0) a.weights[vertex(d, c, k)] += w[k];
    }
    return a;
}

// Probes and weights of local point p by brute force over every cell: the inner cell with the largest
// smallest barycentric coordinate if p is inside the hull, else the best outer cell.
inline Answer locate(const StoreData& d, const Vec& p, double inside_tolerance = 1e-9) {
    const Frame f = frame_of(d);
    Answer best;
    for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
        Answer a = cell_answer(d, f, c, p);
        if (a.score > best.score) best = std::move(a);
    }
    if (best.score >= -inside_tolerance || d.dimension == 0) return best;
    if (d.cell_count() == d.inner_cell_count) {
        best.outside = true;
        return best;
    }
    Answer outer;
    for (uint32_t c = d.inner_cell_count; c < d.cell_count(); ++c) {
        Answer a = cell_answer(d, f, c, p);
        if (a.score > outer.score) outer = std::move(a);
    }
    return outer.score > best.score ? outer : best;
}

}  // namespace reference
