// Small stores built by hand for the run-time tests, independently of bake/: the cell matrices and
// the outer cells' polynomials are derived here from the geometry (Eigen in double).
#pragma once

#include "core/store_data.h"
#include "core/store_format.h"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace hand_built {

using tetprobe::StoreData;
using Vec = Eigen::Vector3d;

inline Vec position(const StoreData& d, uint32_t probe) {
    return Vec(d.positions[3 * probe], d.positions[3 * probe + 1], d.positions[3 * probe + 2]);
}

inline Vec normal(const StoreData& d, uint32_t probe) {
    return Vec(d.normals[3 * probe], d.normals[3 * probe + 1], d.normals[3 * probe + 2]);
}

// Distinct SH per probe, exactly representable in half precision.
inline void fill_sh(StoreData& d) {
    const uint32_t n = d.probe_count();
    d.sh.resize(size_t(n) * 27);
    for (uint32_t p = 0; p < n; ++p)
        for (int c = 0; c < 27; ++c) d.sh[27 * p + c] = float(int((p * 13 + c * 7) % 29) - 14) * 0.25f;
}

// Identity probe_source / input_remap and the single-cell grid.
inline void finish(StoreData& d) {
    const uint32_t n = uint32_t(d.positions.size() / 3);
    d.input_probe_count = n;
    d.probe_source.resize(n);
    d.input_remap.resize(n);
    for (uint32_t i = 0; i < n; ++i) d.probe_source[i] = d.input_remap[i] = i;
    if (d.normals.size() != d.positions.size()) d.normals.assign(d.positions.size(), 0.0f);
    fill_sh(d);
    for (int k = 0; k < 3; ++k) {
        d.bounds_min[k] = d.bounds_max[k] = d.positions[k];
        for (uint32_t i = 0; i < n; ++i) {
            d.bounds_min[k] = std::fmin(d.bounds_min[k], d.positions[3 * i + k]);
            d.bounds_max[k] = std::fmax(d.bounds_max[k], d.positions[3 * i + k]);
        }
    }
    if (d.grid_cells.empty()) {
        d.grid[0] = d.grid[1] = d.grid[2] = 1;
        d.grid_cells = {0};
    }
}

// Rows of the inner barycentric matrix of a simplex of dimension dim (slots 0..dim), projecting
// onto the simplex's affine hull: b_k = M[k].xyz . (p - P_dim) + M[k].w for k < dim, with P_dim the
// slot-dim probe (store_format.h), where every such b_k is zero.
inline void append_inner_matrix(StoreData& d, const std::array<uint32_t, 4>& v, uint32_t dim) {
    std::array<float, 12> m{};
    if (dim == 1) {
        // b0 = (p - v1) . e / |e|^2 with e = v0 - v1 (closed form: cheap for very long lines).
        const Vec e = position(d, v[0]) - position(d, v[1]);
        const Vec row = e / e.squaredNorm();
        for (int j = 0; j < 3; ++j) m[j] = float(row[j]);
        m[3] = 0.0f;
    } else if (dim > 0) {
        const Vec last = position(d, v[dim]);
        Eigen::MatrixXd edges(3, dim);
        for (uint32_t k = 0; k < dim; ++k) edges.col(k) = position(d, v[k]) - last;
        // b = pinv(edges) (p - last): least squares, i.e. the projection onto the affine hull.
        const Eigen::MatrixXd pinv = (edges.transpose() * edges).inverse() * edges.transpose();
        for (uint32_t k = 0; k < dim; ++k) {
            for (int j = 0; j < 3; ++j) m[4 * k + j] = float(pinv(k, j));
            m[4 * k + 3] = 0.0f;
        }
    }
    d.inner_matrices.insert(d.inner_matrices.end(), m.begin(), m.end());
}

// f(t) for an outer cell at point p, from the geometry: positive beyond the hull facet at t = 0.
inline double outer_function(const StoreData& d, const std::array<uint32_t, 3>& v, uint32_t dim, const Vec& plane_normal,
                             double t, const Vec& p) {
    if (dim == 3) {
        const Vec a = position(d, v[0]) + t * normal(d, v[0]) - p;
        const Vec b = position(d, v[1]) + t * normal(d, v[1]) - p;
        const Vec c = position(d, v[2]) + t * normal(d, v[2]) - p;
        return -a.dot(b.cross(c));
    }
    const Vec a = position(d, v[0]) + t * normal(d, v[0]) - p;
    const Vec b = position(d, v[1]) + t * normal(d, v[1]) - p;
    return -plane_normal.dot(a.cross(b));
}

