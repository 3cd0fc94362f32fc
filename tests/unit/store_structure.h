// Structural checks of a StoreData against core/store_format.h (format 3: no matrices), shared by
// the run-time tests: slot layout, neighbour symmetry across shared facets, every probe used, every
// inner cell positively oriented exactly (core/orientation.h on the stored floats, in the store's
// frame: all coordinates, the two other than axis, or coordinate axis), outer facets wound outward
// (exactly) and tiling the hull, hull normals unit and untangled.
#pragma once

#include "reference_interpolator.h"

#include "core/orientation.h"
#include "core/plane_projection.h"
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
    REQUIRE(((d.dimension == 1 || d.dimension == 2) ? d.axis <= 2 : d.axis == 0));
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

// Exact orientation of probes a..: the sign of the simplex in the store's frame (orient3d, orient2d
// on the plane's coordinates, the difference along axis).
inline int frame_orientation(const StoreData& d, const uint32_t* probes) {
    const float* p[4];
    for (uint32_t k = 0; k <= d.dimension; ++k) p[k] = &d.positions[3 * size_t(probes[k])];
    if (d.dimension == 3) return tetprobe::orient3d(p[0], p[1], p[2], p[3]);
    if (d.dimension == 2) {
        float uv[3][2];
        for (int k = 0; k < 3; ++k) tetprobe::project_to_plane(p[k], d.axis, uv[k]);
        return tetprobe::orient2d(uv[0], uv[1], uv[2]);
    }
    if (d.dimension == 1) return p[1][d.axis] > p[0][d.axis] ? 1 : (p[1][d.axis] < p[0][d.axis] ? -1 : 0);
    return 1;
}

// Every inner cell is positively oriented, exactly (none flat, none inverted).
inline void check_inner_orientation(const StoreData& d) {
    Failures f;
    for (uint32_t c = 0; c < d.inner_cell_count && d.dimension > 0; ++c) {
        const int sign = frame_orientation(d, &d.cell_vertices[4 * size_t(c)]);
        STRUCTURE_CHECK(f, sign > 0, "inner cell " << c << " orientation " << sign);
    }
    f.report("inner orientation");
}

