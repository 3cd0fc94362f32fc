// Automatic probe placement: candidates obey the rules (checked against brute-force geometry) and stay in
// the space playable seeds reach, validation points cover the free volume, the result is deterministic
// for a seed and any thread count, a smaller target runs the same greedy rounds and at the target exchanges
// move probes where the light changes, placement beats random subsamples of the
// same candidates on a scene with a sharp shadow and reports the error a high-ray measurement finds,
// noise does not steer it, a large level places at half a metre, cancel and bad input; the selection
// itself gives a bright region beyond the hull of its first probes a probe early.
#include <catch2/catch.hpp>

#include "placement_scenes.h"

#include "bake/lighting_bake.h"
#include "bake/placement_signal.h"
#include "bake/probe_placement.h"
#include "bake/probe_selection.h"
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/store.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace tetprobe;
using namespace placement_test;

namespace {

using Point = std::tuple<float, float, float>;

std::multiset<Point> as_set(const std::vector<float>& positions) {
    std::multiset<Point> s;
    for (size_t i = 0; i + 2 < positions.size(); i += 3) s.insert({positions[i], positions[i + 1], positions[i + 2]});
    return s;
}

// A 6 x 3 x 6 room with a pillar in the middle, a low table, and a bright lamp in one corner.
Scene lit_room() {
    Scene scene;
    add_box(scene, {0, 0, 0}, {6, 3, 6}, false);
    add_box(scene, {2.5f, 0, 2.5f}, {3.5f, 3, 3.5f}, true);
    add_box(scene, {4.5f, 0, 0.5f}, {5.5f, 0.8f, 1.5f}, true);
    LightDescription lamp;
    lamp.position = {0.6f, 2.4f, 0.6f};
    lamp.intensity = 30.0f;
    scene.add_light(lamp);
    return scene;
}

bool in_solid(const float* p) {
    const bool pillar = p[0] > 2.5f && p[0] < 3.5f && p[2] > 2.5f && p[2] < 3.5f;
    const bool table = p[0] > 4.5f && p[0] < 5.5f && p[1] < 0.8f && p[2] > 0.5f && p[2] < 1.5f;
    return pillar || table;
}

PlacementSettings room_settings() {
    PlacementSettings s;
    s.rules.spacing = 0.75;
    s.rules.margin = 0.2;
    s.rays = 64;
    s.bounces = 1;
    s.threads = 2;
    s.seed = 5;
    s.error_bound = 0;
    return s;
}

// An 8 x 8 courtyard open to the sky: a floor and four 3 m walls, all one-sided, lit by a low sun whose
// shadow from the south wall cuts the air above the floor with a sharp edge, and a sky.
Scene courtyard() {
    Scene scene;
    add_floor(scene, 0, 8, 0, 8, 0);
    const float h = 3;
    // Walls facing in: quads wound so their front faces the courtyard.
    auto wall = [&](std::array<float, 3> a, std::array<float, 3> b, std::array<float, 3> c, std::array<float, 3> d) {
        const float v[12] = {a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2]};
        const uint32_t t[6] = {0, 1, 2, 0, 2, 3};
        scene.add_mesh(v, 4, t, 2, {material(false)}, nullptr);
    };
    wall({0, 0, 0}, {8, 0, 0}, {8, h, 0}, {0, h, 0});
    wall({8, 0, 8}, {0, 0, 8}, {0, h, 8}, {8, h, 8});
    wall({0, 0, 8}, {0, 0, 0}, {0, h, 0}, {0, h, 8});
    wall({8, 0, 0}, {8, 0, 8}, {8, h, 8}, {8, h, 0});
    LightDescription sun;
    sun.type = LightType::directional;
    sun.direction = {0.3f, -0.6f, 0.74f};
    sun.intensity = 3.0f;
    scene.add_light(sun);
    const float sky[3] = {0.25f, 0.3f, 0.4f};
    scene.set_sky_color(sky);
    return scene;
}

// Random free points of the courtyard's walkable band (its air from 0.1 to 2 m above the floor).
std::vector<float> courtyard_points(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> across(0.1f, 7.9f), up(0.1f, 2.0f);
    std::vector<float> points;
    for (size_t i = 0; i < count; ++i) points.insert(points.end(), {across(rng), up(rng), across(rng)});
    return points;
}