// The outer matrix of a cell: f is cubic in t and affine in p, so 4 values of t at 4 points recover
// its 16 coefficients (relative to the slot-0 probe). sign flips f so that it is positive outside;
// scale keeps the floats tame.
inline void append_outer_matrix(StoreData& d, const std::array<uint32_t, 3>& v, uint32_t dim, const Vec& plane_normal,
                                double sign) {
    std::array<float, 16> m{};
    if (dim == 1) {
        const Vec n = normal(d, v[0]);
        m[12] = float(n.x());
        m[13] = float(n.y());
        m[14] = float(n.z());
        m[15] = 0.0f;
    } else {
        const double ts[4] = {0.0, 1.0, -1.0, 2.0};
        Eigen::Matrix4d vandermonde;
        for (int i = 0; i < 4; ++i)
            for (int r = 0; r < 4; ++r) vandermonde(i, r) = std::pow(ts[i], 3 - r);
        const Vec anchor = position(d, v[0]);
        const Vec points[4] = {anchor, anchor + Vec::UnitX(), anchor + Vec::UnitY(), anchor + Vec::UnitZ()};
        Eigen::Matrix4d coefficient;  // (power row r, point j)
        for (int j = 0; j < 4; ++j) {
            Eigen::Vector4d values;
            for (int i = 0; i < 4; ++i) values(i) = sign * outer_function(d, v, dim, plane_normal, ts[i], points[j]);
            coefficient.col(j) = vandermonde.partialPivLu().solve(values);
        }
        double scale = 0;
        for (int r = 0; r < 4; ++r)
            for (int j = 0; j < 4; ++j) scale = std::fmax(scale, std::fabs(coefficient(r, j)));
        for (int r = 0; r < 4; ++r) {
            const double w = coefficient(r, 0);
            m[4 * r + 0] = float((coefficient(r, 1) - w) / scale);
            m[4 * r + 1] = float((coefficient(r, 2) - w) / scale);
            m[4 * r + 2] = float((coefficient(r, 3) - w) / scale);
            m[4 * r + 3] = float(w / scale);
        }
        if (dim == 2)
            for (int j = 0; j < 4; ++j) m[j] = 0.0f;  // exactly quadratic
    }
    d.outer_matrices.insert(d.outer_matrices.end(), m.begin(), m.end());
}

inline void set_position(StoreData& d, const std::vector<Vec>& points) {
    d.positions.clear();
    for (const Vec& p : points)
        for (int k = 0; k < 3; ++k) d.positions.push_back(float(p[k]));
}

// One probe: dimension 0, one inner cell {0}.
inline StoreData point_store(Vec at = Vec(1, 2, 3)) {
    StoreData d;
    d.dimension = 0;
    set_position(d, {at});
    d.inner_cell_count = 1;
    d.cell_vertices = {0, tetprobe::kNone32, tetprobe::kNone32, tetprobe::kNone32};
    d.cell_neighbours = {tetprobe::kNone32, tetprobe::kNone32, tetprobe::kNone32, tetprobe::kNone32};
    append_inner_matrix(d, {0, 0, 0, 0}, 0);
    finish(d);
    return d;
}