// Outer facets wound outward: the base cell's probe that is not on the facet lies strictly on the
// negative side (exact orientation with the facet in slot order; for a line, against the end's
// normal). Hull normals are unit (zero off the hull), and each facet moved out along its normals
// keeps turning like the facet itself up to 1e5 diagonals out (otherwise the cell folds over its
// neighbours there), sampled at a few distances.
inline void check_outer_geometry(const StoreData& d, double allowed_fold_fraction = 0) {
    const uint32_t dim = d.dimension, inner = d.inner_cell_count;
    std::vector<char> on_hull(d.probe_count(), 0);
    const reference::Frame frame = reference::frame_of(d);
    Vec lo = Vec::Constant(HUGE_VAL), hi = -lo;
    for (uint32_t j = 0; j < d.probe_count(); ++j) {
        lo = lo.cwiseMin(reference::position(d, j));
        hi = hi.cwiseMax(reference::position(d, j));
    }
    const double diagonal = (hi - lo).norm();
    Failures f, folds;
    for (uint32_t c = inner; c < d.cell_count(); ++c) {
        const uint32_t base = d.cell_neighbours[4 * size_t(c) + dim];
        STRUCTURE_CHECK(f, base < inner, "outer cell " << c << " base " << base);
        if (base >= inner) continue;
        std::set<uint32_t> facet;
        for (uint32_t k = 0; k < dim; ++k) {
            facet.insert(d.cell_vertices[4 * size_t(c) + k]);
            on_hull[d.cell_vertices[4 * size_t(c) + k]] = 1;
        }
        uint32_t apex = kNone32;
        for (uint32_t k = 0; k <= dim; ++k) {
            const uint32_t v = d.cell_vertices[4 * size_t(base) + k];
            if (!facet.count(v)) apex = v;
        }
        STRUCTURE_CHECK(f, apex != kNone32, "outer cell " << c);
        if (apex == kNone32) continue;
        int side;
        if (dim == 1) {
            const float* end = &d.positions[3 * size_t(d.cell_vertices[4 * size_t(c)])];
            const float* inside = &d.positions[3 * size_t(apex)];
            const float direction = d.normals[3 * size_t(d.cell_vertices[4 * size_t(c)]) + d.axis];
            const double along = (double(inside[d.axis]) - end[d.axis]) * direction;
            side = along > 0 ? 1 : (along < 0 ? -1 : 0);
        } else {
            uint32_t probes[4] = {0, 0, 0, 0};
            for (uint32_t k = 0; k < dim; ++k) probes[k] = d.cell_vertices[4 * size_t(c) + k];
            probes[dim] = apex;
            side = frame_orientation(d, probes);
        }
        STRUCTURE_CHECK(f, side < 0, "outer cell " << c << " winding " << side);
        if (dim == 3) {
            const Vec p0 = reference::position(d, d.cell_vertices[4 * size_t(c)]);
            const Vec p1 = reference::position(d, d.cell_vertices[4 * size_t(c) + 1]);
            const Vec p2 = reference::position(d, d.cell_vertices[4 * size_t(c) + 2]);
            Vec n[3];
            for (uint32_t k = 0; k < 3; ++k) n[k] = reference::normal(d, d.cell_vertices[4 * size_t(c) + k]);
            const Vec facet_normal = (p1 - p0).cross(p2 - p0);
            for (double t : {0.0, 1e-2, 1.0, 1e2, 1e3, 1e4, 3e4, 1e5}) {
                const Vec q0 = p0 + t * diagonal * n[0], q1 = p1 + t * diagonal * n[1], q2 = p2 + t * diagonal * n[2];
                const bool keeps = (q1 - q0).cross(q2 - q0).dot(facet_normal) > 0;
                STRUCTURE_CHECK(folds, keeps, "outer cell " << c << " turns over at " << t << " diagonals out");
                if (!keeps) break;  // one count per cell
            }
        } else if (dim == 2) {
            const Vec p0 = frame.project(reference::position(d, d.cell_vertices[4 * size_t(c)]));
            const Vec p1 = frame.project(reference::position(d, d.cell_vertices[4 * size_t(c) + 1]));
            const Vec n0 = frame.project(reference::normal(d, d.cell_vertices[4 * size_t(c)]));
            const Vec n1 = frame.project(reference::normal(d, d.cell_vertices[4 * size_t(c) + 1]));
            const Vec e = p1 - p0;
            for (double t : {0.0, 1e-2, 1.0, 1e2, 1e3, 1e4, 3e4, 1e5}) {
                const Vec moved = (p1 + t * diagonal * n1) - (p0 + t * diagonal * n0);
                STRUCTURE_CHECK(f, moved.dot(e) > 0, "outer cell " << c << " turns over at " << t << " diagonals out");
            }
        }
    }
    for (uint32_t j = 0; j < d.probe_count(); ++j) {
        const double length = reference::normal(d, j).norm();
        if (on_hull[j])
            STRUCTURE_CHECK(f, std::fabs(length - 1) < 1e-6, "probe " << j << " normal length " << length);
        else if (inner < d.cell_count())
            STRUCTURE_CHECK(f, length == 0, "probe " << j << " off the hull, normal length " << length);
    }
    f.report("outer geometry");
    INFO("outer cells that turn over: " << folds.count << " of " << (d.cell_count() - inner) << ", the first: "
                                        << folds.first);
    REQUIRE(double(folds.count) <= allowed_fold_fraction * double(d.cell_count() - inner));
}

// allowed_fold_fraction: of the outer cells, how many may turn over within 1e5 diagonals.
inline void check_all(const StoreData& d, uint32_t seed = 7, double allowed_fold_fraction = 0) {
    (void)seed;
    check_layout_and_links(d);
    check_inner_orientation(d);
    check_outer_geometry(d, allowed_fold_fraction);
}

}  // namespace structure
