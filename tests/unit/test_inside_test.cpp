// Inside geometry: the inside test on shapes whose inside is known analytically, the nearest surface
// point against a brute-force distance, and fixing a user's inside probes (drop, push out).
#include <catch2/catch.hpp>

#include "placement_scenes.h"

#include "bake/inside_probe_fix.h"
#include "bake/inside_test.h"
#include "bake/ray_caster.h"
#include "core/error.h"

#include <random>

using namespace tetprobe;
using namespace placement_test;

namespace {

// Uniform random points in [lo, hi]^3, fixed seed.
std::vector<float> random_points(size_t count, float lo, float hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    std::vector<float> p(3 * count);
    for (float& x : p) x = u(rng);
    return p;
}

std::vector<uint32_t> expected_inside(const std::vector<float>& points, bool (*inside)(const float*)) {
    std::vector<uint32_t> indices;
    for (size_t i = 0; i < points.size() / 3; ++i)
        if (inside(&points[3 * i])) indices.push_back(uint32_t(i));
    return indices;
}

// Points further than `gap` from the shape's surface, so the float geometry cannot blur the answer.
std::vector<float> away_from(const std::vector<float>& points, double (*surface_distance)(const float*), double gap) {
    std::vector<float> kept;
    for (size_t i = 0; i < points.size() / 3; ++i)
        if (surface_distance(&points[3 * i]) > gap) kept.insert(kept.end(), &points[3 * i], &points[3 * i] + 3);
    return kept;
}

bool in_box(const float* p) { return p[0] > 1 && p[0] < 3 && p[1] > 1 && p[1] < 2 && p[2] > 1 && p[2] < 4; }
double box_surface_distance(const float* p) {
    double d = INFINITY;
    const double lo[3] = {1, 1, 1}, hi[3] = {3, 2, 4};
    for (int a = 0; a < 3; ++a) d = std::min({d, std::abs(p[a] - lo[a]), std::abs(p[a] - hi[a])});
    return d;
}

bool in_sphere(const float* p) {
    const double dx = p[0] - 2, dy = p[1] - 2, dz = p[2] - 2;
    return dx * dx + dy * dy + dz * dz < 1.5 * 1.5;
}
double sphere_surface_distance(const float* p) {
    const double dx = p[0] - 2, dy = p[1] - 2, dz = p[2] - 2;
    return std::abs(std::sqrt(dx * dx + dy * dy + dz * dz) - 1.5);
}

}  // namespace

TEST_CASE("inside test: a closed box, one-sided or two-sided, is solid inside", "[inside]") {
    for (bool two_sided : {false, true}) {
        Scene scene;
        add_box(scene, {1, 1, 1}, {3, 2, 4}, true, two_sided);
        const std::vector<float> points = away_from(random_points(3000, 0, 5, 7), box_surface_distance, 1e-3);
        const std::vector<uint32_t> found = find_inside_probes(scene, points, 2);
        CHECK(found.size() > 100);
        CHECK(found == expected_inside(points, in_box));
    }
}

TEST_CASE("inside test: a closed two-sided box wound inward is still solid inside", "[inside]") {
    Scene scene;
    add_box(scene, {1, 1, 1}, {3, 2, 4}, false, true);
    const std::vector<float> points = away_from(random_points(1000, 0, 5, 8), box_surface_distance, 1e-3);
    CHECK(find_inside_probes(scene, points, 1) == expected_inside(points, in_box));
}

TEST_CASE("inside test: a sphere-ish mesh", "[inside]") {
    Scene scene;
    add_sphere(scene, {2, 2, 2}, 1.5f);
    // Facets lie up to 1.5 (1 - cos(pi/24)) = 0.013 inside the sphere; stay clear of that shell.
    const std::vector<float> points = away_from(random_points(3000, 0, 4, 9), sphere_surface_distance, 0.02);
    const std::vector<uint32_t> found = find_inside_probes(scene, points, 2);
    CHECK(found.size() > 500);
    CHECK(found == expected_inside(points, in_sphere));
}

TEST_CASE("inside test: a room (one-sided box facing in) has nothing inside, its walls' backs do", "[inside]") {
    Scene scene;
    add_box(scene, {0, 0, 0}, {4, 3, 4}, false);
    const std::vector<float> points = away_from(random_points(2000, -2, 6, 10), [](const float* p) {
        double d = INFINITY;
        for (int a = 0; a < 3; ++a) d = std::min({d, std::abs(double(p[a])), std::abs(p[a] - (a == 1 ? 3.0 : 4.0))});
        return d;
    }, 1e-3);
    // Outside the room only rays toward it (fewer than half) meet a wall's back: nothing is inside.
    CHECK(find_inside_probes(scene, points, 2).empty());
}

