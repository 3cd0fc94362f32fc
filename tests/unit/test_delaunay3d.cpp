// The exact Delaunay tetrahedralization (core/delaunay3d.h): the exact referee accepts it on random,
// lattice, cospherical, coplanar-sided, clustered and extreme-scale sets; it does not depend on the
// insertion order; it is TetGen 1.5's tessellation cell for cell for the same points in the same
// order, degenerate sets included (small-integer sets fuzzed by the thousand); bad input is refused.
#include "delaunay_referee.h"

#include "bake/delaunay.h"
#include "core/canonical_cells.h"
#include "core/delaunay3d.h"
#include "core/error.h"

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using tetprobe::SimplexMesh;

namespace {

struct PointSet {
    std::string name;
    std::vector<float> xyz;
    uint32_t count() const { return uint32_t(xyz.size() / 3); }
    void add(double x, double y, double z) {
        xyz.push_back(float(x));
        xyz.push_back(float(y));
        xyz.push_back(float(z));
    }
};

PointSet random_set(uint32_t n, uint32_t seed, double scale = 1, double offset = 0) {
    PointSet s{"random " + std::to_string(n) + " scale " + std::to_string(scale) + " offset " + std::to_string(offset), {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (uint32_t i = 0; i < n; ++i) s.add(offset + scale * u(rng), offset + scale * u(rng), offset + scale * u(rng));
    return s;
}

PointSet lattice(int n, double spacing = 1, double offset = 0) {
    PointSet s{"lattice " + std::to_string(n) + " spacing " + std::to_string(spacing), {}};
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) s.add(offset + x * spacing, offset + y * spacing, offset + z * spacing);
    return s;
}

// Every integer point of a sphere of radius r (many cospherical, coplanar and cocircular subsets).
PointSet sphere(int r) {
    PointSet s{"integer sphere " + std::to_string(r), {}};
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            for (int z = -r; z <= r; ++z)
                if (x * x + y * y + z * z == r * r) s.add(x, y, z);
    return s;
}

// Distinct random points of a small integer box: ties of every kind.
PointSet small_integers(uint32_t n, int range, uint32_t seed) {
    PointSet s{"small integers " + std::to_string(n) + " in " + std::to_string(range) + " seed " + std::to_string(seed), {}};
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> u(-range, range);
    std::vector<std::array<int, 3>> seen;
    while (s.count() < n) {
        const std::array<int, 3> p = {u(rng), u(rng), u(rng)};
        if (std::find(seen.begin(), seen.end(), p) != seen.end()) continue;
        seen.push_back(p);
        s.add(p[0], p[1], p[2]);
    }
    return s;
}

// Points on three coordinate planes of a box and inside: coplanar hull sides with many points.
PointSet box_sides(uint32_t n, uint32_t seed) {
    PointSet s{"box sides " + std::to_string(n), {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    for (uint32_t i = 0; i < n; ++i) {
        double p[3] = {u(rng), u(rng), u(rng)};
        if (i % 3 != 2) p[i % 3] = (i % 2) ? 1.0 : 0.0;
        s.add(p[0], p[1], p[2]);
    }
    return s;
}

SimplexMesh tetgen_cells(const PointSet& s) {
    std::vector<Eigen::Vector3d> points(s.count());
    for (size_t j = 0; j < points.size(); ++j) points[j] = Eigen::Vector3d(s.xyz[3 * j], s.xyz[3 * j + 1], s.xyz[3 * j + 2]);
    SimplexMesh mesh = tetprobe::delaunay_tetrahedralize(points);
    tetprobe::canonicalise_cells(mesh, s.xyz.data(), 0);
    return mesh;
}

std::vector<PointSet> families() {
    std::vector<PointSet> sets = {random_set(300, 1),          random_set(200, 2, 1e-4),     random_set(200, 3, 1e5),
                                  random_set(200, 4, 100, 1e6),  random_set(200, 5, 1e-30),    lattice(2),
                                  lattice(5),                  lattice(6, 0.5, -1.25),       lattice(5, 0.3, 1000),
                                  lattice(4, 1e-3),            sphere(5),                    sphere(9),
                                  small_integers(60, 2, 7),    small_integers(120, 3, 8),    box_sides(300, 9)};
    // A cluster 1e-2 wide (300 float steps) inside a set a thousand wide.
    PointSet cluster = random_set(100, 10, 1000);
    const PointSet inner = random_set(60, 11, 1e-2, 321.5);
    cluster.xyz.insert(cluster.xyz.end(), inner.xyz.begin(), inner.xyz.end());
    cluster.name = "cluster";
    sets.push_back(cluster);
    return sets;
}

}  // namespace

TEST_CASE("delaunay3d: the exact referee accepts every family", "[delaunay3d]") {
    for (const PointSet& s : families()) {
        INFO(s.name);
        const SimplexMesh mesh = tetprobe::delaunay_cells_3d(s.xyz.data(), s.count());
        REQUIRE(referee::delaunay_failure_3d(mesh, s.xyz.data(), s.count()).empty());
        // Canonical form: increasing slots, but for the one swap that makes a cell positive.
        for (const auto& v : mesh.vertices) REQUIRE((v[0] != v[1] && std::max(v[0], v[1]) < v[2] && v[2] < v[3]));
    }
}

TEST_CASE("delaunay3d: the tessellation does not depend on the insertion order", "[delaunay3d]") {
    std::mt19937 rng(31);
    for (const PointSet& s : {lattice(4), sphere(5), small_integers(80, 2, 12), box_sides(120, 13), random_set(150, 14)}) {
        INFO(s.name);
        const auto expected = referee::sorted_cells(tetprobe::delaunay_cells_3d(s.xyz.data(), s.count()));
        for (int trial = 0; trial < 5; ++trial) {
            std::vector<uint32_t> order(s.count());
            for (uint32_t i = 0; i < s.count(); ++i) order[i] = i;
            std::shuffle(order.begin(), order.end(), rng);
            REQUIRE(referee::sorted_cells(tetprobe::delaunay_cells_3d(s.xyz.data(), s.count(), order)) == expected);
        }
    }
}

TEST_CASE("delaunay3d: TetGen builds the same cells for the same points in the same order", "[delaunay3d]") {
    for (const PointSet& s : families()) {
        INFO(s.name);
        const SimplexMesh core = tetprobe::delaunay_cells_3d(s.xyz.data(), s.count());
        const SimplexMesh tetgen = tetgen_cells(s);
        REQUIRE(referee::sorted_cells(tetgen) == referee::sorted_cells(core));
    }
}

TEST_CASE("delaunay3d: fuzzed degenerate sets: TetGen's cells are core's wherever TetGen's are Delaunay", "[delaunay3d]") {
    // Small-integer sets are full of cospherical and coplanar subsets. Wherever TetGen 1.5.0 answers
    // with a valid tessellation it must be core's; the sets where it does not are counted (and
    // printed), and core's own answer is always the referee's.
    std::mt19937 rng(37);
    int agree = 0, tetgen_failed = 0, tetgen_invalid = 0;
    const int trials = 1500;
    for (int trial = 0; trial < trials; ++trial) {
        const uint32_t n = 5 + uint32_t(rng() % 40);
        const int range = 1 + int(rng() % 3);
        if (uint32_t((2 * range + 1) * (2 * range + 1) * (2 * range + 1)) < n) continue;
        PointSet s = small_integers(n, range, uint32_t(rng()));
        if (trial % 2) {  // scaled and offset: the same ties in other floats
            for (float& x : s.xyz) x = x * 0.25f + 3.0f;
        }
        SimplexMesh core;
        try {
            core = tetprobe::delaunay_cells_3d(s.xyz.data(), s.count());
        } catch (const tetprobe::Error& e) {
            REQUIRE(e.status() == tetprobe::Status::degenerate);  // all coplanar
            continue;
        }
        INFO(s.name << " (" << trial << ")");
        REQUIRE(referee::delaunay_failure_3d(core, s.xyz.data(), s.count()).empty());
        SimplexMesh tetgen;
        try {
            tetgen = tetgen_cells(s);
        } catch (const tetprobe::Error&) {
            ++tetgen_failed;
            continue;
        }
        const std::string failure = referee::delaunay_failure_3d(tetgen, s.xyz.data(), s.count());
        if (!failure.empty()) {
            ++tetgen_invalid;
            WARN("TetGen's cells fail the referee on " << s.name << ": " << failure);
            continue;
        }
        REQUIRE(referee::sorted_cells(tetgen) == referee::sorted_cells(core));
        ++agree;
    }
    WARN("fuzzed degenerate sets: " << agree << " agree with TetGen, TetGen failed on " << tetgen_failed
                                    << ", gave an invalid tessellation on " << tetgen_invalid);
    REQUIRE(agree > trials / 2);
}

TEST_CASE("delaunay3d: duplicates, sets without volume and too few points are refused", "[delaunay3d]") {
    PointSet duplicate = random_set(20, 40);
    duplicate.add(duplicate.xyz[9], duplicate.xyz[10], duplicate.xyz[11]);
    try {
        tetprobe::delaunay_cells_3d(duplicate.xyz.data(), duplicate.count());
        FAIL("a duplicate was accepted");
    } catch (const tetprobe::Error& e) {
        REQUIRE(e.status() == tetprobe::Status::invalid_argument);
        REQUIRE(std::string(e.what()).find("probes 3 and 20") != std::string::npos);
    }
    PointSet flat;
    for (int i = 0; i < 30; ++i) flat.add(i % 7, i / 7, 2.5);
    REQUIRE_THROWS_AS(tetprobe::delaunay_cells_3d(flat.xyz.data(), flat.count()), tetprobe::Error);
    PointSet three;
    three.add(0, 0, 0), three.add(1, 0, 0), three.add(0, 1, 0);
    REQUIRE_THROWS_AS(tetprobe::delaunay_cells_3d(three.xyz.data(), three.count()), tetprobe::Error);
    const std::vector<uint32_t> bad_order = {0, 1, 1};
    REQUIRE_THROWS_AS(tetprobe::delaunay_cells_3d(three.xyz.data(), three.count(), bad_order), tetprobe::Error);
}

TEST_CASE("delaunay3d: the portable and the AVX2 kernels build the same cells", "[delaunay3d]") {
    // TP_NO_AVX2 selects the portable kernels at each call (as it does for the walk at load).
    for (const PointSet& s : {random_set(500, 50), lattice(5), sphere(9), box_sides(200, 51)}) {
        INFO(s.name);
        const auto chosen = referee::sorted_cells(tetprobe::delaunay_cells_3d(s.xyz.data(), s.count()));
        setenv("TP_NO_AVX2", "1", 1);
        const auto portable = referee::sorted_cells(tetprobe::delaunay_cells_3d(s.xyz.data(), s.count()));
        unsetenv("TP_NO_AVX2");
        REQUIRE(portable == chosen);
    }
}

TEST_CASE("delaunay3d: a cavity with hundreds of boundary vertices gives the same tessellation", "[delaunay3d]") {
    // The centre of an integer sphere inserted last is in conflict with every cell: its cavity's
    // boundary is the whole hull (beyond the direct table's 255 vertices, so the hashed pairing).
    PointSet s = sphere(45);
    REQUIRE(s.count() == 510);
    s.add(0, 0, 0);
    std::vector<uint32_t> centre_last(s.count());
    for (uint32_t i = 0; i < s.count(); ++i) centre_last[i] = i;
    const SimplexMesh mesh = tetprobe::delaunay_cells_3d(s.xyz.data(), s.count(), centre_last);
    REQUIRE(referee::delaunay_failure_3d(mesh, s.xyz.data(), s.count()).empty());
    REQUIRE(referee::sorted_cells(mesh) == referee::sorted_cells(tetprobe::delaunay_cells_3d(s.xyz.data(), s.count())));
    REQUIRE(referee::sorted_cells(mesh) == referee::sorted_cells(tetgen_cells(s)));
}