// The real-level benchmark's metric: RMS over points and the 6 axis normals of |interpolated - reference|
// luminance irradiance, relative to the reference's mean. Probes baked with 256 rays, the reference given.
double measured_error(const Scene& scene, const std::vector<float>& probes, const std::vector<float>& points,
                      const std::vector<float>& reference) {
    BakeSettings bake;
    bake.rays = 256;
    bake.bounces = 1;
    bake.seed = 99;
    bake.threads = 2;
    const std::vector<float> sh = bake_lighting(scene, probes, bake);
    const StoreData data = build_store_data(probes.data(), 12, sh.data(), 108, probes.size() / 3, BuildSettings{});
    const std::vector<uint8_t> blob = write_store_blob(data);
    const std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
    double sum = 0, mean = 0;
    const size_t n = points.size() / 3;
    for (size_t i = 0; i < n; ++i) {
        float interpolated[27];
        store->interpolate(&points[3 * i], nullptr, interpolated);
        double a[kSignalSize], b[kSignalSize];
        luminance6(interpolated, a);
        luminance6(&reference[27 * i], b);
        for (int k = 0; k < kSignalSize; ++k) sum += (a[k] - b[k]) * (a[k] - b[k]), mean += b[k];
    }
    mean /= double(kSignalSize * n);
    return std::sqrt(sum / double(kSignalSize * n)) / mean;
}

std::vector<float> pick(const std::vector<float>& positions, const std::vector<size_t>& indices) {
    std::vector<float> out;
    for (size_t i : indices) out.insert(out.end(), &positions[3 * i], &positions[3 * i] + 3);
    return out;
}

std::vector<size_t> random_indices(size_t count, size_t n, uint32_t seed) {
    std::vector<size_t> all(count);
    for (size_t i = 0; i < count; ++i) all[i] = i;
    std::shuffle(all.begin(), all.end(), std::mt19937(seed));
    all.resize(n);
    return all;
}

// The largest distance from a point to its nearest chosen probe.
double covering_radius(const std::vector<float>& points, const std::vector<float>& chosen) {
    double worst = 0;
    for (size_t i = 0; i < points.size() / 3; ++i) {
        double best = INFINITY;
        for (size_t j = 0; j < chosen.size() / 3; ++j) {
            double d = 0;
            for (int a = 0; a < 3; ++a) d += (points[3 * i + size_t(a)] - chosen[3 * j + size_t(a)]) * (points[3 * i + size_t(a)] - chosen[3 * j + size_t(a)]);
            best = std::min(best, d);
        }
        worst = std::max(worst, std::sqrt(best));
    }
    return worst;
}

Status status_of(const std::function<void()>& call, std::string* message = nullptr) {
    try {
        call();
    } catch (const Error& e) {
        if (message) *message = e.what();
        return e.status();
    }
    return Status::ok;
}

}  // namespace

TEST_CASE("placement candidates: outside geometry and clear of every surface by the margin", "[placement]") {
    const Scene scene = lit_room();
    CandidateRules rules;
    rules.spacing = 0.75;
    rules.margin = 0.2;
    const Candidates c = find_candidates(scene, rules, 1, 2, Progress{});
    CHECK(c.tested == 256);
    CHECK(candidate_bound(scene, rules) == 256);
    // Exactly the lattice points (8 x 4 x 8, centred on the room) that are outside the solids and at least
    // the margin from every surface.
    std::vector<float> expected;
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 8; ++x) {
                const float p[3] = {0.375f + 0.75f * x, 1.5f - 0.75f * 1.5f + 0.75f * y, 0.375f + 0.75f * z};
                if (!in_solid(p) && distance_to_scene(scene, p) >= rules.margin) expected.insert(expected.end(), p, p + 3);
            }
    CHECK(as_set(c.positions) == as_set(expected));
    CHECK(expected.size() / 3 > 100);
    // Each candidate stands for half a spacing up and down in the whole mode.
    REQUIRE(c.extents.size() == 2 * (c.positions.size() / 3));
    for (size_t i = 0; i < c.positions.size() / 3; ++i) {
        CHECK(c.extents[2 * i] == Approx(c.positions[3 * i + 1] - 0.375f));
        CHECK(c.extents[2 * i + 1] == Approx(c.positions[3 * i + 1] + 0.375f));
    }
}

