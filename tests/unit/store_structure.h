// Structural checks of a built StoreData against core/store_format.h, shared by the builder's tests:
// slot layout, neighbour symmetry across shared facets, every probe used, outer cells tiling the
// hull with outward winding and untangled normals, inner and outer matrices agreeing with the
// reference computed from positions.
#pragma once

#include "reference_interpolator.h"

#include "core/store_data.h"
#include "core/store_format.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace structure {

using reference::Vec;
using tetprobe::kNone32;
using tetprobe::kOuter32;
using tetprobe::StoreData;

// Counts failed conditions over a loop and keeps the first one's text, so that checking every cell
// costs one Catch assertion (whose cost dominates under the sanitizers), not millions.
struct Failures {
    std::string first;
    size_t count = 0;
    void report(const char* what) const {
        INFO(what << ": " << count << " failures, the first: " << first);
        REQUIRE(count == 0);
    }
};

#define STRUCTURE_CHECK(failures, condition, context)                        \
    do {                                                                     \
        if (!(condition) && (failures).count++ == 0) {                       \
            std::ostringstream what_;                                        \
            what_ << #condition << " (" << context << ")";                   \
            (failures).first = what_.str();                                  \
        }                                                                    \
    } while (0)

inline std::multiset<uint32_t> facet_without(const StoreData& d, uint32_t cell, uint32_t slot) {
    std::multiset<uint32_t> facet;
    for (uint32_t k = 0; k <= d.dimension; ++k)
        if (k != slot) facet.insert(d.cell_vertices[4 * size_t(cell) + k]);
    return facet;
}

inline void check_layout_and_links(const StoreData& d) {
    const uint32_t dim = d.dimension, cells = d.cell_count(), inner = d.inner_cell_count, probes = d.probe_count();
    const bool extrapolates = !(d.flags & tetprobe::kFlagNoExtrapolation);
    REQUIRE(dim <= 3);
    REQUIRE(d.positions.size() == 3 * size_t(probes));
    REQUIRE(d.normals.size() == 3 * size_t(probes));
    REQUIRE(d.sh.size() == 27 * size_t(probes));
    REQUIRE(d.input_remap.size() == d.input_probe_count);
    REQUIRE(d.cell_neighbours.size() == d.cell_vertices.size());
    REQUIRE(d.inner_matrices.size() == 12 * size_t(inner));
    REQUIRE(d.outer_matrices.size() == 16 * size_t(cells - inner));
    REQUIRE(d.grid_cells.size() == size_t(d.grid[0]) * d.grid[1] * d.grid[2]);
    REQUIRE(d.grid_cells.size() <= 32768);
    if (dim == 0) REQUIRE(cells == 1);
    if (!extrapolates) REQUIRE(cells == inner);

    Failures f;
    for (uint32_t g : d.grid_cells) STRUCTURE_CHECK(f, g < inner, "grid entry " << g);
    for (uint32_t i = 0; i < d.input_probe_count; ++i) STRUCTURE_CHECK(f, d.input_remap[i] < probes, "input " << i);
    for (uint32_t j = 0; j < probes; ++j) {
        STRUCTURE_CHECK(f, d.probe_source[j] < d.input_probe_count, "probe " << j);
        // A survivor maps to itself.
        STRUCTURE_CHECK(f, d.probe_source[j] < d.input_probe_count && d.input_remap[d.probe_source[j]] == j,
                        "probe " << j);
    }
    f.report("probe maps");

    std::vector<char> used(probes, 0);
    for (uint32_t c = 0; c < cells; ++c) {
        const bool outer = c >= inner;
        std::set<uint32_t> distinct;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t v = d.cell_vertices[4 * size_t(c) + k];
            if (k > dim) {
                STRUCTURE_CHECK(f, v == kNone32, "cell " << c << " slot " << k);
                STRUCTURE_CHECK(f, d.cell_neighbours[4 * size_t(c) + k] == kNone32, "cell " << c << " slot " << k);
            } else if (outer && k == dim) {
                STRUCTURE_CHECK(f, v == kOuter32, "cell " << c);
            } else {
                STRUCTURE_CHECK(f, v < probes, "cell " << c << " slot " << k);
                if (v >= probes) continue;
                distinct.insert(v);
                if (!outer) used[v] = 1;
            }
        }
        STRUCTURE_CHECK(f, distinct.size() == (outer ? dim : dim + 1), "cell " << c);
    }
    for (uint32_t j = 0; j < probes; ++j) STRUCTURE_CHECK(f, used[j], "probe " << j << " in no inner cell");
    f.report("cell slots");

    // Neighbour k shares every vertex but slot k's (kOuter32 counting as a vertex), and links back.
    size_t hull_facets = 0;
    for (uint32_t c = 0; c < cells; ++c) {
        for (uint32_t k = 0; k <= dim; ++k) {
            const uint32_t n = d.cell_neighbours[4 * size_t(c) + k];
            if (n == kNone32) {
                // Only hull facets of a store without outer cells, and the far side of a line's end.
                STRUCTURE_CHECK(f, !extrapolates || dim == 0 || (c >= inner && dim == 1), "cell " << c << " slot " << k);
                if (c < inner) ++hull_facets;
                continue;
            }
            STRUCTURE_CHECK(f, n < cells && n != c, "cell " << c << " slot " << k << " neighbour " << n);
            if (n >= cells) continue;
            uint32_t back = 4;
            for (uint32_t j = 0; j <= dim; ++j)
                if (d.cell_neighbours[4 * size_t(n) + j] == c) back = j;
            STRUCTURE_CHECK(f, back <= dim, "cell " << c << " slot " << k << " neighbour " << n << " links back");
            STRUCTURE_CHECK(f, back <= dim && facet_without(d, c, k) == facet_without(d, n, back),
                            "cell " << c << " slot " << k << " neighbour " << n << " shares the facet");
            if (c < inner && n >= inner) {
                ++hull_facets;
                STRUCTURE_CHECK(f, back == dim, "outer cell " << n << " rests on " << c);
            }
            if (c >= inner) STRUCTURE_CHECK(f, (k == dim) == (n < inner), "outer cell " << c << " slot " << k);
        }
    }
    if (extrapolates && dim > 0) STRUCTURE_CHECK(f, hull_facets == cells - inner, hull_facets << " hull facets");
    f.report("neighbours");
}

