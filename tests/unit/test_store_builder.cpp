// The store builder (bake/store_builder.h): structure of the StoreData it produces for every kind of
// probe set (exact orientation of every cell, outward winding of the outer cells, adjacency, no
// peeling: the inner cells tile the convex hull), independence of the input order, merging,
// dimension handling, bad input, progress and cancellation, and the blob it writes.
//
// The checks here read only positions and cells, and decide every sign with TetGen's exact
// predicates (not the builder's own filtered ones), so they referee the builder independently.
#include "probe_families.h"
#include "store_structure.h"

#include "bake/delaunay.h"
#include "bake/probe_merge.h"
#include "bake/set_dimension.h"
#include "core/start_grid.h"
#include "bake/store_builder.h"
#include "capi/tetprobe.h"
#include "core/error.h"
#include "core/position_quantization.h"
#include "core/store.h"
#include "core/store_data.h"
#include "core/store_format.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

// TetGen 1.5's exact predicates (global functions in libtet; REAL is double). Shewchuk's convention:
// orient3dexact(a, b, c, d) = det[a-d, b-d, c-d] = -det[b-a, c-a, d-a] (minus the store's orient3d);
// orient2dexact(a, b, c) = det[b-a, c-a] (the store's orient2d).
void exactinit(int verbose, int noexact, int nofilter, double maxx, double maxy, double maxz);
double orient3dexact(double* pa, double* pb, double* pc, double* pd);
double orient2dexact(double* pa, double* pb, double* pc);
double insphereexact(double* pa, double* pb, double* pc, double* pd, double* pe);

using tetprobe::BuildSettings;
using tetprobe::SectionEntry;
using tetprobe::kNone32;
using tetprobe::kOuter32;
using tetprobe::StoreData;
using Vec = Eigen::Vector3d;

namespace {

StoreData build(const std::vector<float>& positions, uint32_t flags = 0, const std::vector<float>* sh = nullptr,
                bool quantize = false, double merge_tolerance = tetprobe::kDefaultMergeTolerance) {
    BuildSettings settings;
    settings.flags = flags & ~uint32_t(TP_BUILD_COMPACT);  // TP_BUILD_COMPACT as the C ABI reads it
    settings.layout = (flags & TP_BUILD_COMPACT) ? tetprobe::kLayoutCompact : tetprobe::kLayoutFast;
    settings.quantize_positions = quantize;
    settings.merge_tolerance = merge_tolerance;
    return tetprobe::build_store_data(positions.data(), 12, sh ? sh->data() : nullptr, 108, positions.size() / 3,
                                      settings);
}

// Status and message of a build that must fail.
std::pair<tetprobe::Status, std::string> build_error(const std::vector<float>& positions, const BuildSettings& settings = {},
                                              const std::vector<float>* sh = nullptr) {
    try {
        tetprobe::build_store_data(positions.data(), 12, sh ? sh->data() : nullptr, 108, positions.size() / 3, settings);
    } catch (const tetprobe::Error& e) {
        return {e.status(), e.what()};
    }
    return {tetprobe::Status::ok, ""};
}

Vec position(const StoreData& d, uint32_t probe) {
    return Vec(d.positions[3 * size_t(probe)], d.positions[3 * size_t(probe) + 1], d.positions[3 * size_t(probe) + 2]);
}
Vec normal(const StoreData& d, uint32_t probe) {
    return Vec(d.normals[3 * size_t(probe)], d.normals[3 * size_t(probe) + 1], d.normals[3 * size_t(probe) + 2]);
}
uint32_t vertex(const StoreData& d, uint32_t cell, uint32_t slot) { return d.cell_vertices[4 * size_t(cell) + slot]; }
uint32_t neighbour(const StoreData& d, uint32_t cell, uint32_t slot) {
    return d.cell_neighbours[4 * size_t(cell) + slot];
}

// The store's orientation conventions (store_format.h), exactly, on the stored floats.
int orient3d(Vec a, Vec b, Vec c, Vec x) {
    static const bool initialised = (exactinit(0, 0, 0, 1.0, 1.0, 1.0), true);
    (void)initialised;
    const double value = -orient3dexact(a.data(), b.data(), c.data(), x.data());
    return (value > 0) - (value < 0);
}
Eigen::Vector2d plane_uv(const StoreData& d, const Vec& p) {
    const int u = d.axis == 0 ? 1 : 0, v = d.axis == 2 ? 1 : 2;
    return Eigen::Vector2d(p[u], p[v]);
}
int orient2d(const StoreData& d, const Vec& a, const Vec& b, const Vec& x) {
    Eigen::Vector2d p = plane_uv(d, a), q = plane_uv(d, b), r = plane_uv(d, x);
    (void)orient3d(Vec::Zero(), Vec::UnitX(), Vec::UnitY(), Vec::UnitZ());  // exactinit
    const double value = orient2dexact(p.data(), q.data(), r.data());
    return (value > 0) - (value < 0);
}
// Orientation of inner cell c (3D and 2D exactly; 1D along the axis), with p in place of slot `at`.
int cell_orientation(const StoreData& d, uint32_t c, const Vec* p = nullptr, uint32_t at = 4) {
    Vec v[4];
    for (uint32_t k = 0; k <= d.dimension; ++k) v[k] = (k == at && p) ? *p : position(d, vertex(d, c, k));
    if (d.dimension == 3) return orient3d(v[0], v[1], v[2], v[3]);
    if (d.dimension == 2) return orient2d(d, v[0], v[1], v[2]);
    if (d.dimension == 1) return (v[1][d.axis] > v[0][d.axis]) - (v[1][d.axis] < v[0][d.axis]);
    return 1;
}
// Signed measure (volume, area in (u, v), length along the axis) of inner cell c, in double.
double cell_measure(const StoreData& d, uint32_t c) {
    Vec v[4];
    for (uint32_t k = 0; k <= d.dimension; ++k) v[k] = position(d, vertex(d, c, k));
    if (d.dimension == 3) return (v[1] - v[0]).cross(v[2] - v[0]).dot(v[3] - v[0]) / 6;
    if (d.dimension == 2) {
        const Eigen::Vector2d e1 = plane_uv(d, v[1]) - plane_uv(d, v[0]), e2 = plane_uv(d, v[2]) - plane_uv(d, v[0]);
        return (e1.x() * e2.y() - e1.y() * e2.x()) / 2;
    }
    return d.dimension == 1 ? v[1][d.axis] - v[0][d.axis] : 0;
}

std::multiset<uint32_t> facet_without(const StoreData& d, uint32_t cell, uint32_t slot) {
    std::multiset<uint32_t> facet;
    for (uint32_t k = 0; k <= d.dimension; ++k)
        if (k != slot && vertex(d, cell, k) != kOuter32) facet.insert(vertex(d, cell, k));
    return facet;
}

struct StoreFacts {
    size_t flat_cells = 0;  // inner cells of exactly zero orientation on the stored floats
};

// Every invariant of store_format.h the builder owns, checked exhaustively (sets of a few hundred
// probes): sizes and remaps; slots; every inner cell positively oriented, exactly (a flat cell, zero,
// is counted and returned); neighbours symmetric and across the facet opposite their slot; outer
// cells on the hull facets, wound outward exactly; every probe in a cell; hull normals unit on the
// hull and zero inside; grid entries inner cells holding their centres (when inside); and no peeling:
// the boundary of the inner cells is convex and holds every probe (so it is the convex hull), and the
// inner cells' measures add up to the measure it encloses (so they tile it).
StoreFacts check_store(const StoreData& d) {
    const uint32_t dim = d.dimension, cells = d.cell_count(), inner = d.inner_cell_count, probes = d.probe_count();
    const bool extrapolates = !(d.flags & tetprobe::kFlagNoExtrapolation);
    REQUIRE(dim <= 3);
    REQUIRE((dim == 1 || dim == 2 || d.axis == 0));
    REQUIRE(d.axis <= 2);
    REQUIRE(d.positions.size() == 3 * size_t(probes));
    REQUIRE(d.normals.size() == 3 * size_t(probes));
    REQUIRE(d.sh.size() == 27 * size_t(probes));
    REQUIRE(d.input_remap.size() == d.input_probe_count);
    REQUIRE(d.cell_neighbours.size() == d.cell_vertices.size());
    REQUIRE(d.cell_vertices.size() == 4 * size_t(cells));
    REQUIRE(d.grid_cells.size() == size_t(d.grid[0]) * d.grid[1] * d.grid[2]);
    REQUIRE(inner >= 1);
    if (dim == 0) REQUIRE(cells == 1);
    if (!extrapolates || dim == 0) REQUIRE(cells == inner);

    structure::Failures f;
    for (uint32_t i = 0; i < d.input_probe_count; ++i) STRUCTURE_CHECK(f, d.input_remap[i] < probes, "input " << i);
    for (uint32_t j = 0; j < probes; ++j)
        STRUCTURE_CHECK(f, d.probe_source[j] < d.input_probe_count && d.input_remap[d.probe_source[j]] == j, "probe " << j);
    f.report("remaps");

    StoreFacts facts;
    std::vector<char> used(probes, 0);
    structure::Failures slots, orientation, links, winding;
    for (uint32_t c = 0; c < cells; ++c) {
        const bool is_inner = c < inner;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t v = vertex(d, c, k), n = neighbour(d, c, k);
            if (k > dim) {
                STRUCTURE_CHECK(slots, v == kNone32 && n == kNone32, "cell " << c << " slot " << k);
            } else if (k == dim && !is_inner) {
                STRUCTURE_CHECK(slots, v == kOuter32 && n < inner, "outer cell " << c);
            } else {
                STRUCTURE_CHECK(slots, v < probes, "cell " << c << " slot " << k);
                if (v < probes && is_inner) used[v] = 1;
            }
        }
        if (is_inner && dim >= 1) {
            const int o = cell_orientation(d, c);
            STRUCTURE_CHECK(orientation, o >= 0, "cell " << c);
            facts.flat_cells += o == 0;
        }
        // Links: n across the facet opposite slot k, and n links back across the same facet.
        for (uint32_t k = 0; k <= dim && dim >= 1; ++k) {
            const uint32_t n = neighbour(d, c, k);
            if (n == kNone32) {
                STRUCTURE_CHECK(links, (is_inner && (!extrapolates || dim == 0)) || (!is_inner && dim == 1 && k == 0),
                              "cell " << c << " slot " << k << " has no neighbour");
                continue;
            }
            STRUCTURE_CHECK(links, n < cells, "cell " << c << " slot " << k);
            if (n >= cells) continue;
            uint32_t back = 4;
            for (uint32_t m = 0; m <= dim; ++m)
                if (neighbour(d, n, m) == c) back = m;
            STRUCTURE_CHECK(links, back <= dim, "cell " << c << " slot " << k << " -> " << n << " does not link back");
            if (back > dim) continue;
            if (is_inner && n < inner) {
                STRUCTURE_CHECK(links, facet_without(d, c, k) == facet_without(d, n, back), "inner " << c << "/" << n);
            } else if (is_inner) {
                STRUCTURE_CHECK(links, back == dim && facet_without(d, c, k) == facet_without(d, n, dim), "hull " << c);
                // Outward winding: the inner cell's vertex opposite the facet is on the negative side.
                Vec P[3];
                for (uint32_t m = 0; m < dim; ++m) P[m] = position(d, vertex(d, n, m));
                const Vec x = position(d, vertex(d, c, k));
                if (dim == 3) STRUCTURE_CHECK(winding, orient3d(P[0], P[1], P[2], x) <= 0, "outer " << n);
                if (dim == 3 && facts.flat_cells == 0) STRUCTURE_CHECK(winding, orient3d(P[0], P[1], P[2], x) < 0, "outer " << n);
                if (dim == 2) STRUCTURE_CHECK(winding, orient2d(d, P[0], P[1], x) <= 0, "outer " << n);
                if (dim == 1) {
                    // Slot 0 is the end probe; the inner cell's other probe lies the other way along the axis.
                    const uint32_t end = vertex(d, n, 0);
                    STRUCTURE_CHECK(winding, end == vertex(d, c, 1 - k), "outer " << n);
                    const Vec ray = normal(d, end);
                    STRUCTURE_CHECK(winding, ray.dot(position(d, end) - x) > 0, "outer " << n);
                }
            } else if (n >= inner) {
                // Outer neighbours share d - 1 probes: the facets without the slot each one links by.
                std::multiset<uint32_t> a = facet_without(d, c, k), b = facet_without(d, n, back);
                STRUCTURE_CHECK(links, k < dim && back < dim && a == b, "outer " << c << "/" << n);
            }
        }
    }
    slots.report("slots");
    orientation.report("inner cells positively oriented (exactly)");
    links.report("neighbour links");
    winding.report("outer cells wound outward (exactly)");
    REQUIRE(std::count(used.begin(), used.end(), 1) == int(probes));