TEST_CASE("placement candidates: walkable stands points across the band above every floor", "[placement]") {
    // The room with a table and a short pillar: floors at 0, on the table (0.8) and on the pillar (2).
    Scene scene;
    add_box(scene, {0, 0, 0}, {6, 3, 6}, false);
    add_box(scene, {2.5f, 0, 2.5f}, {3.5f, 2, 3.5f}, true);
    add_box(scene, {4.5f, 0, 0.5f}, {5.5f, 0.8f, 1.5f}, true);
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    rules.spacing = 0.75;
    rules.margin = 0.2;
    rules.walk_min_height = 0.0;
    rules.walk_max_height = 1.5;
    const Candidates c = find_candidates(scene, rules, 1, 2, Progress{});
    // Independently: per column, per floor, the band from the floor + 0.2 (the margin) to the lower of
    // floor + 1.5 and the surface above less the margin, in layers at most 0.75 apart, both ends included
    // (a ten-thousandth of a spacing inside).
    std::vector<float> expected;
    size_t before_tests = 0;
    for (int z = 0; z < 8; ++z)
        for (int x = 0; x < 8; ++x) {
            const float px = 0.375f + 0.75f * x, pz = 0.375f + 0.75f * z;
            const bool pillar = px > 2.5f && px < 3.5f && pz > 2.5f && pz < 3.5f;
            const bool table = px > 4.5f && px < 5.5f && pz > 0.5f && pz < 1.5f;
            std::vector<std::pair<float, float>> floors;  // floor and the surface above it
            if (pillar) floors.push_back({2.0f, 3.0f});
            if (table) floors.push_back({0.8f, 3.0f});
            floors.push_back({0.0f, pillar ? 2.0f : table ? 0.8f : 3.0f});
            for (const auto& [floor, ceiling] : floors) {
                const double inset = 0.75e-4;  // the band's ends a ten-thousandth of a spacing inside
                const double low = floor + 0.2 + inset, high = std::min(floor + 1.5, ceiling - 0.2) - inset;
                if (high < low) continue;
                const int layers = int(std::ceil((high - low) / 0.75 - 1e-9)) + 1;
                for (int k = 0; k < layers; ++k) {
                    const float p[3] = {px, float(layers == 1 ? low : low + (high - low) * k / (layers - 1)), pz};
                    ++before_tests;
                    const bool solid = (pillar && p[1] < 2.0f) || (table && p[1] < 0.8f);
                    if (!solid && distance_to_scene(scene, p) >= rules.margin) expected.insert(expected.end(), p, p + 3);
                }
            }
        }
    CHECK(c.tested == before_tests);
    CHECK(candidate_bound(scene, rules) == before_tests);
    REQUIRE(c.positions.size() == expected.size());
    const std::multiset<Point> got = as_set(c.positions), want = as_set(expected);
    auto g = got.begin();
    for (auto w = want.begin(); w != want.end(); ++w, ++g) {
        CHECK(std::get<0>(*g) == Approx(std::get<0>(*w)).margin(1e-5));
        CHECK(std::get<1>(*g) == Approx(std::get<1>(*w)).margin(1e-5));
        CHECK(std::get<2>(*g) == Approx(std::get<2>(*w)).margin(1e-5));
    }
    CHECK(expected.size() / 3 > 100);
}

TEST_CASE("placement candidates: walkable bands end below the ceiling, inside the room", "[placement]") {
    // A closed 6 x 3 x 6 room with a 2 x 2 crate 2 high: above the crate's top the band (0.1 to 2) ends at
    // 2.9 (the ceiling less the margin), so the crate's columns get two layers, 2.1 and 2.9.
    Scene scene;
    add_box(scene, {0, 0, 0}, {6, 3, 6}, false);
    add_box(scene, {2, 0, 2}, {4, 2, 4}, true);
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    const double ceiling = 3.0 - rules.margin;
    auto in_room = [&](const float* p) {
        return p[0] > 0 && p[0] < 6 && p[1] > 0 && double(p[1]) <= ceiling + 1e-6 && p[2] > 0 && p[2] < 6;
    };
    const Candidates c = find_candidates(scene, rules, 1, 2, Progress{});
    size_t on_crate = 0;
    for (size_t i = 0; i < c.positions.size() / 3; ++i) {
        CHECK(in_room(&c.positions[3 * i]));
        if (c.positions[3 * i + 1] > 2.0f) ++on_crate;
    }
    for (size_t i = 0; i < c.validation.size() / 3; ++i) CHECK(in_room(&c.validation[3 * i]));
    CHECK(on_crate == 4 * 2);                        // 2 x 2 columns over the crate, two layers each
    CHECK(c.positions.size() / 3 == 4 * 2 + 3 * 32);  // the floor's 32 columns: 0.1, 1.05, 2
}

TEST_CASE("placement candidates: a walkable band far taller than the scene still ends", "[placement]") {
    // The downward ray starts above the band's top: 1e4 above a 1 m room, the 1e-5 step past each hit
    // rounds away in float, and the room's ceiling (a face turned down, never a floor) was hit again
    // forever. Every candidate must still lie inside the room.
    Scene scene;
    add_box(scene, {0, 0, 0}, {1, 1, 1}, false);
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    rules.spacing = 0.5;
    rules.margin = 0.01;
    rules.walk_max_height = 1e4;
    const Candidates c = find_candidates(scene, rules, 1, 1, Progress{});
    CHECK(c.positions.size() / 3 == 4 * 3);  // 2 x 2 columns, the band 0.01 to 0.99 in three layers
    for (size_t i = 0; i < c.positions.size() / 3; ++i) {
        const float* p = &c.positions[3 * i];
        CHECK((p[0] > 0 && p[0] < 1 && p[1] > 0 && p[1] < 1 && p[2] > 0 && p[2] < 1));
    }
}