// Outer cells wound outward, hull normals unit (zero off the hull), and each facet moved out along
// its normals turning like the facet itself up to 1e5 diagonals out (otherwise the cell folds over
// its neighbours there), sampled at a few distances.
inline void check_outer_geometry(const StoreData& d) {
    const uint32_t dim = d.dimension, inner = d.inner_cell_count;
    std::vector<char> on_hull(d.probe_count(), 0);
    const reference::Frame frame = reference::frame_of(d);
    Vec lo = Vec::Constant(HUGE_VAL), hi = -lo;
    for (uint32_t j = 0; j < d.probe_count(); ++j) {
        lo = lo.cwiseMin(reference::position(d, j));
        hi = hi.cwiseMax(reference::position(d, j));
    }
    const double diagonal = (hi - lo).norm();
    Failures f;
    for (uint32_t c = inner; c < d.cell_count(); ++c) {
        const uint32_t base = d.cell_neighbours[4 * size_t(c) + dim];
        std::set<uint32_t> facet;
        for (uint32_t k = 0; k < dim; ++k) {
            facet.insert(d.cell_vertices[4 * size_t(c) + k]);
            on_hull[d.cell_vertices[4 * size_t(c) + k]] = 1;
        }
        // The base cell's probe that is not on the facet lies on the inner side.
        uint32_t apex = kNone32;
        for (uint32_t k = 0; k <= dim; ++k) {
            const uint32_t v = d.cell_vertices[4 * size_t(base) + k];
            if (!facet.count(v)) apex = v;
        }
        STRUCTURE_CHECK(f, apex != kNone32, "outer cell " << c);
        if (apex == kNone32) continue;
        const Vec p0 = reference::position(d, d.cell_vertices[4 * size_t(c)]);
        const Vec inside = reference::position(d, apex);
        double side;
        if (dim == 3) {
            const Vec p1 = reference::position(d, d.cell_vertices[4 * size_t(c) + 1]);
            const Vec p2 = reference::position(d, d.cell_vertices[4 * size_t(c) + 2]);
            side = (p1 - p0).cross(p2 - p0).dot(inside - p0);
            Vec n[3];
            for (uint32_t k = 0; k < 3; ++k) n[k] = reference::normal(d, d.cell_vertices[4 * size_t(c) + k]);
            // Moved out along its normals, the facet keeps its orientation up to 1e5 diagonals.
            const Vec facet = (p1 - p0).cross(p2 - p0);
            for (double t : {0.0, 1e-2, 1.0, 1e2, 1e3, 1e4, 3e4, 1e5}) {
                const Vec q0 = p0 + t * diagonal * n[0], q1 = p1 + t * diagonal * n[1], q2 = p2 + t * diagonal * n[2];
                STRUCTURE_CHECK(f, (q1 - q0).cross(q2 - q0).dot(facet) > 0,
                                "outer cell " << c << " turns over at " << t << " diagonals out");
            }
        } else if (dim == 2) {
            const Vec p1 = reference::position(d, d.cell_vertices[4 * size_t(c) + 1]);
            side = (p1 - p0).cross(inside - p0).dot(frame.n);
        } else {
            side = (inside - p0).dot(reference::normal(d, d.cell_vertices[4 * size_t(c)]));
        }
        STRUCTURE_CHECK(f, side < 0, "outer cell " << c << " winding");
    }
    for (uint32_t j = 0; j < d.probe_count(); ++j) {
        const double length = reference::normal(d, j).norm();
        if (on_hull[j])
            STRUCTURE_CHECK(f, std::fabs(length - 1) < 1e-6, "probe " << j << " normal length " << length);
        else if (inner < d.cell_count())
            STRUCTURE_CHECK(f, length == 0, "probe " << j << " off the hull, normal length " << length);
    }
    f.report("outer geometry");
}