    // Hull normals: unit on the hull (probes of outer cells), zero elsewhere.
    if (extrapolates && dim >= 1) {
        std::vector<char> on_hull(probes, 0);
        for (uint32_t c = inner; c < cells; ++c)
            for (uint32_t k = 0; k < dim; ++k) on_hull[vertex(d, c, k)] = 1;
        structure::Failures normals;
        for (uint32_t j = 0; j < probes; ++j) {
            const double length = normal(d, j).norm();
            STRUCTURE_CHECK(normals, on_hull[j] ? std::fabs(length - 1) < 1e-6 : length == 0, "probe " << j);
        }
        normals.report("hull normals");
    }

    // No peeling: the hull facets (inner facets without an inner neighbour) are convex, with every
    // probe on their inner side or on them, and the inner cells add up to what they enclose.
    if (dim >= 2) {
        std::vector<std::array<Vec, 3>> facets;
        double enclosed = 0, tiled = 0;
        static const int kOthers[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
        for (uint32_t c = 0; c < inner; ++c) {
            tiled += cell_measure(d, c);
            for (uint32_t k = 0; k <= dim; ++k) {
                const uint32_t n = neighbour(d, c, k);
                if (n < inner) continue;
                std::array<Vec, 3> facet;
                if (dim == 3) {
                    for (int m = 0; m < 3; ++m) facet[size_t(m)] = position(d, vertex(d, c, uint32_t(kOthers[k][m])));
                    enclosed += facet[0].dot(facet[1].cross(facet[2])) / 6;
                } else {
                    facet[0] = position(d, vertex(d, c, (k + 2) % 3));
                    facet[1] = position(d, vertex(d, c, (k + 1) % 3));
                    const Eigen::Vector2d a = plane_uv(d, facet[0]), b = plane_uv(d, facet[1]);
                    enclosed += (b.x() * a.y() - a.x() * b.y()) / 2;  // the boundary runs clockwise in (u, v)
                }
                facets.push_back(facet);
            }
        }
        structure::Failures convex;
        for (const auto& facet : facets)
            for (uint32_t j = 0; j < probes; ++j) {
                const int side = dim == 3 ? orient3d(facet[0], facet[1], facet[2], position(d, j))
                                          : orient2d(d, facet[0], facet[1], position(d, j));
                STRUCTURE_CHECK(convex, side <= 0, "probe " << j << " beyond a hull facet");
            }
        convex.report("the inner cells' boundary is the convex hull");
        INFO("inner cells " << tiled << ", enclosed by their boundary " << enclosed);
        REQUIRE(tiled == Approx(enclosed).epsilon(1e-9));
    }

    // Grid entries: inner cells, holding their centre when some inner cell does (exactly).
    structure::Failures grid;
    for (uint32_t z = 0; z < d.grid[2]; ++z)
        for (uint32_t y = 0; y < d.grid[1]; ++y)
            for (uint32_t x = 0; x < d.grid[0]; ++x) {
                const uint32_t g = d.grid_cells[(size_t(z) * d.grid[1] + y) * d.grid[0] + x];
                STRUCTURE_CHECK(grid, g < inner, "grid " << x << "," << y << "," << z);
            }
    grid.report("grid entries");
    return facts;
}

// A lattice under a random rotation, rounded to float: nearly (not exactly) coplanar and cospherical
// everywhere, the hardest family for exact decisions.
families::ProbeSet rotated_lattice(int n, uint32_t seed, double spacing = 1, double offset = 0) {
    families::ProbeSet s{"rotated lattice " + std::to_string(n) + " seed " + std::to_string(seed), {}};
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    const Eigen::Quaterniond q = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    const Eigen::Matrix3d r = q.toRotationMatrix();
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const Vec p = r * Vec(x, y, z) * spacing + Vec::Constant(offset);
                s.add(p.x(), p.y(), p.z());
            }
    return s;
}

}  // namespace