TEST_CASE("placement candidates: the whole mode stays within the scene's bounds", "[placement]") {
    // A closed room whose bounds are not a multiple of the spacing: no lattice point may leave them.
    Scene scene;
    add_box(scene, {0, 0, 0}, {5.3f, 2.9f, 4.1f}, false);
    CandidateRules rules;
    rules.margin = 0;
    const Candidates c = find_candidates(scene, rules, 1, 2, Progress{});
    CHECK(c.positions.size() / 3 == 5 * 2 * 4);
    for (size_t i = 0; i < c.positions.size() / 3; ++i) {
        const float* p = &c.positions[3 * i];
        CHECK((p[0] >= 0 && p[0] <= 5.3f && p[1] >= 0 && p[1] <= 2.9f && p[2] >= 0 && p[2] <= 4.1f));
    }
}

TEST_CASE("placement candidates: playable seeds keep the space they reach", "[placement]") {
    // Two closed rooms side by side, not connected: a seed in the first keeps only its candidates.
    Scene scene;
    add_box(scene, {0, 0, 0}, {4, 3, 4}, false);
    add_box(scene, {6, 0, 0}, {10, 3, 4}, false);
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    const Candidates all = find_candidates(scene, rules, 1, 2, Progress{});
    size_t first_room = 0;
    for (size_t i = 0; i < all.positions.size() / 3; ++i) first_room += all.positions[3 * i] < 5;
    REQUIRE(first_room > 0);
    REQUIRE(first_room < all.positions.size() / 3);
    CHECK(all.unreached == 0);

    const float seed[3] = {1.2f, 0.4f, 2.1f};
    scene.set_playable_seeds(seed, 1);
    const Candidates reached = find_candidates(scene, rules, 1, 2, Progress{});
    CHECK(reached.positions.size() / 3 == first_room);
    CHECK(reached.unreached == all.positions.size() / 3 - first_room);
    for (size_t i = 0; i < reached.positions.size() / 3; ++i) CHECK(reached.positions[3 * i] < 5);
    for (size_t i = 0; i < reached.validation.size() / 3; ++i) CHECK(reached.validation[3 * i] < 4);
    // A seed that sees no candidate within two spacings: a clear status naming the seeds.
    const float nowhere[3] = {50, 0.5f, 50};
    scene.set_playable_seeds(nowhere, 1);
    std::string message;
    CHECK(status_of([&] { find_candidates(scene, rules, 1, 2, Progress{}); }, &message) == Status::scene);
    CHECK(message.find("1 playable seeds") != std::string::npos);
}

TEST_CASE("placement validation points: free points over the candidates' volume, up to the walls", "[placement]") {
    const Scene scene = lit_room();
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    rules.spacing = 0.75;
    rules.margin = 0.2;
    const Candidates c = find_candidates(scene, rules, 3, 2, Progress{});
    const size_t candidates = c.positions.size() / 3, points = c.validation.size() / 3;
    // One per candidate below 1,024 candidates, a few lost to moves into geometry.
    CHECK(points <= candidates);
    CHECK(points > candidates * 3 / 4);
    size_t near_wall = 0;
    for (size_t i = 0; i < points; ++i) {
        const float* p = &c.validation[3 * i];
        CHECK_FALSE(in_solid(p));
        CHECK((p[0] > 0 && p[0] < 6 && p[1] > 0 && p[1] < 3 && p[2] > 0 && p[2] < 6));
        near_wall += distance_to_scene(scene, p) < rules.margin;
    }
    // The strip between the walls and the candidates (which keep the margin) is measured too.
    CHECK(near_wall > 0);
    // Another seed draws other points.
    CHECK(find_candidates(scene, rules, 4, 2, Progress{}).validation != c.validation);
}

TEST_CASE("placement validation points: walkable ones stand in the band above a floor, not over a drop", "[placement]") {
    // Open ground at 0 with a 4 m high platform over x < 6 (and a pillar raising the scene's top to 10):
    // the platform's edge candidates have no neighbour at their height beyond the edge, so their boxes
    // reach a spacing past it, over the ground 4 m and more below: outside the band, never a point.
    Scene scene;
    add_floor(scene, 0, 12, 0, 12, 0);
    add_box(scene, {0, 0, 0}, {6, 4, 12}, true);
    add_box(scene, {11, 0, 11}, {12, 10, 12}, true);
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    rules.spacing = 1;
    rules.margin = 0.1;
    rules.walk_min_height = 0;
    rules.walk_max_height = 2;
    const Candidates c = find_candidates(scene, rules, 5, 2, Progress{});
    size_t on_platform = 0, platform_edge = 0, ground = 0;
    for (size_t i = 0; i < c.validation.size() / 3; ++i) {
        const float* p = &c.validation[3 * i];
        const bool pillar = p[0] > 11 && p[2] > 11;
        REQUIRE_FALSE(pillar);
        const float floor = p[0] < 6 ? 4.0f : 0.0f;
        CHECK(p[1] - floor >= 0.1f);
        CHECK(p[1] - floor <= 2.0f);
        on_platform += floor == 4.0f;
        platform_edge += floor == 4.0f && p[0] > 5.5f;
        ground += floor == 0.0f;
    }
    CHECK(on_platform > 100);
    CHECK(ground > 100);
    CHECK(platform_edge > 0);  // the strip along the edge, beyond the last candidates, is still measured
}

