// The exact Delaunay triangulation of flat sets (core/delaunay2d.h): the exact referee accepts it on
// random, grid, cocircular and collinear-sided sets in each axis plane; it does not depend on the
// insertion order; it is the triangulation TetGen 1.5 gives the baker under an apex
// (bake/flat_delaunay.cpp), degenerate sets included; bad input is refused.
#include "delaunay_referee.h"

#include "bake/flat_delaunay.h"
#include "core/canonical_cells.h"
#include "core/delaunay2d.h"
#include "core/error.h"

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

using tetprobe::SimplexMesh;

namespace {

// A flat set: plane coordinates (u, v) placed in the two coordinates other than axis, the third fixed.
struct FlatSet {
    std::string name;
    uint32_t axis = 2;
    std::vector<float> uv;
    uint32_t count() const { return uint32_t(uv.size() / 2); }
    void add(double u, double v) {
        uv.push_back(float(u));
        uv.push_back(float(v));
    }
    std::vector<float> xyz() const {
        std::vector<float> out;
        const uint32_t a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;
        for (uint32_t i = 0; i < count(); ++i) {
            float p[3] = {2.5f, 2.5f, 2.5f};
            p[a] = uv[2 * i];
            p[b] = uv[2 * i + 1];
            out.insert(out.end(), p, p + 3);
        }
        return out;
    }
};

FlatSet random_flat(uint32_t n, uint32_t seed, uint32_t axis, double scale = 1) {
    FlatSet s{"random flat " + std::to_string(n) + " axis " + std::to_string(axis), axis, {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-scale, scale);
    for (uint32_t i = 0; i < n; ++i) s.add(u(rng), u(rng));
    return s;
}

FlatSet grid(int n, double spacing, uint32_t axis) {
    FlatSet s{"grid " + std::to_string(n), axis, {}};
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) s.add(x * spacing, y * spacing);
    return s;
}

FlatSet circle_points(int r) {
    FlatSet s{"integer circle " + std::to_string(r), 1, {}};
    for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
            if (x * x + y * y == r * r) s.add(x, y);
    s.add(0, 0);
    return s;
}

FlatSet small_integers(uint32_t n, int range, uint32_t seed) {
    FlatSet s{"small integers " + std::to_string(n) + " in " + std::to_string(range) + " seed " + std::to_string(seed), 0, {}};
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> u(-range, range);
    std::vector<std::pair<int, int>> seen;
    while (s.count() < n) {
        const std::pair<int, int> p = {u(rng), u(rng)};
        if (std::find(seen.begin(), seen.end(), p) != seen.end()) continue;
        seen.push_back(p);
        s.add(p.first, p.second);
    }
    return s;
}

SimplexMesh tetgen_cells(const FlatSet& s) {
    std::vector<Eigen::Vector2d> points(s.count());
    for (size_t j = 0; j < points.size(); ++j) points[j] = Eigen::Vector2d(s.uv[2 * j], s.uv[2 * j + 1]);
    SimplexMesh mesh = tetprobe::delaunay_triangulate_plane(points);
    const std::vector<float> xyz = s.xyz();
    tetprobe::canonicalise_cells(mesh, xyz.data(), s.axis);
    return mesh;
}

std::vector<FlatSet> families() {
    return {random_flat(200, 1, 0), random_flat(200, 2, 1, 1e-3), random_flat(200, 3, 2, 1e4), grid(6, 1, 2),
            grid(9, 0.3, 0),        circle_points(5),             circle_points(25),              small_integers(40, 3, 4)};
}

}  // namespace

TEST_CASE("delaunay2d: the exact referee accepts every family", "[delaunay2d]") {
    for (const FlatSet& s : families()) {
        INFO(s.name);
        const std::vector<float> xyz = s.xyz();
        const SimplexMesh mesh = tetprobe::delaunay_cells_2d(xyz.data(), s.count(), s.axis);
        REQUIRE(referee::delaunay_failure_2d(mesh, s.uv.data(), s.count()).empty());
        for (const auto& v : mesh.vertices) REQUIRE((v[0] != v[1] && std::max(v[0], v[1]) < v[2] && v[3] == tetprobe::kNone32));
    }
}