static void check_structure_of(const std::vector<families::ProbeSet>& sets) {
    for (const auto& set : sets) {
        for (uint32_t flags : {0u, uint32_t(TP_BUILD_NO_EXTRAPOLATION)}) {
            INFO(set.name << " flags " << flags);
            check_store(build(set.positions, flags));
        }
    }
}

TEST_CASE("builder: every inner cell is positively oriented and every outer cell wound outward, exactly", "[builder]") {
    check_structure_of({families::random_cloud(150, 1), families::lattice(2, 2, 2), families::lattice(4, 3, 5),
                        families::lattice(5, 5, 5, 1, 2.4e-7), families::lattice(6, 6, 6, 1, 2.4e-7, 3),
                        families::slab(6, 1e-3), families::dense_room_in_a_level(5)});
}

TEST_CASE("builder: rotated lattices are oriented exactly, and tiled without peeling", "[builder]") {
    std::vector<families::ProbeSet> sets;
    for (uint32_t seed : {1u, 2u, 3u}) sets.push_back(rotated_lattice(5 + int(seed), seed));
    sets.push_back(rotated_lattice(6, 4, 0.5, 1000.0));  // far from the world origin
    check_structure_of(sets);
}

TEST_CASE("builder: flat sets and lines are oriented exactly in their stored coordinates", "[builder]") {
    check_structure_of({families::plane(60, 2), families::tilted_plane_rounded(80, 3), families::line(7),
                        families::racetrack(40), families::lattice(6, 5, 1), families::lattice(7, 1, 4)});
}

TEST_CASE("builder: the axis of a flat set is the one dropped, of a line the one it runs along", "[builder]") {
    // A plane x = 3 is triangulated in (y, z): axis 0. A plane y = const: axis 1, in (x, z).
    std::vector<float> yz, xz;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 4; ++j) {
            yz.insert(yz.end(), {3.0f, float(i), float(j * j)});
            xz.insert(xz.end(), {float(i * i), -2.0f, float(j)});
        }
    CHECK(build(yz).axis == 0);
    CHECK(build(xz).axis == 1);
    CHECK(build(families::plane(30, 4).positions).axis == 2);
    // Lines: the largest component of the direction (0.5, -0.25, 0.75) is z.
    const StoreData line = build(families::line(6).positions);
    REQUIRE(line.dimension == 1);
    CHECK(line.axis == 2);
    // Segments are ordered by the stored coordinate along that axis: v0 < v1.
    for (uint32_t c = 0; c < line.inner_cell_count; ++c)
        CHECK(position(line, vertex(line, c, 0))[2] < position(line, vertex(line, c, 1))[2]);
}

TEST_CASE("builder: set dimension follows the shape", "[builder]") {
    CHECK(build(families::random_cloud(40, 2).positions).dimension == 3);
    CHECK(build(families::lattice(3, 3, 3).positions).dimension == 3);
    CHECK(build(families::slab(5, 1e-3).positions).dimension == 3);
    CHECK(build(families::slab(5, 1e-6).positions).dimension == 2);  // thinner than the flat tolerance
    CHECK(build(families::plane(30, 4).positions).dimension == 2);
    CHECK(build(families::tilted_plane_rounded(30, 5).positions).dimension == 2);
    CHECK(build(families::racetrack(20).positions).dimension == 2);
    CHECK(build(families::line(5).positions).dimension == 1);
    CHECK(build({1, 2, 3}).dimension == 0);
    CHECK(build({1, 2, 3, 1, 2, 3, 1, 2, 3}).dimension == 0);  // identical probes merge into one
}

TEST_CASE("builder: one probe is one inner cell and no outer cell", "[builder]") {
    const StoreData d = build({5, -2, 7});
    check_store(d);
    REQUIRE(d.dimension == 0);
    REQUIRE(d.cell_count() == 1);
    REQUIRE(d.inner_cell_count == 1);
    REQUIRE(d.cell_vertices == std::vector<uint32_t>{0, tetprobe::kNone32, tetprobe::kNone32, tetprobe::kNone32});
    REQUIRE(d.origin[0] == 5);
    REQUIRE(d.origin[1] == -2);
    REQUIRE(d.origin[2] == 7);
    REQUIRE(d.positions == std::vector<float>{0, 0, 0});
}

TEST_CASE("builder: two probes and collinear probes make segments with two end cells", "[builder]") {
    SECTION("two probes") {
        const StoreData d = build({0, 0, 0, 2, 4, 4});
        check_store(d);
        REQUIRE(d.dimension == 1);
        REQUIRE(d.inner_cell_count == 1);
        REQUIRE(d.cell_count() == 3);
        // The ends' rays point away from each other along the segment.
        const Vec n0 = normal(d, 0), n1 = normal(d, 1);
        REQUIRE(n0.dot(Vec(2, 4, 4).normalized()) == Approx(-1));
        REQUIRE(n1.dot(Vec(2, 4, 4).normalized()) == Approx(1));
    }
    SECTION("collinear, unsorted input") {
        const std::vector<float> p = {3, 3, 3, 0, 0, 0, 1, 1, 1, 4, 4, 4, 2, 2, 2};
        const StoreData d = build(p);
        check_store(d);
        REQUIRE(d.dimension == 1);
        REQUIRE(d.inner_cell_count == 4);
        REQUIRE(d.cell_count() == 6);
        // Segments join neighbours along the line: every segment is one unit of (1,1,1) long.
        for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
            const Vec a = position(d, d.cell_vertices[4 * c]);
            const Vec b = position(d, d.cell_vertices[4 * c + 1]);
            REQUIRE((a - b).norm() == Approx(std::sqrt(3.0)));
        }
    }
}

TEST_CASE("builder: flat sets are triangulated in their plane", "[builder]") {
    SECTION("three probes") {
        const StoreData d = build({0, 0, 0, 1, 0, 0, 0, 1, 0});
        check_store(d);
        REQUIRE(d.dimension == 2);
        REQUIRE(d.inner_cell_count == 1);
        REQUIRE(d.cell_count() == 4);
    }
    SECTION("a square lattice gives two triangles per square and no cell off the plane") {
        const StoreData d = build(families::lattice(6, 5, 1).positions);
        check_store(d);
        REQUIRE(d.dimension == 2);
        REQUIRE(d.inner_cell_count == 2 * 5 * 4);
        REQUIRE(d.cell_count() - d.inner_cell_count == 2 * (5 + 4));  // boundary edges
    }
}

TEST_CASE("builder: duplicates and near-duplicates merge into the first, with the mean SH", "[builder]") {
    families::ProbeSet set = families::random_cloud(30, 9);
    const size_t base = set.count();
    std::vector<float> sh(27 * base);
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = float(i % 97) * 0.01f;
    // Probe base + i copies probe 3 * i exactly, or 1e-8 of the diagonal away.
    for (size_t i = 0; i < 5; ++i) {
        const float* p = &set.positions[3 * (3 * i)];
        set.add(p[0] + (i % 2 ? 1e-7f * 40 : 0.f), p[1], p[2]);
        for (int c = 0; c < 27; ++c) sh.push_back(float(c));
    }
    const StoreData d = build(set.positions, 0, &sh);
    check_store(d);
    REQUIRE(d.input_probe_count == base + 5);
    REQUIRE(d.probe_count() == base);
    for (size_t i = 0; i < 5; ++i) {
        const uint32_t survivor = d.input_remap[3 * i];
        REQUIRE(d.input_remap[base + i] == survivor);
        REQUIRE(d.probe_source[survivor] == 3 * i);
        for (int c = 0; c < 27; ++c) REQUIRE(d.sh[27 * survivor + c] == Approx((sh[27 * 3 * i + c] + float(c)) / 2));
    }
    // Probes that were not merged keep their SH and position.
    const uint32_t kept = d.input_remap[1];
    REQUIRE(d.probe_source[kept] == 1);
    for (int c = 0; c < 27; ++c) REQUIRE(d.sh[27 * kept + c] == sh[27 + c]);
    for (int a = 0; a < 3; ++a) REQUIRE(d.positions[3 * kept + a] + d.origin[a] == Approx(set.positions[3 + a]));
}