TEST_CASE("placement: the same bytes for a seed on one thread and two; a smaller target after the same rounds",
          "[placement]") {
    const Scene scene = lit_room();
    PlacementSettings settings = room_settings();
    settings.target_count = 60;
    settings.threads = 1;
    const Placement one = place_probes(scene, settings);
    settings.threads = 2;
    const Placement two = place_probes(scene, settings);
    REQUIRE(one.positions.size() == 3 * 60);
    CHECK(std::memcmp(one.positions.data(), two.positions.data(), one.positions.size() * sizeof(float)) == 0);
    REQUIRE(one.curve.size() == two.curve.size());
    for (size_t i = 0; i < one.curve.size(); ++i) {
        CHECK(one.curve[i].probes == two.curve[i].probes);
        CHECK(one.curve[i].error == two.curve[i].error);
    }
    // The curve: counts increasing, ending at the target.
    REQUIRE(one.curve.size() >= 3);
    CHECK(one.curve.back().probes == 60);
    for (size_t i = 1; i < one.curve.size(); ++i) CHECK(one.curve[i].probes > one.curve[i - 1].probes);
    // A smaller target runs the same greedy rounds (the same curve up to its last point), then gets its
    // own exchanged set of that many.
    const size_t middle = one.curve.size() / 2;
    settings.target_count = one.curve[middle].probes;
    const Placement fewer = place_probes(scene, settings);
    REQUIRE(fewer.positions.size() == 3 * size_t(settings.target_count));
    REQUIRE(fewer.curve.size() == middle + 1);
    CHECK(fewer.curve.back().probes == settings.target_count);
    for (size_t i = 0; i < middle; ++i) {
        CHECK(fewer.curve[i].probes == one.curve[i].probes);
        CHECK(fewer.curve[i].error == one.curve[i].error);
    }
    // Another seed bakes other samples: still a valid placement of the same size.
    settings.seed = 6;
    settings.target_count = 60;
    CHECK(place_probes(scene, settings).positions.size() == 3 * 60);
}

TEST_CASE("placement: beats random subsamples of its candidates at a sharp shadow, and reports the error a "
          "high-ray measurement finds", "[placement]") {
    const Scene scene = courtyard();
    PlacementSettings settings;
    settings.rules.mode = PlacementMode::walkable;
    settings.rules.spacing = 0.5;
    settings.bounces = 1;
    settings.threads = 2;
    settings.seed = 3;
    settings.error_bound = 0;
    settings.target_count = 60;
    const Placement placed = place_probes(scene, settings);
    REQUIRE(placed.positions.size() == 3 * 60);

    const std::vector<float> points = courtyard_points(400, 11);
    BakeSettings reference_bake;
    reference_bake.rays = 1024;
    reference_bake.bounces = 1;
    reference_bake.seed = 12;
    reference_bake.threads = 2;
    const std::vector<float> reference = bake_lighting(scene, points, reference_bake);
    const double smart = measured_error(scene, placed.positions, points, reference);

    const Candidates all = find_candidates(scene, settings.rules, settings.seed, 2, Progress{});
    REQUIRE(all.positions.size() / 3 == placed.candidates);
    double random = 0;
    for (uint32_t seed : {1u, 2u, 3u})
        random += measured_error(scene, pick(all.positions, random_indices(placed.candidates, 60, seed)), points, reference) / 3;
    const double reported = placed.curve.back().error;
    WARN("60 of " << placed.candidates << " candidates: placed " << smart << " (reported " << reported
                  << "), random subsamples " << random);
    CHECK(smart < 0.8 * random);
    // The reported error is the measured one within 30%.
    CHECK(reported > 0.7 * smart);
    CHECK(reported < 1.3 * smart);
}