// Probes on the x axis at the given coordinates (ascending); with extrapolation, an outer cell at each end.
inline StoreData line_store(const std::vector<double>& xs, bool extrapolate) {
    using tetprobe::kNone32;
    using tetprobe::kOuter32;
    StoreData d;
    d.dimension = 1;
    std::vector<Vec> points;
    for (double x : xs) points.push_back(Vec(x, 0, 0));
    set_position(d, points);
    const uint32_t n = uint32_t(xs.size()), segments = n - 1;
    const uint32_t first_outer = segments, last_outer = segments + 1;
    d.inner_cell_count = segments;
    for (uint32_t s = 0; s < segments; ++s) {
        d.cell_vertices.insert(d.cell_vertices.end(), {s, s + 1, kNone32, kNone32});
        // Neighbour 0 is across vertex s+1 (towards +x), neighbour 1 across vertex s (towards -x).
        const uint32_t right = s + 1 < segments ? s + 1 : (extrapolate ? last_outer : kNone32);
        const uint32_t left = s > 0 ? s - 1 : (extrapolate ? first_outer : kNone32);
        d.cell_neighbours.insert(d.cell_neighbours.end(), {right, left, kNone32, kNone32});
        append_inner_matrix(d, {s, s + 1, 0, 0}, 1);
    }
    d.normals.assign(3 * size_t(n), 0.0f);
    if (extrapolate) {
        d.normals[0] = -1.0f;
        d.normals[3 * (n - 1)] = 1.0f;
        d.cell_vertices.insert(d.cell_vertices.end(), {0, kOuter32, kNone32, kNone32});
        d.cell_neighbours.insert(d.cell_neighbours.end(), {kNone32, 0, kNone32, kNone32});
        d.cell_vertices.insert(d.cell_vertices.end(), {n - 1, kOuter32, kNone32, kNone32});
        d.cell_neighbours.insert(d.cell_neighbours.end(), {kNone32, segments - 1, kNone32, kNone32});
        append_outer_matrix(d, {0, 0, 0}, 1, Vec::Zero(), 1.0);
        append_outer_matrix(d, {n - 1, 0, 0}, 1, Vec::Zero(), 1.0);
    } else {
        d.flags |= tetprobe::kFlagNoExtrapolation;
    }
    finish(d);
    return d;
}

// A tetrahedron; with extrapolation, its four faces carry outer cells along rays from the centroid.
inline StoreData tetrahedron_store(const std::array<Vec, 4>& corners, bool extrapolate) {
    using tetprobe::kNone32;
    using tetprobe::kOuter32;
    StoreData d;
    d.dimension = 3;
    set_position(d, {corners[0], corners[1], corners[2], corners[3]});
    d.inner_cell_count = 1;
    d.cell_vertices = {0, 1, 2, 3};
    append_inner_matrix(d, {0, 1, 2, 3}, 3);
    d.normals.assign(12, 0.0f);
    if (!extrapolate) {
        d.flags |= tetprobe::kFlagNoExtrapolation;
        d.cell_neighbours = {kNone32, kNone32, kNone32, kNone32};
        finish(d);
        return d;
    }
    // Outer cell 1 + k rests on the face opposite vertex k.
    d.cell_neighbours = {1, 2, 3, 4};
    const Vec centroid = (corners[0] + corners[1] + corners[2] + corners[3]) / 4.0;
    std::array<std::array<uint32_t, 3>, 4> faces;
    std::array<Vec, 4> face_normal;
    for (uint32_t k = 0; k < 4; ++k) {
        std::array<uint32_t, 3> f;
        int n = 0;
        for (uint32_t j = 0; j < 4; ++j)
            if (j != k) f[n++] = j;
        Vec nrm = (corners[f[1]] - corners[f[0]]).cross(corners[f[2]] - corners[f[0]]).normalized();
        if (nrm.dot(corners[f[0]] - centroid) < 0) {
            std::swap(f[1], f[2]);  // outward winding, as the builder's hull facets have
            nrm = -nrm;
        }
        faces[k] = f;
        face_normal[k] = nrm;
    }
    // Radial rays from the centroid never cross, so the outer cells tile everything outside.
    for (uint32_t v = 0; v < 4; ++v) {
        const Vec ray = (corners[v] - centroid).normalized();
        for (int j = 0; j < 3; ++j) d.normals[3 * v + j] = float(ray[j]);
    }
    for (uint32_t k = 0; k < 4; ++k) {
        const auto& f = faces[k];
        d.cell_vertices.insert(d.cell_vertices.end(), {f[0], f[1], f[2], kOuter32});
        // Neighbour j < 3: the face sharing the edge without f[j], i.e. the face opposite f[j].
        d.cell_neighbours.insert(d.cell_neighbours.end(), {1 + f[0], 1 + f[1], 1 + f[2], 0});
        const Vec beyond = (corners[f[0]] + corners[f[1]] + corners[f[2]]) / 3.0 + face_normal[k];
        const double sign = outer_function(d, f, 3, Vec::Zero(), 0.0, beyond) > 0 ? 1.0 : -1.0;
        append_outer_matrix(d, f, 3, Vec::Zero(), sign);
    }
    finish(d);
    return d;
}

}  // namespace hand_built