TEST_CASE("inside test: open two-sided geometry cannot decide, and says so", "[inside]") {
    Scene scene;
    add_floor(scene, 0, 4, 0, 4, 0, true);
    const std::vector<float> points = {1, 1, 1};
    try {
        find_inside_probes(scene, points, 1);
        FAIL("expected an error");
    } catch (const Error& e) {
        CHECK(e.status() == Status::scene);
        CHECK(std::string(e.what()).find("two-sided and open") != std::string::npos);
    }
    bool decided = true;
    CHECK(find_inside_probes(scene, points, 1, &decided).empty());
    CHECK_FALSE(decided);
    // One-sided, the same quad has a solid back: now the test can decide (the point above is outside).
    Scene one_sided;
    add_floor(one_sided, 0, 4, 0, 4, 0, false);
    CHECK(find_inside_probes(one_sided, points, 1, &decided).empty());
    CHECK(decided);
}

TEST_CASE("nearest surface: Embree's point query agrees with a brute-force distance", "[inside]") {
    Scene scene;
    add_box(scene, {0, 0, 0}, {4, 3, 4}, false);
    add_sphere(scene, {2, 1, 2}, 0.7f);
    add_box(scene, {0.5f, 0, 0.5f}, {1.2f, 2.0f, 1.0f}, true);
    const double origin[3] = {0.25, -0.5, 0.125};
    const RayCaster caster(scene, origin);
    const std::vector<float> points = random_points(500, -0.5f, 4.5f, 11);
    for (size_t i = 0; i < points.size() / 3; ++i) {
        const float* p = &points[3 * i];
        const float local[3] = {float(p[0] - origin[0]), float(p[1] - origin[1]), float(p[2] - origin[2])};
        SurfacePoint nearest;
        REQUIRE(caster.nearest_surface(local, INFINITY, &nearest));
        CHECK(nearest.distance == Approx(distance_to_scene(scene, p)).margin(1e-5));
        // With a radius below the distance nothing is found.
        CHECK_FALSE(caster.nearest_surface(local, nearest.distance * 0.99f, &nearest));
    }
}

TEST_CASE("inside probes: drop keeps the others in order, push moves the inside ones out by the margin", "[inside]") {
    // A room with a 0.4 thick wall across it (a solid box) and a pillar.
    Scene scene;
    add_box(scene, {0, 0, 0}, {6, 3, 4}, false);
    add_box(scene, {2.8f, 0, 0}, {3.2f, 3, 4}, true);
    add_box(scene, {4.5f, 0, 1.5f}, {5.5f, 3, 2.5f}, true);
    const std::vector<float> probes = {1, 1, 1,   3.0f, 1.5f, 2,   2.9f, 0.5f, 3.5f,  5, 2, 2,   5.2f, 1, 1.9f,  1.5f, 2, 3};
    CHECK(find_inside_probes(scene, probes, 1) == std::vector<uint32_t>{1, 2, 3, 4});

    const std::vector<float> dropped = fix_inside_probes(scene, probes, InsideFix::drop, 0.1, 2);
    CHECK(dropped == std::vector<float>{1, 1, 1, 1.5f, 2, 3});

    const double margin = 0.15;
    const std::vector<float> pushed = fix_inside_probes(scene, probes, InsideFix::push, margin, 2);
    REQUIRE(pushed.size() == probes.size());
    CHECK(find_inside_probes(scene, pushed, 1).empty());
    // Distance from each inside probe to the nearest face of its solid.
    const double depth[6] = {0, 0.2, 0.1, 0.5, 0.3, 0};
    for (size_t i = 0; i < probes.size() / 3; ++i) {
        const float* p = &pushed[3 * i];
        if (i == 0 || i == 5) {
            CHECK(std::equal(p, p + 3, &probes[3 * i]));  // outside probes stay where they were
            continue;
        }
        CHECK(distance_to_scene(scene, p) >= margin);
        // Each moved straight through the nearest face of its solid, to just beyond the margin.
        const double moved = std::sqrt((p[0] - probes[3 * i]) * (p[0] - probes[3 * i]) +
                                       (p[1] - probes[3 * i + 1]) * (p[1] - probes[3 * i + 1]) +
                                       (p[2] - probes[3 * i + 2]) * (p[2] - probes[3 * i + 2]));
        CHECK(moved == Approx(depth[i] + margin).margin(0.01));
    }
}

TEST_CASE("inside probes: a probe with no free point near it is an error naming it", "[inside]") {
    // A solid box in a room so small that no point of it is 1 from every surface.
    Scene scene;
    add_box(scene, {-0.5f, -0.5f, -0.5f}, {1.5f, 1.5f, 1.5f}, false);
    add_box(scene, {0, 0, 0}, {1, 1, 1}, true);
    const std::vector<float> probes = {0.5f, 0.5f, 0.5f};
    CHECK(fix_inside_probes(scene, probes, InsideFix::push, 0.2, 1) != probes);  // a small margin fits
    try {
        fix_inside_probes(scene, probes, InsideFix::push, 1.0, 1);
        FAIL("expected an error");
    } catch (const Error& e) {
        CHECK(e.status() == Status::scene);
        CHECK(std::string(e.what()).find("probe 0") != std::string::npos);
    }
    CHECK_THROWS_AS(fix_inside_probes(scene, probes, InsideFix::push, -1.0, 1), Error);
}