TEST_CASE("placement: noise does not steer it (a smooth field baked with few rays)", "[placement]") {
    // A wide floor under a uniform sky: the irradiance above its middle barely changes, but 4 rays per
    // candidate make every value noisy. The estimate must see no error, and the probes spread like a
    // lattice rather than chase the noise.
    Scene scene;
    add_box(scene, {-20, -1, -20}, {20, 0, 20}, true);  // the ground, a solid slab: its top is the floor
    add_box(scene, {19.9f, 0, 19.9f}, {20, 4, 20}, true);  // a thin pole: the scene's bounds reach above the band
    const float sky[3] = {0.3f, 0.3f, 0.3f};
    scene.set_sky_color(sky);
    PlacementSettings settings;
    settings.rules.mode = PlacementMode::walkable;
    settings.rules.spacing = 1;
    settings.rays = 4;
    settings.bounces = 1;
    settings.threads = 2;
    settings.seed = 2;
    settings.error_bound = 0;
    settings.target_count = 100;
    const Placement placed = place_probes(scene, settings);
    REQUIRE(placed.positions.size() == 3 * 100);
    // The candidates' own noise is large: the half bakes of one candidate differ by a fifth of the light.
    const Candidates all = find_candidates(scene, settings.rules, settings.seed, 2, Progress{});
    BakeSettings bake;
    bake.rays = 4;
    bake.bounces = 1;
    bake.threads = 2;
    const PointSignal signal = measure_signal(scene, all.positions, bake, Progress{});
    double noise = 0, mean = 0;
    for (size_t i = 0; i < signal.noise.size(); ++i) {
        noise += signal.noise[i] / signal.noise.size() / kSignalSize;
        for (int k = 0; k < kSignalSize; ++k) mean += signal.value[kSignalSize * i + size_t(k)] / signal.noise.size() / kSignalSize;
    }
    CHECK(std::sqrt(noise) / mean > 0.05);
    // No error is reported where none is (up to the floor's edges, far from most points).
    CHECK(placed.curve.back().error < 0.25 * std::sqrt(noise) / mean);
    // Spread: the farthest candidate from the probes is no farther than with random picks of the same count.
    double random = 0;
    for (uint32_t seed : {1u, 2u, 3u})
        random += covering_radius(all.positions, pick(all.positions, random_indices(all.positions.size() / 3, 100, seed))) / 3;
    const double spread = covering_radius(all.positions, placed.positions);
    WARN("covering radius: placed " << spread << ", random " << random);
    CHECK(spread < random);
}

TEST_CASE("placement: a 250 x 100 x 250 m level places at half a metre (memory grows with the candidates)",
          "[placement]") {
    // Walkways 4 m wide across a 250 m square, a 100 m mast at a corner: 250,000 columns and 40 million
    // lattice points over the bounds, of which only the walkways' bands are candidates.
    Scene scene;
    add_box(scene, {0, -1, 100}, {250, 0, 104}, true);
    add_box(scene, {123, 9, 0}, {127, 10, 250}, true);
    add_box(scene, {0, 0, 0}, {1, 100, 1}, true);
    LightDescription sun;
    sun.type = LightType::directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    scene.add_light(sun);
    PlacementSettings settings;
    settings.rules.mode = PlacementMode::walkable;
    settings.rules.spacing = 0.5;
    settings.rays = 2;
    settings.bounces = 0;
    settings.threads = 2;
    settings.error_bound = 0;
    settings.target_count = 300;
    const Placement placed = place_probes(scene, settings);
    REQUIRE(placed.positions.size() == 3 * 300);
    // Eight columns across each walkway, the band 0.1 to 2 in five layers; the crossing counted once.
    CHECK(placed.candidates >= 2 * 8 * 490 * 5);
    CHECK(placed.candidates <= 2 * 8 * 500 * 5);
    for (size_t i = 0; i < 300; ++i) {
        const float* p = &placed.positions[3 * i];
        const bool first = p[2] > 100 && p[2] < 104 && p[1] > 0 && p[1] <= 2;
        const bool second = p[0] > 123 && p[0] < 127 && p[1] > 10 && p[1] <= 12;
        CHECK((first || second));
    }
}

TEST_CASE("placement: cancelling in any stage stops with Status::cancelled", "[placement]") {
    const Scene scene = lit_room();
    // Target 40 is below the candidates and small enough for exchanges, so every stage runs.
    for (const char* stage : {"candidates", "bake", "select", "exchange"}) {
        PlacementSettings settings = room_settings();
        settings.target_count = 40;
        struct Cancel {
            const char* stage;
            bool reached = false;
        } cancel{stage};
        settings.progress.callback = [](void* user, float, const char* now) {
            auto* c = static_cast<Cancel*>(user);
            c->reached = c->reached || std::string(now) == c->stage;
            return c->reached ? 1 : 0;
        };
        settings.progress.user = &cancel;
        CHECK(status_of([&] { place_probes(scene, settings); }) == Status::cancelled);
        CHECK(cancel.reached);
    }
}