TEST_CASE("builder: probes closer than the merge tolerance merge, farther ones do not", "[builder]") {
    std::vector<float> p = families::lattice(3, 3, 3).positions;  // diagonal 2 sqrt(3)
    p.insert(p.end(), {1.0f + 1e-3f, 1, 1});                        // 2.9e-4 of the diagonal from (1,1,1)
    BuildSettings settings;
    settings.merge_tolerance = 1e-3;
    StoreData merged = tetprobe::build_store_data(p.data(), 12, nullptr, 108, p.size() / 3, settings);
    REQUIRE(merged.probe_count() == 27);
    REQUIRE(merged.input_remap[27] == merged.input_remap[13]);
    settings.merge_tolerance = 1e-4;
    StoreData kept = tetprobe::build_store_data(p.data(), 12, nullptr, 108, p.size() / 3, settings);
    REQUIRE(kept.probe_count() == 28);
    check_store(kept);
}

TEST_CASE("builder: probes that coincide in a line's (flat set's) decided coordinates merge, at any merge tolerance", "[builder]") {
    // Off the line (plane) by less than the flat tolerance and sharing the coordinates the run time
    // decides in with another probe: moved onto the set they would be two probes at one point (found by
    // fuzzing with coordinates near 1e25, where the reduced coordinates still differed by a rounding).
    std::vector<float> line, flat;
    for (int k = 0; k < 10; ++k) line.insert(line.end(), {0.0f, 0.0f, float(k)});
    line.insert(line.end(), {1e-6f, 0.0f, 5.0f});
    for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 4; ++y) flat.insert(flat.end(), {float(x), float(y), 0.0f});
    flat.insert(flat.end(), {2.0f, 1.0f, 1e-6f});
    for (const auto& set : {std::make_pair(line, 5u), std::make_pair(flat, 9u)}) {
        const StoreData d = build(set.first, 0, nullptr, false, 0.0);
        const uint32_t last = uint32_t(set.first.size() / 3) - 1;
        INFO("dimension " << d.dimension);
        REQUIRE(d.dimension == (set.second == 5u ? 1u : 2u));
        REQUIRE(d.probe_count() == last);
        REQUIRE(d.input_remap[last] == d.input_remap[set.second]);
        REQUIRE(d.probe_source[d.input_remap[last]] == set.second);  // the first given survives
    }
}

TEST_CASE("builder: a flat set merges probes that differ only across its plane", "[builder]") {
    std::vector<float> p = families::lattice(4, 4, 1).positions;
    p.insert(p.end(), {1, 1, 1e-5f});  // above lattice probe (1,1,0): the same point of the plane
    const StoreData d = build(p);
    REQUIRE(d.dimension == 2);
    REQUIRE(d.probe_count() == 16);
    REQUIRE(d.input_remap[16] == d.input_remap[5]);
    check_store(d);
}

TEST_CASE("builder: no extrapolation leaves hull facets without neighbours", "[builder]") {
    const StoreData d = build(families::random_cloud(50, 4).positions, TP_BUILD_NO_EXTRAPOLATION);
    REQUIRE(d.cell_count() == d.inner_cell_count);
    REQUIRE((d.flags & tetprobe::kFlagNoExtrapolation) != 0);
    size_t open = 0;
    for (uint32_t n : d.cell_neighbours) open += n == tetprobe::kNone32;
    REQUIRE(open > 0);
    check_store(d);
}

TEST_CASE("builder: cell 0 is the inner cell nearest the centre and the grid names cells holding its centres", "[builder]") {
    const StoreData d = build(families::random_cloud(150, 5, 4.0, 20.0).positions);
    Vec centre;
    for (int a = 0; a < 3; ++a) centre[a] = 0.5 * (double(d.bounds_min[a]) + double(d.bounds_max[a]));
    auto centroid = [&](uint32_t c) {
        Vec s = Vec::Zero();
        for (uint32_t k = 0; k < 4; ++k) s += position(d, d.cell_vertices[4 * c + k]) / 4;
        return s;
    };
    const double best = (centroid(0) - centre).norm();
    for (uint32_t c = 1; c < d.inner_cell_count; ++c) REQUIRE((centroid(c) - centre).norm() >= best - 1e-6);
    REQUIRE(d.grid[0] * d.grid[1] * d.grid[2] > 1);
    // A grid centre that some inner cell holds (exactly) is held by the cell its entry names.
    auto holds = [&](uint32_t c, const Vec& p) {
        for (uint32_t k = 0; k < 4; ++k)
            if (cell_orientation(d, c, &p, k) < 0) return false;
        return true;
    };
    size_t inside = 0;
    for (uint32_t z = 0; z < d.grid[2]; ++z)
        for (uint32_t y = 0; y < d.grid[1]; ++y)
            for (uint32_t x = (y + z) % 3; x < d.grid[0]; x += 3) {  // a third of the grid suffices
                const uint32_t g[3] = {x, y, z};
                Vec p;
                for (int a = 0; a < 3; ++a)
                    p[a] = d.bounds_min[a] + (g[a] + 0.5) * (double(d.bounds_max[a]) - d.bounds_min[a]) / d.grid[a];
                bool held = false;
                for (uint32_t c = 0; c < d.inner_cell_count && !held; ++c) held = holds(c, p);
                if (!held) continue;
                ++inside;
                REQUIRE(holds(d.grid_cells[(z * d.grid[1] + y) * d.grid[0] + x], p));
            }
    REQUIRE(inside > 0);
}

TEST_CASE("builder: origin is the centre of the bounding box and positions are local", "[builder]") {
    const families::ProbeSet set = families::random_cloud(20, 6, 1.0, 1000.0);
    const StoreData d = build(set.positions);
    for (int a = 0; a < 3; ++a) {
        double lo = set.positions[size_t(a)], hi = lo;
        for (size_t i = 0; i < set.count(); ++i) {
            lo = std::min(lo, double(set.positions[3 * i + a]));
            hi = std::max(hi, double(set.positions[3 * i + a]));
        }
        REQUIRE(d.origin[a] == 0.5 * (lo + hi));
    }
    for (uint32_t j = 0; j < d.probe_count(); ++j)
        for (int a = 0; a < 3; ++a)
            REQUIRE(d.positions[3 * j + a] == float(double(set.positions[3 * d.probe_source[j] + a]) - d.origin[a]));
}