// Inner matrices against the reference barycentrics at random points in and around sampled cells.
// Float rows carry a relative error of ~6e-8 each, so the bound scales with the sum of |terms|.
inline void check_inner_matrices(const StoreData& d, uint32_t seed, uint32_t max_cells = 400) {
    const uint32_t dim = d.dimension, inner = d.inner_cell_count;
    if (dim == 0) return;
    const reference::Frame frame = reference::frame_of(d);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-0.2, 1.2);
    Failures f;
    const uint32_t stride = std::max(1u, inner / max_cells);
    uint32_t flat_cells = 0, checked_cells = 0;
    for (uint32_t c = 0; c < inner; c += stride) {
        const float* m = &d.inner_matrices[12 * size_t(c)];
        const Vec anchor = reference::position(d, d.cell_vertices[4 * size_t(c) + dim]);
        ++checked_cells;
        if (dim == 3) {
            // A cell of zero volume (TetGen keeps some when rounding makes four probes coplanar) has
            // no barycentrics to compare with: the builder gives it pseudo-inverse rows, by the same
            // test as here. Such cells hold no point; they must stay rare.
            const Vec last = reference::position(d, d.cell_vertices[4 * size_t(c) + 3]);
            Eigen::Matrix3d edges;
            for (int k = 0; k < 3; ++k) edges.col(k) = reference::position(d, d.cell_vertices[4 * size_t(c) + k]) - last;
            const double scale = edges.col(0).norm() * edges.col(1).norm() * edges.col(2).norm();
            if (std::fabs(edges.determinant()) <= 1e-12 * scale) {
                ++flat_cells;
                continue;
            }
        }
        for (int trial = 0; trial < 4; ++trial) {
            // A flat set's cells extrude along its plane normal; the test points stay on the
            // triangle's plane, where the reference needs no normal beyond its sign.
            double lambda[4], sum = 0;
            for (uint32_t k = 0; k <= dim; ++k) sum += (lambda[k] = u(rng));
            Vec p = Vec::Zero();
            for (uint32_t k = 0; k <= dim; ++k) p += lambda[k] / sum * reference::position(d, d.cell_vertices[4 * size_t(c) + k]);
            double expected[4];
            reference::inner_barycentrics(d, frame, c, p, expected);
            double stored_sum = 0, bound = 0;
            for (uint32_t k = 0; k <= dim; ++k) {
                double b;
                if (k < dim) {
                    const Vec q = p - anchor;
                    b = m[4 * k] * q.x() + m[4 * k + 1] * q.y() + m[4 * k + 2] * q.z() + m[4 * k + 3];
                    stored_sum += b;
                    bound += std::fabs(m[4 * k] * q.x()) + std::fabs(m[4 * k + 1] * q.y()) +
                             std::fabs(m[4 * k + 2] * q.z()) + std::fabs(m[4 * k + 3]);
                } else {
                    b = 1 - stored_sum;
                }
                STRUCTURE_CHECK(f, std::fabs(b - expected[k]) <= 1e-5 * (1 + bound) + 1e-8,
                                "cell " << c << " slot " << k << " stored " << b << " reference " << expected[k]);
            }
        }
    }
    STRUCTURE_CHECK(f, flat_cells * 50 <= checked_cells, flat_cells << " of " << checked_cells << " cells have zero volume");
    // Extrusion: every flat cell ignores one and the same direction (rows 0 and 1 are normal to it),
    // close to the triangles' mean normal.
    if (dim == 2) {
        Vec first = Vec::Zero();
        for (uint32_t c = 0; c < inner; ++c) {
            const float* m = &d.inner_matrices[12 * size_t(c)];
            const Vec ignored = Vec(m[0], m[1], m[2]).cross(Vec(m[4], m[5], m[6])).normalized();
            if (c == 0) first = ignored;
            STRUCTURE_CHECK(f, std::fabs(std::fabs(ignored.dot(first)) - 1) < 1e-6, "cell " << c << " extrusion");
            STRUCTURE_CHECK(f, ignored.cross(reference::plane_normal(d)).norm() < 1e-3, "cell " << c << " extrusion");
        }
    }
    f.report("inner matrices");
}