TEST_CASE("placement: bad input gets a clear status and a message naming the number", "[placement]") {
    const Scene scene = lit_room();
    std::string message;
    PlacementSettings s = room_settings();
    for (double spacing : {0.0, -1.0, double(NAN)}) {
        s.rules.spacing = spacing;
        CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::invalid_argument);
        CHECK(message.find("spacing must be positive") != std::string::npos);
    }
    s = room_settings();
    s.rules.margin = 100;
    CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::invalid_argument);
    CHECK(message.find("larger than the scene") != std::string::npos);
    s.rules.margin = 2.9;  // smaller than the scene, but no point of the room is that clear
    CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::degenerate);
    CHECK(message.find("no candidate") != std::string::npos);
    // A target above the candidates names both.
    s = room_settings();
    s.target_count = 10000;
    CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::invalid_argument);
    CHECK(message.find("target_count 10000 is more than the") != std::string::npos);
    // A spacing that would hold more than memory allows: refused with the count, before any test.
    s = room_settings();
    s.rules.spacing = 0.0005;
    CHECK(status_of([&] { placement_bound(scene, s); }, &message) == Status::invalid_argument);
    CHECK(message.find("raise the spacing") != std::string::npos);
    CHECK(message.find("8.64e+11 lattice points") != std::string::npos);  // 12,000 x 6,000 x 12,000
    // A spacing larger than the room: one lattice point, refused with the counts, never a silent single probe
    // (the C harness sees the "only N candidates" case).
    s = room_settings();
    s.rules.spacing = 1000;
    s.target_count = 1;
    CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::degenerate);
    CHECK(message.find("spacing 1000, 1 points tested") != std::string::npos);  // the one point is in the pillar
    CHECK(message.find("needs at least 4") != std::string::npos);
    // A walkable placement where nothing faces up: no floor, no candidate.
    Scene roofless;  // walls and a ceiling, no floor
    add_box(roofless, {0, 0, 0}, {4, 3, 4}, false);
    Scene no_floor;
    {
        const Mesh& box = roofless.meshes()[0];
        std::vector<uint32_t> kept;
        for (size_t t = 0; t < box.triangle_count(); ++t) {
            float lowest = INFINITY, highest = -INFINITY;
            for (int k = 0; k < 3; ++k) {
                const float y = box.vertices[3 * size_t(box.indices[3 * t + size_t(k)]) + 1];
                lowest = std::min(lowest, y), highest = std::max(highest, y);
            }
            if (highest > 0) kept.insert(kept.end(), &box.indices[3 * t], &box.indices[3 * t] + 3);
        }
        no_floor.add_mesh(box.vertices.data(), box.vertices.size() / 3, kept.data(), kept.size() / 3, {material(false)}, nullptr);
    }
    s = room_settings();
    s.rules.mode = PlacementMode::walkable;
    CHECK(status_of([&] { place_probes(no_floor, s); }, &message) == Status::degenerate);
    CHECK(message.find("not above a floor") != std::string::npos);
    // Two rays at least: the two half bakes measure the noise.
    s = room_settings();
    s.rays = 1;
    CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::invalid_argument);
    s = room_settings();
    s.rules.mode = PlacementMode::walkable;
    s.rules.walk_min_height = 2, s.rules.walk_max_height = 1;
    CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::invalid_argument);

    Scene open;  // only a two-sided sheet: nothing has an inside
    add_floor(open, 0, 4, 0, 4, 0, true);
    CHECK(status_of([&] { place_probes(open, room_settings()); }, &message) == Status::scene);
    CHECK(message.find("cannot be decided") != std::string::npos);
    Scene empty;
    CHECK(status_of([&] { place_probes(empty, room_settings()); }, &message) == Status::scene);
}