namespace {

SectionEntry section_of(const std::vector<uint8_t>& blob, tetprobe::Section id) {
    SectionEntry e;
    std::memcpy(&e, blob.data() + sizeof(tetprobe::StoreHeader) + id * sizeof(SectionEntry), sizeof e);
    return e;
}

// Builds `set` with SH, then shuffled and reversed copies, and requires the same store: positions,
// normals, SH, cells, links, grid, origin, bit for bit; the remaps agree up to the permutation. The
// blobs (quantised ones included) are the same bytes outside the probe maps and the checksum.
void require_order_independent(const families::ProbeSet& set, uint32_t seed, bool quantize = false) {
    const size_t n = set.count();
    std::vector<float> sh(27 * n);
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = float((i * 7919) % 1013) * 0.001f;
    const StoreData a = build(set.positions, 0, &sh, quantize);
    std::vector<uint8_t> blob_a;
    for (const tetprobe::ShEncoding encoding : {tetprobe::kShHalf, tetprobe::kShUnorm8}) {
        StoreData encoded = a;
        encoded.sh_encoding = encoding;
        blob_a = tetprobe::write_store_blob(encoded);
    }
    std::mt19937 rng(seed);
    for (int trial = 0; trial < 4; ++trial) {
        std::vector<uint32_t> perm(n);  // shuffled input i is input perm[i]
        std::iota(perm.begin(), perm.end(), 0u);
        if (trial == 0) std::reverse(perm.begin(), perm.end());
        else std::shuffle(perm.begin(), perm.end(), rng);
        std::vector<float> p(3 * n), q(27 * n);
        for (size_t i = 0; i < n; ++i) {
            std::copy_n(&set.positions[3 * size_t(perm[i])], 3, &p[3 * i]);
            std::copy_n(&sh[27 * size_t(perm[i])], 27, &q[27 * i]);
        }
        const StoreData b = build(p, 0, &q, quantize);
        INFO(set.name << " trial " << trial << (quantize ? ", quantised" : ""));
        for (int k = 0; k < 3; ++k) REQUIRE(a.origin[k] == b.origin[k]);
        REQUIRE(a.dimension == b.dimension);
        REQUIRE(a.axis == b.axis);
        REQUIRE(a.positions == b.positions);
        REQUIRE(a.normals == b.normals);
        REQUIRE(a.sh == b.sh);
        REQUIRE(a.inner_cell_count == b.inner_cell_count);
        REQUIRE(a.cell_vertices == b.cell_vertices);
        REQUIRE(a.cell_neighbours == b.cell_neighbours);
        REQUIRE(a.grid_cells == b.grid_cells);
        for (size_t i = 0; i < n; ++i) REQUIRE(b.input_remap[i] == a.input_remap[perm[i]]);
        StoreData encoded = b;
        encoded.sh_encoding = tetprobe::kShUnorm8;
        const std::vector<uint8_t> blob_b = tetprobe::write_store_blob(encoded);
        REQUIRE(blob_a.size() == blob_b.size());
        for (uint32_t s = 0; s < tetprobe::kSectionCount; ++s) {
            if (s == tetprobe::kSectionProbeSource || s == tetprobe::kSectionInputRemap) continue;
            const SectionEntry ea = section_of(blob_a, tetprobe::Section(s)), eb = section_of(blob_b, tetprobe::Section(s));
            INFO("section " << s);
            REQUIRE(ea.offset == eb.offset);
            REQUIRE(ea.size == eb.size);
            REQUIRE(std::memcmp(blob_a.data() + ea.offset, blob_b.data() + eb.offset, ea.size) == 0);
        }
        REQUIRE(std::memcmp(blob_a.data(), blob_b.data(), tetprobe::kChecksumOffset) == 0);  // the header up to its checksum
    }
}

}  // namespace

TEST_CASE("builder: the store does not depend on the order the probes are given in", "[builder]") {
    require_order_independent(families::random_cloud(300, 21), 1);
    require_order_independent(families::lattice(5, 5, 5, 1, 2.4e-7, 4), 2);
    require_order_independent(rotated_lattice(6, 7), 3);
    require_order_independent(families::dense_room_in_a_level(8), 4);
    require_order_independent(families::tilted_plane_rounded(60, 9), 5);
    require_order_independent(families::racetrack(30), 6);
    require_order_independent(families::line(9), 7);
    require_order_independent(families::random_cloud(300, 22, 10, 1e3), 8, true);
    require_order_independent(families::lattice(5, 5, 5, 1, 3e-5, 5), 9, true);
    require_order_independent(families::tilted_plane_rounded(60, 10), 10, true);
}

// ---- quantised positions

namespace {

// Violations of the empty-sphere property: inner facets whose opposite vertex in the neighbouring inner
// cell lies strictly inside the cell's circumsphere, decided by TetGen's exact predicates on the
// stored positions (a triangulation of the hull that is locally Delaunay everywhere is Delaunay).
size_t delaunay_violations(const StoreData& d) {
    exactinit(0, 0, 0, 1, 1, 1);
    size_t violations = 0;
    auto point = [&](uint32_t probe, double out[3]) {
        for (int a = 0; a < 3; ++a) out[a] = d.positions[3 * size_t(probe) + a];
    };
    for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
        double p[5][3];
        for (int k = 0; k < 4; ++k) point(d.cell_vertices[4 * size_t(c) + k], p[k]);
        const double orientation = orient3dexact(p[0], p[1], p[2], p[3]);
        for (int k = 0; k < 4; ++k) {
            const uint32_t n = d.cell_neighbours[4 * size_t(c) + k];
            if (n >= d.inner_cell_count) continue;
            uint32_t opposite = kNone32;
            for (int j = 0; j < 4; ++j) {
                const uint32_t v = d.cell_vertices[4 * size_t(n) + j];
                if (std::find(&d.cell_vertices[4 * size_t(c)], &d.cell_vertices[4 * size_t(c)] + 4, v) ==
                    &d.cell_vertices[4 * size_t(c)] + 4)
                    opposite = v;
            }
            point(opposite, p[4]);
            // Shewchuk: insphere > 0 for a point inside when orient3d > 0; the product says so for either winding.
            if (insphereexact(p[0], p[1], p[2], p[3], p[4]) * orientation > 0) ++violations;
        }
    }
    return violations;
}

}  // namespace

TEST_CASE("builder: quantised positions are on their grid, within half a step of their inputs, in a valid store", "[builder]") {
    const std::vector<families::ProbeSet> sets = {
        families::random_cloud(500, 41), families::random_cloud(300, 42, 10, 1e3), families::lattice(6, 6, 6, 1, 3e-5, 4),
        families::plane(80, 43), families::tilted_plane_rounded(60, 44), families::line(9), families::racetrack(30),
        families::dense_room_in_a_level(45), families::random_cloud(200, 46, 3.0, 1e4)};
    for (const families::ProbeSet& set : sets) {
        const StoreData d = build(set.positions, 0, nullptr, true);
        INFO(set.name << ", dimension " << d.dimension);
        REQUIRE(d.position_encoding == tetprobe::kPositionsUnorm16);
        structure::check_layout_and_links(d);
        structure::check_inner_orientation(d);
        double gap[3], worst[3] = {0, 0, 0};
        for (int a = 0; a < 3; ++a) gap[a] = tetprobe::position_max_gap(d.bounds_min[a], d.bounds_max[a]);
        for (uint32_t j = 0; j < d.probe_count(); ++j) {
            const uint32_t input = d.probe_source[j];
            for (int a = 0; a < 3; ++a) {
                const float stored = d.positions[3 * size_t(j) + a];
                REQUIRE(tetprobe::quantize_position(stored, d.bounds_min[a], d.bounds_max[a]) == stored);
                // A flat set's dropped coordinate (a line's other two) moved onto the fitted plane (line).
                const bool moved_onto_the_set = (d.dimension == 2 && uint32_t(a) == d.axis) ||
                                                (d.dimension == 1 && uint32_t(a) != d.axis);
                if (moved_onto_the_set) continue;
                const float given = float(double(set.positions[3 * size_t(input) + a]) - d.origin[a]);
                worst[a] = std::max(worst[a], std::fabs(double(stored) - double(given)));
            }
        }
        for (int a = 0; a < 3; ++a) {
            INFO("axis " << a << ": moved at most " << worst[a] << ", step " << gap[a]);
            REQUIRE(worst[a] <= 0.5 * gap[a]);
        }
        if (d.dimension == 3) REQUIRE(delaunay_violations(d) == 0);
        // The data writes a blob that loads and decodes to the same floats.
        const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
        const std::unique_ptr<tetprobe::Store> store = tetprobe::Store::load(blob.data(), blob.size());
        for (uint32_t j = 0; j < d.probe_count(); ++j)
            REQUIRE(std::memcmp(store->probe_position(j), &d.positions[3 * size_t(j)], 3 * sizeof(float)) == 0);
        if (&set == &sets[0])  // the probes did move (elsewhere float input may already lie on the grid)
            for (int a = 0; a < 3; ++a) CHECK(worst[a] > 0.3 * gap[a]);
    }
}