// Outer rows against the reference plane (line) equation of the moved facet: equal up to one
// positive factor.
inline void check_outer_matrices(const StoreData& d, uint32_t seed) {
    const uint32_t dim = d.dimension, inner = d.inner_cell_count;
    if (dim == 0) return;
    const reference::Frame frame = reference::frame_of(d);
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    const double diagonal = reference::set_diagonal(d);
    Failures f;
    for (uint32_t c = inner; c < d.cell_count(); ++c) {
        const float* m = &d.outer_matrices[16 * size_t(c - inner)];
        Vec P[3], N[3];
        for (uint32_t k = 0; k < dim; ++k) {
            P[k] = reference::position(d, d.cell_vertices[4 * size_t(c) + k]);
            N[k] = reference::normal(d, d.cell_vertices[4 * size_t(c) + k]);
        }
        for (int trial = 0; trial < 3; ++trial) {
            Vec offset = diagonal * Vec(g(rng), g(rng), g(rng));
            if (dim == 2) offset -= offset.dot(frame.n) * frame.n;  // off-plane reads are checked by extrusion
            const Vec p = P[0] + offset;
            double coefficient[4];
            const Vec q = p - P[0];  // rows are relative to the slot-0 probe
            for (int r = 0; r < 4; ++r)
                coefficient[r] = m[4 * r] * q.x() + m[4 * r + 1] * q.y() + m[4 * r + 2] * q.z() + m[4 * r + 3];
            if (dim == 1) {
                STRUCTURE_CHECK(f, coefficient[0] == 0 && coefficient[1] == 0 && coefficient[2] == 0, "outer cell " << c);
                STRUCTURE_CHECK(f, std::fabs(coefficient[3] - (p - P[0]).dot(N[0])) <= 1e-6 * diagonal, "outer cell " << c);
                continue;
            }
            if (dim == 2) STRUCTURE_CHECK(f, coefficient[0] == 0, "outer cell " << c);
            // Compare at t = 0, diagonal/3, diagonal: f_stored(t) = k f_reference(t) for one k > 0.
            double stored[3], expected[3], magnitude = 0;
            const double ts[3] = {0, diagonal / 3, diagonal};
            for (int i = 0; i < 3; ++i) {
                const double t = ts[i];
                stored[i] = ((coefficient[0] * t + coefficient[1]) * t + coefficient[2]) * t + coefficient[3];
                expected[i] = reference::moved_facet_equation(P, N, dim, frame, p, t);
                magnitude = std::max(magnitude, std::fabs(expected[i]));
            }
            double k_num = 0, k_den = 0;
            for (int i = 0; i < 3; ++i) {
                k_num += stored[i] * expected[i];
                k_den += expected[i] * expected[i];
            }
            const double k = k_num / k_den;
            STRUCTURE_CHECK(f, k > 0, "outer cell " << c << " factor " << k);
            for (int i = 0; i < 3; ++i) {
                STRUCTURE_CHECK(f, std::fabs(stored[i] - k * expected[i]) <= 1e-4 * k * magnitude,
                                "outer cell " << c << " t " << ts[i] << " stored " << stored[i] << " reference*k "
                                              << k * expected[i]);
            }
        }
    }
    f.report("outer matrices");
}

inline void check_all(const StoreData& d, uint32_t seed = 7) {
    check_layout_and_links(d);
    check_outer_geometry(d);
    check_inner_matrices(d, seed);
    check_outer_matrices(d, seed);
}

}  // namespace structure