TEST_CASE("placement: a bright spot beyond the hull of the first probes, mixed with dark points, gets a probe",
          "[placement]") {
    // A 20 x 20 x 2 m slab of candidates, 1 m apart, holding a smooth bowl-shaped field (the cells inside
    // have insertions that surely gain, round after round), and up to a metre beyond its x = 20 face, near
    // one corner, a small region the farthest-point start leaves outside its hull: three bright points
    // right above the face and, farther out, dark ones. In that one outer cell no single insertion has a
    // trusted gain (the dark points would take the bright residual), so without the starved-cell
    // rule the region waits behind the trusted gains inside; with it the worst-missed bright point is
    // inserted in the first rounds.
    SignalPoints points;
    auto add = [&](float x, float y, float z, double value) {
        points.positions.insert(points.positions.end(), {x, y, z});
        for (int k = 0; k < kSignalSize; ++k) points.signal.value.push_back(float(value));
        points.signal.noise.push_back(1e-4f);
        points.counted.push_back(1);
    };
    auto field = [](double x, double y) { return 1.0 + 0.01 * ((x - 10) * (x - 10) + (y - 10) * (y - 10)); };
    for (int x = 0; x <= 20; ++x)
        for (int y = 0; y <= 20; ++y)
            for (int z = 0; z <= 2; ++z) add(float(x), float(y), float(z), field(x, y));
    const size_t region = points.counted.size();
    for (float y : {1.0f, 1.5f, 2.0f}) add(20.3f, y, 1.0f, field(20.3, y) + 10.0);
    const size_t bright_end = points.counted.size();
    for (float x : {20.6f, 20.9f})
        for (float y : {1.0f, 1.5f, 2.0f})
            for (float z : {0.8f, 1.0f, 1.2f}) add(x, y, z, field(x, y) - 0.5);
    SelectionSettings settings;
    settings.target_count = 30;  // three rounds: 16, 20, 25, 30
    settings.threads = 1;
    settings.exchange = false;   // the greedy's rounds alone: the first 16 are the start
    const Selection chosen = select_probes(points, points, settings, Progress{});
    REQUIRE(chosen.order.size() == 30);
    std::string order;
    for (uint32_t i : chosen.order) order += std::to_string(i) + " ";
    INFO("order: " << order);
    // The start (16 probes) leaves the whole region beyond its hull, in one outer cell.
    std::vector<float> start;
    for (size_t k = 0; k < 16; ++k) {
        const float* p = &points.positions[3 * size_t(chosen.order[k])];
        start.insert(start.end(), p, p + 3);
    }
    const std::vector<float> no_sh(27 * 16, 0.0f);
    const std::vector<uint8_t> blob = write_store_blob(build_store_data(start.data(), 12, no_sh.data(), 108, 16, BuildSettings{}));
    const std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
    const size_t in_region = points.counted.size() - region;
    std::vector<int32_t> cells(in_region, -1);
    std::vector<uint32_t> probes(4 * in_region);
    std::vector<float> weights(4 * in_region);
    size_t first_outside = 0;
    store->weights_batch(in_region, &points.positions[3 * region], 12, cells.data(), 4, probes.data(), 16, weights.data(), 16,
                         BatchSettings{}, &first_outside);
    REQUIRE(cells[0] >= int32_t(store->header().inner_cell_count));
    for (int32_t c : cells) REQUIRE(c == cells[0]);
    // By 30 probes a bright point has one (without the rule the region's first probe, a dark point, is
    // the 593rd and its first bright one the 663rd).
    size_t bright = 0;
    for (uint32_t i : chosen.order) bright += i >= region && i < bright_end;
    CHECK(bright >= 1);
}

TEST_CASE("placement: at the target, probes the spread start left where the light is flat move to where it changes",
          "[placement]") {
    // A 21 x 21 x 3 slab of candidates, 1 m apart, with a flat field but for one bright bump (about 2 m
    // wide) off the centre. A target of 16 is the farthest-point start alone: spread over the slab for
    // distance only, it has one probe near the bump, and the greedy never takes a probe back. The
    // exchange at the target moves probes from the flat field (where one more or less costs nothing: a
    // constant is interpolated exactly) to the bump.
    SignalPoints points;
    const double centre[3] = {5.3, 13.6, 1.0};
    for (int x = 0; x <= 20; ++x)
        for (int y = 0; y <= 20; ++y)
            for (int z = 0; z <= 2; ++z) {
                points.positions.insert(points.positions.end(), {float(x), float(y), float(z)});
                const double d2 = (x - centre[0]) * (x - centre[0]) + (y - centre[1]) * (y - centre[1]) + (z - centre[2]) * (z - centre[2]);
                for (int k = 0; k < kSignalSize; ++k) points.signal.value.push_back(float(1.0 + 4.0 * std::exp(-d2 / 2.0)));
                points.signal.noise.push_back(1e-4f);
                points.counted.push_back(1);
            }
    SelectionSettings settings;
    settings.target_count = 16;
    settings.threads = 2;
    const Selection chosen = select_probes(points, points, settings, Progress{});
    REQUIRE(chosen.order.size() == 16);
    REQUIRE(chosen.curve.size() == 1);
    std::string order;
    for (uint32_t i : chosen.order) order += std::to_string(i) + " ";
    INFO("order: " << order << " error " << chosen.curve.back().error);
    // The start alone has one probe within 3 m of the bump's centre (at 1.75 m; the others 5.5 m and
    // more away); exchanged, at least three.
    size_t near = 0;
    for (uint32_t i : chosen.order) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) d2 += (points.positions[3 * size_t(i) + size_t(a)] - centre[a]) * (points.positions[3 * size_t(i) + size_t(a)] - centre[a]);
        near += d2 <= 3.0 * 3.0;
    }
    CHECK(near >= 3);
    // The same set on one thread.
    settings.threads = 1;
    CHECK(select_probes(points, points, settings, Progress{}).order == chosen.order);
}