TEST_CASE("builder: a lattice on the quantisation grid stays a lattice: the same positions and cells as unquantised", "[builder]") {
    // Probes every 0.5 (and at 1e4 from the origin, where float input itself lies on a coarse grid): the
    // power-of-two step divides their coordinates, so quantising moves none of them.
    for (const families::ProbeSet& set : {families::lattice(6, 5, 4, 0.5), families::random_cloud(200, 49, 3.0, 1e4)}) {
        const StoreData plain = build(set.positions), quantized = build(set.positions, 0, nullptr, true);
        INFO(set.name);
        REQUIRE(quantized.position_encoding == tetprobe::kPositionsUnorm16);
        REQUIRE(quantized.probe_count() == plain.probe_count());
        for (size_t i = 0; i < plain.positions.size(); ++i)
            REQUIRE(double(quantized.positions[i]) + quantized.origin[i % 3] == double(plain.positions[i]) + plain.origin[i % 3]);
        REQUIRE(quantized.probe_source == plain.probe_source);
        // The same cells (stored in another order: the order follows the bounds, the quantisation box here).
        auto cell_set = [](const StoreData& d) {
            std::multiset<std::array<uint32_t, 4>> cells;
            for (size_t c = 0; c < d.cell_count(); ++c) {
                std::array<uint32_t, 4> v;
                std::copy_n(&d.cell_vertices[4 * c], 4, v.begin());
                std::sort(v.begin(), v.end());
                cells.insert(v);
            }
            return cells;
        };
        REQUIRE(quantized.inner_cell_count == plain.inner_cell_count);
        REQUIRE(cell_set(quantized) == cell_set(plain));
    }
}

TEST_CASE("builder: the cells are Delaunay for the quantised positions, not for the given ones", "[builder]") {
    // A lattice jittered by about half a quantisation step: the given positions decide its ties one way,
    // the quantised ones another. The quantised build triangulates what it stores.
    const families::ProbeSet set = families::lattice(7, 7, 7, 1, 5e-5, 47);
    const StoreData quantized = build(set.positions, 0, nullptr, true);
    REQUIRE(delaunay_violations(quantized) == 0);
    // The cells of the given positions, with those positions moved to the same grid afterwards, are not.
    StoreData snapped = build(set.positions);
    for (size_t i = 0; i < snapped.positions.size(); ++i)
        snapped.positions[i] = tetprobe::quantize_position(snapped.positions[i], quantized.bounds_min[i % 3],
                                                           quantized.bounds_max[i % 3]);
    CHECK(delaunay_violations(snapped) > 0);
}

TEST_CASE("builder: probes that quantise to the same point are merged into the first, with the mean SH", "[builder]") {
    // 200 probes and copies of 20 of them a quarter of a step away (distinct floats, which a float build
    // with merge tolerance 0 keeps apart) that quantise to their originals' point. The grid is the
    // builder's, read from a build of the originals (the copies lie inside their bounds, so it stays).
    families::ProbeSet set = families::random_cloud(200, 48);
    const StoreData originals = build(set.positions, 0, nullptr, true, 0.0);
    double lo[3], hi[3], origin[3];
    float box_lo[3], box_hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = hi[a] = set.positions[size_t(a)];
        for (size_t i = 0; i < set.count(); ++i)
            lo[a] = std::min(lo[a], double(set.positions[3 * i + a])), hi[a] = std::max(hi[a], double(set.positions[3 * i + a]));
        origin[a] = originals.origin[a];
        box_lo[a] = originals.bounds_min[a], box_hi[a] = originals.bounds_max[a];
    }
    std::vector<uint32_t> copied;
    for (uint32_t i = 0; i < 200 && copied.size() < 20; ++i) {
        float world[3];
        bool same_point = true, distinct = false;
        for (int a = 0; a < 3; ++a) {
            const float given = set.positions[3 * i + a], local = float(double(given) - origin[a]);
            const float grid = tetprobe::quantize_position(local, box_lo[a], box_hi[a]);
            const double quarter = 0.25 * tetprobe::position_max_gap(box_lo[a], box_hi[a]);
            world[a] = float(origin[a] + double(grid) + (local < grid ? quarter : -quarter));
            const float moved = float(double(world[a]) - origin[a]);
            same_point &= tetprobe::quantize_position(moved, box_lo[a], box_hi[a]) == grid;
            same_point &= world[a] > lo[a] && world[a] < hi[a];  // the bounds stay those of the originals
            distinct |= world[a] != given;
        }
        if (!same_point || !distinct) continue;
        set.add(world[0], world[1], world[2]);
        copied.push_back(i);
    }
    REQUIRE(copied.size() == 20);
    std::vector<float> sh(27 * set.count());
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = float(i % 97) * 0.01f;
    REQUIRE(build(set.positions, 0, &sh, false, 0.0).probe_count() == 220);
    const StoreData d = build(set.positions, 0, &sh, true, 0.0);
    REQUIRE(d.probe_count() == 200);
    REQUIRE(d.input_probe_count == 220);
    for (uint32_t k = 0; k < 20; ++k) {
        const uint32_t i = copied[k], stored = d.input_remap[200 + k];
        REQUIRE(d.input_remap[i] == stored);
        REQUIRE(d.probe_source[stored] == i);  // the first given survives
        for (int c = 0; c < 27; ++c)
            REQUIRE(d.sh[27 * size_t(stored) + c] == float((double(sh[27 * i + c]) + double(sh[27 * (200 + k) + c])) / 2));
    }
    // The blob keeps input_remap (something merged) and reports the merge.
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
    const std::unique_ptr<tetprobe::Store> store = tetprobe::Store::load(blob.data(), blob.size());
    REQUIRE(store->header().input_probe_count - store->header().probe_count == 20);
    REQUIRE(store->input_to_stored(205) == store->input_to_stored(copied[5]));
}

TEST_CASE("builder: probes are stored along a space-filling curve, cells too", "[builder]") {
    // Consecutive stored probes are near each other: far nearer on average than in the caller's
    // (random) order.
    const families::ProbeSet set = families::random_cloud(2000, 31);
    const StoreData d = build(set.positions);
    double stored = 0, given = 0;
    for (uint32_t j = 1; j < d.probe_count(); ++j) {
        stored += (position(d, j) - position(d, j - 1)).norm();
        given += (position(d, d.input_remap[j]) - position(d, d.input_remap[j - 1])).norm();
    }
    CHECK(stored < given / 4);
    double cells = 0;
    auto centroid = [&](uint32_t c) {
        Vec s = Vec::Zero();
        for (uint32_t k = 0; k < 4; ++k) s += position(d, vertex(d, c, k)) / 4;
        return s;
    };
    for (uint32_t c = 2; c < d.inner_cell_count; ++c) cells += (centroid(c) - centroid(c - 1)).norm();
    CHECK(cells / (d.inner_cell_count - 2) < given / (d.probe_count() - 1) / 4);
}

TEST_CASE("builder: TP_BUILD_COMPACT is accepted and sets the compact layout; the other flag bits are the store's", "[builder]") {
    const std::vector<float> p = families::random_cloud(30, 12).positions;
    STATIC_REQUIRE(TP_BUILD_NO_EXTRAPOLATION == tetprobe::kFlagNoExtrapolation);
    STATIC_REQUIRE(TP_BUILD_INDEX32 == tetprobe::kFlagIndex32);
    for (uint32_t flags = 0; flags < 8; ++flags) {
        const StoreData d = build(p, flags);
        INFO("flags " << flags);
        REQUIRE(d.flags == (flags & ~uint32_t(TP_BUILD_COMPACT)));
        REQUIRE(d.layout == ((flags & TP_BUILD_COMPACT) ? tetprobe::kLayoutCompact : tetprobe::kLayoutFast));
    }
    // The compact layout is a layout only: the same cells.
    REQUIRE(build(p, TP_BUILD_COMPACT).cell_vertices == build(p).cell_vertices);
}

