// Rebuilding cells at load (core/cell_rebuild.h) gives exactly what the builder stores: on every
// hard-case family (lattices plain, rotated and jittered, cospherical and cocircular sets, flat and
// tilted sets, lines, clusters, offsets, scales, merged duplicates, with and without extrapolation)
// and on fuzzed degenerate sets, the rebuilt cells, neighbours and start grid equal the built store's
// index for index; the stored inner cells are the exact Delaunay tessellation (referee) and TetGen's
// for the same probes in the same order; and the steps after triangulating depend only on which
// cells there are, not on the order they came in.
#include "delaunay_referee.h"
#include "probe_families.h"

#include "bake/delaunay.h"
#include "bake/flat_delaunay.h"
#include "bake/store_builder.h"
#include "core/canonical_cells.h"
#include "core/cell_order.h"
#include "core/cell_rebuild.h"
#include "core/error.h"
#include "core/hull_normals.h"
#include "core/start_grid.h"

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using tetprobe::SimplexMesh;
using tetprobe::StoreData;

namespace {

StoreData build(const families::ProbeSet& set, uint32_t flags = 0) {
    tetprobe::BuildSettings settings;
    settings.flags = flags;
    return tetprobe::build_store_data(set.positions.data(), 12, nullptr, 108, set.count(), settings);
}

std::vector<float> plane_coordinates(const StoreData& d) {
    const uint32_t u = d.axis == 0 ? 1 : 0, w = d.axis == 2 ? 1 : 2;
    std::vector<float> uv(size_t(d.probe_count()) * 2);
    for (size_t j = 0; j < d.probe_count(); ++j) {
        uv[2 * j] = d.positions[3 * j + u];
        uv[2 * j + 1] = d.positions[3 * j + w];
    }
    return uv;
}

// The stored inner cells as a mesh (canonical slots, as stored).
SimplexMesh stored_inner_cells(const StoreData& d) {
    SimplexMesh mesh;
    mesh.dimension = d.dimension;
    for (uint32_t c = 0; c < d.inner_cell_count; ++c) {
        tetprobe::CellSlots v, n;
        for (int k = 0; k < 4; ++k) {
            v[size_t(k)] = d.cell_vertices[4 * size_t(c) + size_t(k)];
            const uint32_t link = d.cell_neighbours[4 * size_t(c) + size_t(k)];
            n[size_t(k)] = link < d.inner_cell_count ? link : tetprobe::kNone32;
        }
        mesh.add_cell(v, n);
    }
    return mesh;
}

// TetGen's cells for the stored probes in stored order (as the builder calls it), canonical.
SimplexMesh tetgen_cells(const StoreData& d) {
    SimplexMesh mesh;
    if (d.dimension == 3) {
        std::vector<Eigen::Vector3d> points(d.probe_count());
        for (size_t j = 0; j < points.size(); ++j) points[j] = Eigen::Vector3d(d.positions[3 * j], d.positions[3 * j + 1], d.positions[3 * j + 2]);
        mesh = tetprobe::delaunay_tetrahedralize(points);
    } else {
        const std::vector<float> uv = plane_coordinates(d);
        std::vector<Eigen::Vector2d> points(d.probe_count());
        for (size_t j = 0; j < points.size(); ++j) points[j] = Eigen::Vector2d(uv[2 * j], uv[2 * j + 1]);
        mesh = tetprobe::delaunay_triangulate_plane(points);
    }
    tetprobe::canonicalise_cells(mesh, d.positions.data(), d.axis);
    return mesh;
}

// The rebuild equals the store, index for index; the stored cells are the exact Delaunay ones and
// TetGen's. Returns whether TetGen agreed (it may fail or differ only where the builder documents it).
bool check_rebuild(const StoreData& d) {
    const tetprobe::RebuiltCells r =
        tetprobe::rebuild_cells(d.positions.data(), d.probe_count(), d.dimension, d.axis,
                                !(d.flags & tetprobe::kFlagNoExtrapolation), d.bounds_min, d.bounds_max, d.grid);
    REQUIRE(r.inner_cell_count == d.inner_cell_count);
    REQUIRE(r.cell_vertices == d.cell_vertices);
    REQUIRE(r.cell_neighbours == d.cell_neighbours);
    REQUIRE(std::equal(r.grid, r.grid + 3, d.grid));
    REQUIRE(r.grid_cells == d.grid_cells);
    if (d.dimension < 2) return true;
    const SimplexMesh stored = stored_inner_cells(d);
    if (d.dimension == 3) {
        REQUIRE(referee::delaunay_failure_3d(stored, d.positions.data(), d.probe_count()).empty());
    } else {
        const std::vector<float> uv = plane_coordinates(d);
        REQUIRE(referee::delaunay_failure_2d(stored, uv.data(), d.probe_count()).empty());
    }
    try {
        return referee::sorted_cells(tetgen_cells(d)) == referee::sorted_cells(stored);
    } catch (const tetprobe::Error&) {
        return false;
    }
}

families::ProbeSet cospherical(int r) {
    families::ProbeSet s{"integer sphere " + std::to_string(r) + " and its centre", {}};
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            for (int z = -r; z <= r; ++z)
                if (x * x + y * y + z * z == r * r) s.add(100 + x, 200 + y, 300 + z);
    s.add(100, 200, 300);
    return s;
}

families::ProbeSet cocircular(int r) {
    families::ProbeSet s{"integer circle " + std::to_string(r) + " and its centre, tilted", {}};
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            if (x * x + y * y == r * r) s.add(x, y, 2 * x - y);
    s.add(0, 0, 0);
    return s;
}

std::vector<families::ProbeSet> hard_families() {
    using namespace families;
    std::vector<ProbeSet> sets = {random_cloud(200, 1),
                                  random_cloud(60, 2, 0.5),
                                  lattice(2, 2, 2),
                                  lattice(3, 3, 3),
                                  lattice(5, 5, 5),
                                  lattice(8, 8, 8),
                                  lattice(12, 12, 12, 0.5),
                                  lattice(6, 6, 6, 1, 2.4e-7),
                                  lattice(7, 3, 2, 0.1),
                                  slab(8, 1e-3),
                                  plane(80, 5),
                                  tilted_plane_rounded(120, 6),
                                  racetrack(48),
                                  line(12),
                                  random_cloud(150, 11, 10, 1e3),
                                  random_cloud(150, 12, 10, 1e6),
                                  dense_room_in_a_level(21),
                                  random_cloud(150, 13, 1e-4),
                                  random_cloud(150, 14, 1e5),
                                  rotated_lattice(4, 1),
                                  rotated_lattice(7, 2),
                                  rotated_lattice(12, 1),
                                  rotated_lattice(6, 3, 1e6),
                                  cluster_in_a_level(300, 1e-2, 41),
                                  cluster_in_a_level(40, 1e-2, 42),
                                  cospherical(5),
                                  cospherical(9),
                                  cocircular(5),
                                  cocircular(25)};
    // Duplicates and near-duplicates (merged).
    ProbeSet duplicates = random_cloud(80, 10);
    std::mt19937 rng(10);
    for (int i = 0; i < 40; ++i) {
        const size_t j = rng() % 80;
        duplicates.add(duplicates.positions[3 * j] + (i % 2 ? 1e-6f : 0.0f), duplicates.positions[3 * j + 1],
                       duplicates.positions[3 * j + 2]);
    }
    duplicates.name = "duplicates";
    sets.push_back(duplicates);
    ProbeSet one{"1 probe", {}}, two{"2 probes", {}}, three{"3 probes", {}}, corridor{"3 in a corridor", {}};
    one.add(4, 5, 6);
    two.add(0, 0, 0), two.add(1, 2, 2);
    three.add(0, 0, 0), three.add(4, 0, 0), three.add(1, 3, 0);
    corridor.add(0, 1, 0), corridor.add(10, 1, 0), corridor.add(20, 1, 0);
    sets.insert(sets.end(), {one, two, three, corridor});
    return sets;
}

}  // namespace