TEST_CASE("delaunay2d: the triangulation does not depend on the insertion order", "[delaunay2d]") {
    std::mt19937 rng(5);
    for (const FlatSet& s : {grid(5, 1, 2), circle_points(5), small_integers(20, 2, 6), random_flat(100, 7, 1)}) {
        INFO(s.name);
        const std::vector<float> xyz = s.xyz();
        const auto expected = referee::sorted_cells(tetprobe::delaunay_cells_2d(xyz.data(), s.count(), s.axis));
        for (int trial = 0; trial < 5; ++trial) {
            std::vector<uint32_t> order(s.count());
            for (uint32_t i = 0; i < s.count(); ++i) order[i] = i;
            std::shuffle(order.begin(), order.end(), rng);
            REQUIRE(referee::sorted_cells(tetprobe::delaunay_cells_2d(xyz.data(), s.count(), s.axis, order)) == expected);
        }
    }
}

TEST_CASE("delaunay2d: TetGen's flat triangulation is core's for the same points in the same order", "[delaunay2d]") {
    for (const FlatSet& s : families()) {
        INFO(s.name);
        const std::vector<float> xyz = s.xyz();
        REQUIRE(referee::sorted_cells(tetgen_cells(s)) ==
                referee::sorted_cells(tetprobe::delaunay_cells_2d(xyz.data(), s.count(), s.axis)));
    }
}

TEST_CASE("delaunay2d: fuzzed degenerate flat sets: TetGen's triangles are core's wherever TetGen's are Delaunay", "[delaunay2d]") {
    std::mt19937 rng(9);
    int agree = 0, tetgen_failed = 0, tetgen_invalid = 0;
    const int trials = 1500;
    for (int trial = 0; trial < trials; ++trial) {
        const int range = 1 + int(rng() % 4);
        const uint32_t n = 4 + uint32_t(rng() % std::min(40, (2 * range + 1) * (2 * range + 1) - 4));
        FlatSet s = small_integers(n, range, uint32_t(rng()));
        const std::vector<float> xyz = s.xyz();
        SimplexMesh core;
        try {
            core = tetprobe::delaunay_cells_2d(xyz.data(), s.count(), s.axis);
        } catch (const tetprobe::Error& e) {
            REQUIRE(e.status() == tetprobe::Status::degenerate);  // all collinear
            continue;
        }
        INFO(s.name << " (" << trial << ")");
        REQUIRE(referee::delaunay_failure_2d(core, s.uv.data(), s.count()).empty());
        SimplexMesh tetgen;
        try {
            tetgen = tetgen_cells(s);
        } catch (const tetprobe::Error&) {
            ++tetgen_failed;
            continue;
        }
        const std::string failure = referee::delaunay_failure_2d(tetgen, s.uv.data(), s.count());
        if (!failure.empty()) {
            ++tetgen_invalid;
            WARN("TetGen's triangles fail the referee on " << s.name << ": " << failure);
            continue;
        }
        REQUIRE(referee::sorted_cells(tetgen) == referee::sorted_cells(core));
        ++agree;
    }
    WARN("fuzzed degenerate flat sets: " << agree << " agree with TetGen, TetGen failed on " << tetgen_failed
                                         << ", gave an invalid triangulation on " << tetgen_invalid);
    REQUIRE(agree > trials / 2);
}

TEST_CASE("delaunay2d: duplicates in the plane, collinear sets and too few probes are refused", "[delaunay2d]") {
    FlatSet duplicate = random_flat(10, 11, 2);
    duplicate.add(duplicate.uv[4], duplicate.uv[5]);
    std::vector<float> xyz = duplicate.xyz();
    try {
        tetprobe::delaunay_cells_2d(xyz.data(), duplicate.count(), duplicate.axis);
        FAIL("a duplicate was accepted");
    } catch (const tetprobe::Error& e) {
        REQUIRE(e.status() == tetprobe::Status::invalid_argument);
        REQUIRE(std::string(e.what()).find("probes 2 and 10") != std::string::npos);
    }
    FlatSet line{"line", 2, {}};
    for (int i = 0; i < 10; ++i) line.add(i, 2 * i);
    xyz = line.xyz();
    REQUIRE_THROWS_AS(tetprobe::delaunay_cells_2d(xyz.data(), line.count(), line.axis), tetprobe::Error);
    FlatSet two{"two", 2, {}};
    two.add(0, 0), two.add(1, 1);
    xyz = two.xyz();
    REQUIRE_THROWS_AS(tetprobe::delaunay_cells_2d(xyz.data(), two.count(), two.axis), tetprobe::Error);
}