TEST_CASE("builder: bad input is refused with a status naming the probe", "[builder]") {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    std::vector<float> p = families::random_cloud(10, 7).positions;

    auto with = [&](size_t index, float value) {
        std::vector<float> q = p;
        q[index] = value;
        return build_error(q);
    };
    auto e = with(3 * 4 + 1, nan);
    REQUIRE(e.first == tetprobe::Status::invalid_argument);
    REQUIRE(e.second.find("probe 4") != std::string::npos);
    REQUIRE(e.second.find(" y ") != std::string::npos);
    e = with(3 * 9 + 2, -inf);
    REQUIRE(e.first == tetprobe::Status::invalid_argument);
    REQUIRE(e.second.find("probe 9") != std::string::npos);
    REQUIRE(e.second.find(" z ") != std::string::npos);
    e = with(0, 3e31f);
    REQUIRE(e.first == tetprobe::Status::invalid_argument);
    REQUIRE(e.second.find("probe 0") != std::string::npos);

    std::vector<float> sh(27 * 10, 0.5f);
    sh[27 * 6 + 13] = nan;
    e = build_error(p, {}, &sh);
    REQUIRE(e.first == tetprobe::Status::invalid_argument);
    REQUIRE(e.second.find("probe 6") != std::string::npos);

    REQUIRE(build_error({}).first == tetprobe::Status::degenerate);
    // Distinct probes closer than 1e-9 units: refused; identical probes (one position) are fine.
    const auto tiny = build_error({1e-20f, 0, 0, 0, 3e-21f, 0, 0, 0, 1e-20f, 2e-21f, 2e-21f, 2e-21f});
    REQUIRE(tiny.first == tetprobe::Status::degenerate);
    REQUIRE(tiny.second.find("span") != std::string::npos);
    REQUIRE(build_error({0, 0, 0, 2e-9f, 0, 0}).first == tetprobe::Status::ok);
    REQUIRE(build_error({5, 5, 5, 5, 5, 5}).first == tetprobe::Status::ok);

    BuildSettings bad;
    bad.merge_tolerance = -1;
    REQUIRE(build_error(p, bad).first == tetprobe::Status::invalid_argument);
    bad = BuildSettings();
    bad.flat_tolerance = std::nan("");
    REQUIRE(build_error(p, bad).first == tetprobe::Status::invalid_argument);
    bad = BuildSettings();
    bad.flags = 0x80;
    REQUIRE(build_error(p, bad).first == tetprobe::Status::invalid_argument);
}

namespace {

struct ProgressLog {
    std::vector<float> fractions;
    std::vector<std::string> stages;
    int cancel_at = -1;
};

int log_progress(void* user, float fraction, const char* stage) {
    auto* log = static_cast<ProgressLog*>(user);
    log->fractions.push_back(fraction);
    log->stages.push_back(stage);
    return int(log->fractions.size()) - 1 == log->cancel_at ? 1 : 0;
}

}  // namespace

TEST_CASE("builder: progress reaches 1 in order, and a non-zero return cancels", "[builder]") {
    const std::vector<float> p = families::random_cloud(40, 8).positions;
    ProgressLog log;
    BuildSettings settings;
    settings.progress.callback = &log_progress;
    settings.progress.user = &log;
    tetprobe::build_store_data(p.data(), 12, nullptr, 108, p.size() / 3, settings);
    REQUIRE(log.fractions.size() >= 5);
    REQUIRE(log.fractions.front() == 0.0f);
    REQUIRE(log.fractions.back() == 1.0f);
    for (size_t i = 1; i < log.fractions.size(); ++i) REQUIRE(log.fractions[i] >= log.fractions[i - 1]);

    for (int at : {0, 2, int(log.fractions.size()) - 1}) {
        ProgressLog cancel;
        cancel.cancel_at = at;
        settings.progress.user = &cancel;
        auto e = build_error(p, settings);
        REQUIRE(e.first == tetprobe::Status::cancelled);
        REQUIRE(e.second == "cancelled by the progress callback during " + cancel.stages.back());
        REQUIRE(cancel.fractions.size() == size_t(at) + 1);
    }
}

TEST_CASE("builder: strided positions and SH read the same as packed ones", "[builder]") {
    const families::ProbeSet set = families::random_cloud(25, 10);
    std::vector<float> sh(27 * set.count());
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = float(i) * 0.001f;
    const size_t ps = 5, ss = 31;  // floats per record
    std::vector<float> strided_p(ps * set.count(), -1.f), strided_sh(ss * set.count(), -1.f);
    for (size_t i = 0; i < set.count(); ++i) {
        std::memcpy(&strided_p[ps * i], &set.positions[3 * i], 12);
        std::memcpy(&strided_sh[ss * i], &sh[27 * i], 108);
    }
    BuildSettings settings;
    const StoreData a = tetprobe::build_store_data(set.positions.data(), 12, sh.data(), 108, set.count(), settings);
    const StoreData b =
        tetprobe::build_store_data(strided_p.data(), ps * 4, strided_sh.data(), ss * 4, set.count(), settings);
    REQUIRE(a.positions == b.positions);
    REQUIRE(a.sh == b.sh);
    REQUIRE(a.cell_vertices == b.cell_vertices);
    REQUIRE(a.cell_neighbours == b.cell_neighbours);
}

TEST_CASE("builder: the data writes a blob that loads and answers at the probes", "[builder]") {
    // (tp_store_build itself is this path behind the C boundary; the C harness covers its arguments.)
    const families::ProbeSet set = families::random_cloud(30, 11);
    for (uint32_t flags : {0u, uint32_t(TP_BUILD_INDEX32), uint32_t(TP_BUILD_NO_EXTRAPOLATION)}) {
        const StoreData d = build(set.positions, flags);
        const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
        const auto store = tetprobe::Store::load(blob.data(), blob.size());
        REQUIRE(store->header().probe_count == 30);
        REQUIRE(store->header().dimension == 3);
        REQUIRE(((store->header().flags & tetprobe::kFlagIndex32) != 0) == ((flags & TP_BUILD_INDEX32) != 0));
        for (uint32_t i = 0; i < 30; ++i) {
            const tetprobe::Location loc = store->locate(&set.positions[3 * i], -1);
            REQUIRE(loc.status == tetprobe::Status::ok);
            for (int k = 0; k < 4; ++k) {
                if (loc.probes[k] == d.input_remap[i]) REQUIRE(loc.weights[k] == Approx(1).margin(1e-5));
            }
        }
    }
}

TEST_CASE("builder: merging keeps the first probe of each group and leaves survivors apart", "[builder]") {
    std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0.5, 0, 0}, {1.0, 0, 0}, {0.9, 0, 0}, {0, 0, 0}, {3, 3, 3}};
    const tetprobe::ProbeMerge merge = tetprobe::merge_close_points(points, 0.6);
    // 0 survives; 0.5 joins 0; 1.0 survives (1.0 from 0); 0.9 joins 1.0 (0.9 from 0 is too far);
    // the duplicate of 0 joins 0; (3,3,3) survives.
    REQUIRE(merge.survivors == std::vector<uint32_t>{0, 2, 5});
    REQUIRE(merge.group_of == std::vector<uint32_t>{0, 0, 1, 1, 0, 2});
    const tetprobe::ProbeMerge exact = tetprobe::merge_close_points(points, 0.0);
    REQUIRE(exact.survivors == std::vector<uint32_t>{0, 1, 2, 3, 5});
    REQUIRE(exact.group_of[4] == 0);
}

TEST_CASE("builder: dimension detection compares thickness with the flat tolerance times the diagonal", "[builder]") {
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) points.emplace_back(i, j, (i * j) % 2 ? 1e-3 : 0.0);
    const double diagonal = std::sqrt(81.0 + 81.0 + 1e-6);
    REQUIRE(tetprobe::detect_set_dimension(points, diagonal, 1e-3).dimension == 2);
    REQUIRE(tetprobe::detect_set_dimension(points, diagonal, 1e-5).dimension == 3);
    // The caller's tolerance never goes below the float-rounding floor.
    std::vector<Eigen::Vector3d> thin = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1e-9}};
    REQUIRE(tetprobe::detect_set_dimension(thin, std::sqrt(2.0), 0.0).dimension == 2);
    std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2 + 1e-8}};
    const tetprobe::SetShape shape = tetprobe::detect_set_dimension(line, std::sqrt(12.0), 1e-4);
    REQUIRE(shape.dimension == 1);
    REQUIRE(std::fabs(shape.axes.col(0).dot(Eigen::Vector3d(1, 1, 1).normalized())) == Approx(1));
}

