// Small stores built by hand for the run-time tests, independently of bake/: positions, normals,
// cells and neighbours (format 3 has no matrices: the run time decides from positions and normals).
#pragma once

#include "core/orientation.h"
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
    finish(d);
    return d;
}

// Probes on the x axis at the given coordinates (ascending); with extrapolation, an outer cell at each end.
inline StoreData line_store(const std::vector<double>& xs, bool extrapolate) {
    using tetprobe::kNone32;
    using tetprobe::kOuter32;
    StoreData d;
    d.dimension = 1;
    d.axis = 0;
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
    }
    d.normals.assign(3 * size_t(n), 0.0f);
    if (extrapolate) {
        d.normals[0] = -1.0f;
        d.normals[3 * (n - 1)] = 1.0f;
        d.cell_vertices.insert(d.cell_vertices.end(), {0, kOuter32, kNone32, kNone32});
        d.cell_neighbours.insert(d.cell_neighbours.end(), {kNone32, 0, kNone32, kNone32});
        d.cell_vertices.insert(d.cell_vertices.end(), {n - 1, kOuter32, kNone32, kNone32});
        d.cell_neighbours.insert(d.cell_neighbours.end(), {kNone32, segments - 1, kNone32, kNone32});
    } else {
        d.flags |= tetprobe::kFlagNoExtrapolation;
    }
    finish(d);
    return d;
}

// A tetrahedron; with extrapolation, its four faces carry outer cells along rays from the centroid.
// The inner cell lists the corners in their order, or with the last two swapped when that order is
// negatively oriented (exactly, on the floats).
inline StoreData tetrahedron_store(const std::array<Vec, 4>& corners, bool extrapolate) {
    using tetprobe::kNone32;
    using tetprobe::kOuter32;
    StoreData d;
    d.dimension = 3;
    set_position(d, {corners[0], corners[1], corners[2], corners[3]});
    d.inner_cell_count = 1;
    const float* p = d.positions.data();
    const bool swapped = tetprobe::orient3d(p, p + 3, p + 6, p + 9) < 0;
    const std::array<uint32_t, 4> slots = swapped ? std::array<uint32_t, 4>{0, 1, 3, 2} : std::array<uint32_t, 4>{0, 1, 2, 3};
    d.cell_vertices.assign(slots.begin(), slots.end());
    d.normals.assign(12, 0.0f);
    if (!extrapolate) {
        d.flags |= tetprobe::kFlagNoExtrapolation;
        d.cell_neighbours = {kNone32, kNone32, kNone32, kNone32};
        finish(d);
        return d;
    }
    // Outer cell 1 + k rests on the face opposite probe k, which is slot k's neighbour.
    for (uint32_t k = 0; k < 4; ++k) d.cell_neighbours.push_back(1 + slots[k]);
    const Vec centroid = (corners[0] + corners[1] + corners[2] + corners[3]) / 4.0;
    std::array<std::array<uint32_t, 3>, 4> faces;
    for (uint32_t k = 0; k < 4; ++k) {
        std::array<uint32_t, 3> f;
        int n = 0;
        for (uint32_t j = 0; j < 4; ++j)
            if (j != k) f[n++] = j;
        // Outward winding, as the builder's hull facets have: the opposite probe on the negative side.
        if (tetprobe::orient3d(p + 3 * f[0], p + 3 * f[1], p + 3 * f[2], p + 3 * k) > 0) std::swap(f[1], f[2]);
        faces[k] = f;
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
    }
    finish(d);
    return d;
}

}  // namespace hand_built