TEST_CASE("rebuild: every hard-case family rebuilds the stored cells, neighbours and grid, with and without extrapolation", "[rebuild]") {
    int tetgen_agrees = 0, sets = 0;
    for (const families::ProbeSet& set : hard_families()) {
        for (const uint32_t flags : {0u, uint32_t(tetprobe::kFlagNoExtrapolation)}) {
            INFO(set.name << (flags ? " without extrapolation" : ""));
            const StoreData d = build(set, flags);
            // TetGen agrees on every one of these families: the store holds TetGen's cells.
            REQUIRE(check_rebuild(d));
            tetgen_agrees += 1;
            ++sets;
        }
    }
    REQUIRE(tetgen_agrees == sets);
}

TEST_CASE("rebuild: 11,000 probes (32-bit indices) rebuild the stored cells", "[rebuild]") {
    const StoreData d = build(families::random_cloud(11000, 18));
    REQUIRE(d.cell_count() > 65535);
    REQUIRE(check_rebuild(d));
}

TEST_CASE("rebuild: the set that crashes TetGen 1.5.0 rebuilds the cells TetGen gives it with its axes cycled", "[rebuild]") {
    families::ProbeSet set{"seven small integers", {}};
    const float p[] = {0, 0, 3, 0, 0, 0, 0, 0, -1, -1, -1, 0, 1, 0, 0, 1, 1, 2, 2, 3, -3};
    for (int i = 0; i < 7; ++i) set.add(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    const StoreData d = build(set);
    REQUIRE(d.probe_count() == 7);
    REQUIRE(check_rebuild(d));
}

TEST_CASE("rebuild: fuzzed degenerate sets rebuild what the builder stores", "[rebuild]") {
    // Small-integer and lattice-subset sets, scaled and offset, some flat or collinear, some with
    // duplicates: ties of every kind. Every one rebuilds exactly; TetGen's cells are the stored ones
    // wherever TetGen answers (counted).
    std::mt19937 rng(43);
    int built = 0, tetgen_agrees = 0;
    for (int trial = 0; trial < 600; ++trial) {
        families::ProbeSet set{"fuzz " + std::to_string(trial), {}};
        const int n = 2 + int(rng() % 60), range = 1 + int(rng() % 4), kind = trial % 4;
        const double scale = std::ldexp(1.0, int(rng() % 21) - 10) * (trial % 3 ? 1.0 : 0.3);
        const double offset = (trial % 5 == 0) ? 1000.0 : 0.0;
        for (int i = 0; i < n; ++i) {
            const int a = int(rng() % uint32_t(2 * range + 1)) - range, b = int(rng() % uint32_t(2 * range + 1)) - range,
                      c = int(rng() % uint32_t(2 * range + 1)) - range;
            switch (kind) {
                case 0: set.add(offset + scale * a, offset + scale * b, offset + scale * c); break;
                case 1: set.add(offset + scale * a, offset + scale * b, offset + 2.5); break;           // flat
                case 2: set.add(offset + scale * a, offset + scale * (a + b), offset + scale * (a - b)); break;  // tilted flat
                default: set.add(offset + scale * a, offset + 2 * scale * a, offset + scale * (b + 3 * c)); break;
            }
        }
        StoreData d;
        try {
            d = build(set);
        } catch (const tetprobe::Error&) {
            continue;  // e.g. every probe merged into one place along a line: not this test's concern
        }
        INFO(set.name << ", dimension " << d.dimension << ", " << d.probe_count() << " probes");
        tetgen_agrees += check_rebuild(d);
        ++built;
    }
    WARN("fuzzed sets: " << built << " built and rebuilt exactly; TetGen's cells are the stored ones for " << tetgen_agrees);
    REQUIRE(built > 500);
}

TEST_CASE("rebuild: ordering, outer cells and grid depend only on which cells there are", "[rebuild]") {
    // The same inner cells listed in another order, each with its slots rotated: identical store.
    for (const families::ProbeSet& set : {families::lattice(5, 5, 5), families::rotated_lattice(6, 2), families::plane(60, 3)}) {
        INFO(set.name);
        const StoreData d = build(set);
        SimplexMesh mesh = tetprobe::inner_cells(d.positions.data(), d.probe_count(), d.dimension, d.axis);
        std::mt19937 rng(47);
        std::vector<uint32_t> order(mesh.cell_count());
        for (uint32_t c = 0; c < order.size(); ++c) order[c] = c;
        std::shuffle(order.begin(), order.end(), rng);
        std::vector<uint32_t> new_of_old(order.size());
        for (uint32_t c = 0; c < order.size(); ++c) new_of_old[order[c]] = c;
        SimplexMesh shuffled;
        shuffled.dimension = mesh.dimension;
        for (uint32_t c = 0; c < order.size(); ++c) {
            tetprobe::CellSlots v = mesh.vertices[order[c]], n = mesh.neighbours[order[c]];
            for (auto& link : n)
                if (link != tetprobe::kNone32) link = new_of_old[link];
            // An even rotation of slots 1..3 (3D) keeps the orientation; canonical form undoes it.
            if (mesh.dimension == 3) {
                std::rotate(v.begin() + 1, v.begin() + 2, v.end());
                std::rotate(n.begin() + 1, n.begin() + 2, n.end());
            }
            shuffled.add_cell(v, n);
        }
        tetprobe::canonicalise_cells(shuffled, d.positions.data(), d.axis);
        StoreData e = d;
        tetprobe::store_cells(shuffled, e);
        tetprobe::order_cells_for_locality(e);
        tetprobe::build_start_grid(e);
        REQUIRE(e.cell_vertices == d.cell_vertices);
        REQUIRE(e.cell_neighbours == d.cell_neighbours);
        REQUIRE(e.grid_cells == d.grid_cells);
        // The hull normals follow the cells alone too.
        const Eigen::Vector3d direction = d.dimension == 2 ? Eigen::Vector3d(0, 0, 1) : Eigen::Vector3d(1, 0, 0);
        const auto a = tetprobe::hull_vertex_normals(d, direction), b = tetprobe::hull_vertex_normals(e, direction);
        for (size_t j = 0; j < a.size(); ++j) REQUIRE(a[j] == b[j]);
    }
}

TEST_CASE("rebuild: bad dimensions and degenerate probes are refused with a status", "[rebuild]") {
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const uint32_t grid[3] = {1, 1, 1}, no_grid[3] = {0, 1, 1};
    const float flat[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0.5f, 0.5f, 0};
    REQUIRE_THROWS_AS(tetprobe::rebuild_cells(flat, 5, 3, 0, true, lo, hi, grid), tetprobe::Error);
    REQUIRE_THROWS_AS(tetprobe::rebuild_cells(flat, 5, 4, 0, true, lo, hi, grid), tetprobe::Error);
    REQUIRE_THROWS_AS(tetprobe::rebuild_cells(flat, 5, 0, 0, true, lo, hi, grid), tetprobe::Error);
    const float same[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0};
    try {
        tetprobe::rebuild_cells(same, 5, 3, 0, true, lo, hi, grid);
        FAIL("a duplicate was accepted");
    } catch (const tetprobe::Error& e) {
        REQUIRE(e.status() == tetprobe::Status::invalid_argument);
    }
    REQUIRE_THROWS_AS(tetprobe::rebuild_cells(flat, 5, 2, 3, true, lo, hi, grid), tetprobe::Error);
    REQUIRE_THROWS_AS(tetprobe::rebuild_cells(flat, 5, 1, 7, true, lo, hi, grid), tetprobe::Error);
    const float nan_hi[3] = {1, std::nanf(""), 1};
    REQUIRE_THROWS_AS(tetprobe::rebuild_cells(flat, 5, 2, 2, true, lo, nan_hi, grid), tetprobe::Error);
    // A flat set rebuilds in its plane.
    REQUIRE_THROWS_AS(tetprobe::rebuild_cells(flat, 5, 2, 2, true, lo, hi, no_grid), tetprobe::Error);
    const tetprobe::RebuiltCells r = tetprobe::rebuild_cells(flat, 5, 2, 2, true, lo, hi, grid);
    REQUIRE(r.inner_cell_count == 4);
    REQUIRE(r.cell_vertices.size() == 4 * (4 + 4));
}