TEST_CASE("builder: start grid dimensions follow the extents within the cell budget", "[builder]") {
    uint32_t g[3];
    const float lo[3] = {0, 0, 0}, cube[3] = {10, 10, 10}, flat[3] = {20, 10, 0}, box[3] = {40, 10, 10};
    tetprobe::start_grid_dimensions(lo, cube, 4000, 4, g);
    REQUIRE(g[0] == 10);
    REQUIRE(g[1] == 10);
    REQUIRE(g[2] == 10);
    tetprobe::start_grid_dimensions(lo, cube, 8000, 8, g);  // the rebuilt layout's cells per entry
    REQUIRE(g[0] == 10);
    REQUIRE(g[1] == 10);
    REQUIRE(g[2] == 10);
    tetprobe::start_grid_dimensions(lo, flat, 800, 4, g);
    REQUIRE(g[2] == 1);
    REQUIRE(g[0] == 2 * g[1]);
    tetprobe::start_grid_dimensions(lo, box, 100000000, 4, g);
    REQUIRE(size_t(g[0]) * g[1] * g[2] <= tetprobe::kMaxStartGridCells);
    REQUIRE(g[0] > 3 * g[1]);
    tetprobe::start_grid_dimensions(lo, lo, 1, 4, g);
    REQUIRE(g[0] * g[1] * g[2] == 1);
}

TEST_CASE("builder: a set that crashes TetGen 1.5.0 is contained and retried", "[builder]") {
    // Found by fuzz_build: centred and rounded to float, these seven points make Debian's TetGen
    // 1.5.0 fail an assertion (abort). With its axes cycled TetGen handles them; the build must
    // succeed that way, and the process must live either way.
    const std::vector<float> positions = {0, 0, 3, 0, 0, 0, 0, 0, -1, -1, -1, 0, 1, 0, 0, 1, 1, 2, 2, 3, -3};
    const StoreData d = build(positions, 0);
    REQUIRE(d.dimension == 3);
    REQUIRE(d.probe_count() == 7);
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
    const auto store = tetprobe::Store::load(blob.data(), blob.size());
    for (uint32_t i = 0; i < 7; ++i) {
        const tetprobe::Location loc = store->locate(&positions[3 * i], -1);
        REQUIRE(loc.status == tetprobe::Status::ok);
        float own = 0;
        for (int k = 0; k < 4; ++k)
            if (loc.probes[k] == d.input_remap[i]) own += loc.weights[k];
        CHECK(own == Approx(1).margin(1e-5));
    }
}

TEST_CASE("builder: a flat set with collinear boundary probes keeps every probe", "[builder]") {
    // Found by fuzz_build: four probes on one straight stretch of the boundary. TetGen 1.5.0 left one
    // out of the flat triangulation for one apex (with clang's rounding), which merged it into a
    // neighbour 1.1 away; another apex keeps it.
    const std::vector<float> positions = {1000.f, 1000.f, 1000.f,  1000.37f, 1000.f, 1000.f,  1000.f, 1000.f, 999.63f,
                                          1001.48f, 1000.f, 1000.37f, 1000.f, 1000.f, 1000.37f, 1001.11f, 1000.f, 1000.f,
                                          1000.f, 1000.f, 1001.48f};
    const StoreData d = build(positions, 0);
    REQUIRE(d.dimension == 2);
    REQUIRE(d.probe_count() == 7);
}

namespace {

// Every input probe answers as its survivor alone, with the hint carried from query to query as a
// moving object would.
void require_exact_at_inputs(const StoreData& d, const std::vector<float>& positions) {
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
    const auto store = tetprobe::Store::load(blob.data(), blob.size());
    int32_t hint = -1;
    for (size_t i = 0; i < positions.size() / 3; ++i) {
        const tetprobe::Location loc = store->locate(&positions[3 * i], hint);
        REQUIRE(loc.status == tetprobe::Status::ok);
        hint = loc.cell;
        float own = 0;
        for (int k = 0; k < 4; ++k)
            if (loc.probes[k] == d.input_remap[i]) own += loc.weights[k];
        INFO("input probe " << i);
        REQUIRE(own == Approx(1).margin(1e-5));
    }
}

}  // namespace

TEST_CASE("builder: a flat set already on its plane keeps its coordinates and makes no slivers", "[builder]") {
    // Found by fuzz_build: probes on the plane y = 0, four of them on one straight stretch of the
    // boundary. Rotated into the plane's principal axes and rounded, the four were no longer
    // collinear; TetGen then built slivers along them, and the end probe was left in a sliver only,
    // which the run time never answers. Triangulated in the plane's own coordinates they stay
    // exactly collinear.
    SECTION("the fuzzer's set") {
        const std::vector<float> positions = {0, 0, 3, 4, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 1};
        const StoreData d = build(positions);
        REQUIRE(d.dimension == 2);
        REQUIRE(d.probe_count() == 5);
        REQUIRE(d.inner_cell_count == 3);  // a fan from (4, 0, 0) over the three boundary segments
        require_exact_at_inputs(d, positions);
    }
    SECTION("random small-integer sets on axis planes") {
        uint32_t state = 12345;
        auto next = [&state](int range) {
            state = state * 1664525u + 1013904223u;
            return int((state >> 8) % uint32_t(range)) - range / 2;
        };
        for (int trial = 0; trial < 300; ++trial) {
            std::vector<float> positions;
            const int count = 4 + trial % 12, kind = trial % 2;
            for (int i = 0; i < count; ++i) {
                const int a = next(9), b = next(9);
                switch (kind) {
                    case 0: positions.insert(positions.end(), {float(a), 2.5f, float(b)}); break;
                    case 1: positions.insert(positions.end(), {float(a), float(b), -7.0f}); break;
                    case 2: positions.insert(positions.end(), {float(a), float(b), float(a + b)}); break;
                    default: positions.insert(positions.end(), {float(2 * a - b), float(a), float(b)}); break;
                }
            }
            BuildSettings settings;
            StoreData d;
            try {
                d = tetprobe::build_store_data(positions.data(), 12, nullptr, 108, size_t(count), settings);
            } catch (const tetprobe::Error&) {
                continue;  // fewer than three distinct probes off one line: not this test's concern
            }
            if (d.dimension != 2) continue;
            INFO("trial " << trial << " kind " << kind);
            check_store(d);
            // Stored exactly as given: the local position is the input minus the origin, rounded once.
            for (size_t i = 0; i < size_t(count); ++i) {
                const uint32_t s = d.input_remap[i];
                if (d.probe_source[s] != i) continue;
                for (int c = 0; c < 3; ++c) REQUIRE(d.positions[3 * s + c] == float(double(positions[3 * i + c]) - d.origin[c]));
            }
            // No sliver: with integer coordinates in [-4, 4] a real triangle's area is at least 1/2.
            for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
                const Vec p0 = position(d, d.cell_vertices[4 * c]);
                const Vec p1 = position(d, d.cell_vertices[4 * c + 1]);
                const Vec p2 = position(d, d.cell_vertices[4 * c + 2]);
                REQUIRE((p1 - p0).cross(p2 - p0).norm() > 0.5);
            }
            require_exact_at_inputs(d, positions);
        }
    }
}

TEST_CASE("builder: a needle on the hull is not peeled as a sliver", "[builder]") {
    // Found by fuzz_build: near the hull a needle cell (three probes close together, one far away)
    // has almost no volume relative to its longest edge, but peeling it left the probe at
    // (0.86, -1.05e15, 0) 1e-4 of the set's size beyond a new hull facet, whose outer cell then
    // answered a query at that probe. Peeling now requires every probe to stay that close.
    const std::vector<float> positions = {-2.3038981e-02f, 4.5559e-41f, 1.076e-42f, -9.228156e+18f, -2.5245947e-29f,
                                          1.36e-43f, 1.8525781e+02f, 1.6495023e-33f, 1.6495023e-33f, 1.6495023e-33f,
                                          1.6495023e-33f, 6.1743466e+16f, 6.1743466e+16f, 6.1743466e+16f,
                                          6.1743466e+16f, 8.568627e-01f, -1.0526106e+15f, -3.6268155e-14f};
    const StoreData d = build(positions);
    REQUIRE(d.dimension == 3);
    require_exact_at_inputs(d, positions);
}
