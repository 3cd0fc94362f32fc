// Automatic probe placement: candidates obey the rules (checked against brute-force geometry), the
// result is deterministic for a seed and any thread count, pruning beats a uniform subsample of the
// same size on a scene with a light gradient, the error bound stops it, cancel and bad input.
#include <catch2/catch.hpp>

#include "placement_scenes.h"

#include "bake/lighting_bake.h"
#include "bake/probe_placement.h"
#include "bake/probe_pruning.h"
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/store.h"

#include <cstring>
#include <random>
#include <string>
#include <utility>

using namespace tetprobe;
using namespace placement_test;

namespace {

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

// The candidate grid of the room at spacing 0.75, written out independently: 8 x 4 x 8 points.
std::vector<float> room_grid(float y_extent = 3.0f) {
    std::vector<float> grid;
    const int ny = int(y_extent / 0.75f);
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < 8; ++x) {
                grid.push_back(0.375f + 0.75f * x);
                grid.push_back(y_extent / 2 - 0.75f * (ny - 1) / 2.0f + 0.75f * y);
                grid.push_back(0.375f + 0.75f * z);
            }
    return grid;
}

PlacementSettings room_settings() {
    PlacementSettings s;
    s.rules.spacing = 0.75;
    s.rules.margin = 0.2;
    s.rays = 64;
    s.bounces = 1;
    s.threads = 2;
    s.seed = 5;
    return s;
}

// Mean over `points` of the relative irradiance error (RMS over normals and channels, over the
// reference's own) of the store built from the probes at `positions`, both baked alike.
double true_error(const Scene& scene, const std::vector<float>& positions, const std::vector<float>& points) {
    BakeSettings bake;
    bake.rays = 256;
    bake.bounces = 1;
    bake.seed = 99;
    bake.threads = 2;
    const std::vector<float> sh = bake_lighting(scene, positions, bake);
    const std::vector<float> reference = bake_lighting(scene, points, bake);
    const StoreData data = build_store_data(positions.data(), 12, sh.data(), 108, positions.size() / 3, BuildSettings{});
    const std::vector<uint8_t> blob = write_store_blob(data);
    const std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
    double sum = 0;
    for (size_t i = 0; i < points.size() / 3; ++i) {
        float interpolated[27];
        store->interpolate(&points[3 * i], nullptr, interpolated);
        double a[27], b[27], d[27];
        irradiance_coefficients(interpolated, a);
        irradiance_coefficients(&reference[27 * i], b);
        for (int k = 0; k < 27; ++k) d[k] = a[k] - b[k];
        sum += irradiance_rms(d) / irradiance_rms(b);
    }
    return sum / double(points.size() / 3);
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
    const Candidates c = find_candidates(scene, rules, 2, Progress{});
    CHECK(c.grid_points == 256);
    CHECK(candidate_bound(scene, rules) == 256);
    // Exactly the grid points that are outside the solids and at least the margin from every surface.
    const std::vector<float> grid = room_grid();
    std::vector<float> expected;
    for (size_t i = 0; i < grid.size() / 3; ++i)
        if (!in_solid(&grid[3 * i]) && distance_to_scene(scene, &grid[3 * i]) >= rules.margin)
            expected.insert(expected.end(), &grid[3 * i], &grid[3 * i] + 3);
    REQUIRE(c.positions.size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) CHECK(c.positions[i] == Approx(expected[i]).margin(1e-6));
    CHECK(expected.size() / 3 > 100);
    // Held-out points obey the same rules.
    CHECK(c.held_out.size() / 3 > 50);
    for (size_t i = 0; i < c.held_out.size() / 3; ++i) {
        CHECK_FALSE(in_solid(&c.held_out[3 * i]));
        CHECK(distance_to_scene(scene, &c.held_out[3 * i]) >= rules.margin);
    }
}

TEST_CASE("placement candidates: walkable stands points across a band above every floor", "[placement]") {
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
    rules.walk_max_height = 1.5;  // two layers: 0.375 and 1.125 above each floor
    const Candidates c = find_candidates(scene, rules, 2, Progress{});
    std::vector<float> expected;
    size_t before_tests = 0;
    for (int z = 0; z < 8; ++z)
        for (int x = 0; x < 8; ++x) {
            const float px = 0.375f + 0.75f * x, pz = 0.375f + 0.75f * z;
            const bool pillar = px > 2.5f && px < 3.5f && pz > 2.5f && pz < 3.5f;
            const bool table = px > 4.5f && px < 5.5f && pz > 0.5f && pz < 1.5f;
            std::vector<std::pair<float, float>> floors;  // floor and the surface above it, from the top down
            if (pillar) floors.push_back({2.0f, 3.0f});
            if (table) floors.push_back({0.8f, 3.0f});
            floors.push_back({0.0f, pillar ? 2.0f : table ? 0.8f : 3.0f});
            for (const auto& [floor, ceiling] : floors)
                for (float h : {0.375f, 1.125f}) {
                    const float p[3] = {px, floor + h, pz};
                    if (double(p[1]) > double(ceiling) - rules.margin) continue;  // the band ends below the ceiling
                    ++before_tests;
                    const bool solid = (px > 2.5f && px < 3.5f && pz > 2.5f && pz < 3.5f && p[1] < 2.0f) ||
                                       (px > 4.5f && px < 5.5f && pz > 0.5f && pz < 1.5f && p[1] < 0.8f);
                    if (!solid && p[1] < 3.0f && distance_to_scene(scene, p) >= rules.margin)
                        expected.insert(expected.end(), p, p + 3);
                }
        }
    CHECK(c.grid_points == before_tests);
    CHECK(candidate_bound(scene, rules) == before_tests);
    REQUIRE(c.positions.size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) CHECK(c.positions[i] == Approx(expected[i]).margin(1e-5));
    CHECK(expected.size() / 3 > 100);
}

TEST_CASE("placement candidates: walkable bands end below the ceiling, inside the room", "[placement]") {
    // A closed 6 x 3 x 6 room with a 2 x 2 crate 2 high: above the crate's top the default band
    // (0..2 at spacing 1: 0.5 and 1.5 above a floor) would reach 3.5, above the roof.
    Scene scene;
    add_box(scene, {0, 0, 0}, {6, 3, 6}, false);
    add_box(scene, {2, 0, 2}, {4, 2, 4}, true);
    LightDescription lamp;
    lamp.position = {0.6f, 2.4f, 0.6f};
    lamp.intensity = 30.0f;
    scene.add_light(lamp);
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    const double ceiling = 3.0 - rules.margin;
    auto in_room = [&](const float* p) {
        return p[0] > 0 && p[0] < 6 && p[1] > 0 && double(p[1]) <= ceiling && p[2] > 0 && p[2] < 6;
    };
    const Candidates c = find_candidates(scene, rules, 2, Progress{});
    size_t on_crate = 0;
    for (size_t i = 0; i < c.positions.size() / 3; ++i) {
        CHECK(in_room(&c.positions[3 * i]));
        if (c.positions[3 * i + 1] == 2.5f) ++on_crate;
    }
    for (size_t i = 0; i < c.held_out.size() / 3; ++i) CHECK(in_room(&c.held_out[3 * i]));
    CHECK(on_crate == 4);                        // the crate's top keeps its lower layer
    CHECK(c.positions.size() / 3 == 4 + 2 * 32);  // and the floor both layers around the crate
    CHECK(c.grid_points == 4 + 2 * 36);           // the upper layer above the crate is never a candidate

    PlacementSettings settings;
    settings.rules = rules;
    settings.rays = 32;
    settings.threads = 2;
    settings.error_bound = 0;
    const Placement placed = place_probes(scene, settings);
    REQUIRE(placed.positions.size() / 3 >= 4);
    for (size_t i = 0; i < placed.positions.size() / 3; ++i) CHECK(in_room(&placed.positions[3 * i]));
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
    const Candidates c = find_candidates(scene, rules, 1, Progress{});
    CHECK(c.positions.size() / 3 == 8);  // two layers (0.25 and 0.75 above the floor) in each of 2 x 2 columns
    for (size_t i = 0; i < c.positions.size() / 3; ++i) {
        const float* p = &c.positions[3 * i];
        CHECK((p[0] > 0 && p[0] < 1 && p[1] > 0 && p[1] < 1 && p[2] > 0 && p[2] < 1));
    }
}

TEST_CASE("placement candidates: the whole mode stays within the scene's bounds", "[placement]") {
    // A closed room whose bounds are not a multiple of the spacing: no grid point may leave them.
    Scene scene;
    add_box(scene, {0, 0, 0}, {5.3f, 2.9f, 4.1f}, false);
    CandidateRules rules;
    rules.margin = 0;
    const Candidates c = find_candidates(scene, rules, 2, Progress{});
    CHECK(c.positions.size() / 3 == 5 * 2 * 4);
    for (const std::vector<float>* points : {&c.positions, &c.held_out})
        for (size_t i = 0; i < points->size() / 3; ++i) {
            const float* p = &(*points)[3 * i];
            CHECK((p[0] >= 0 && p[0] <= 5.3f && p[1] >= 0 && p[1] <= 2.9f && p[2] >= 0 && p[2] <= 4.1f));
        }
}

TEST_CASE("placement: the same bytes for a seed on one thread and two", "[placement]") {
    const Scene scene = lit_room();
    PlacementSettings settings = room_settings();
    settings.target_count = 60;
    settings.error_bound = 0;
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
    // Another seed bakes other samples: still a valid placement of the same size.
    settings.seed = 6;
    CHECK(place_probes(scene, settings).positions.size() == 3 * 60);
}

TEST_CASE("placement: pruning keeps probes where the light changes, beating a uniform subsample", "[placement]") {
    const Scene scene = lit_room();
    PlacementSettings settings = room_settings();
    settings.target_count = 40;
    settings.error_bound = 0;
    const Placement placed = place_probes(scene, settings);
    REQUIRE(placed.positions.size() == 3 * 40);

    // The curve: from every candidate with error 0 down to the target, counts falling, error rising.
    REQUIRE(placed.curve.size() >= 3);
    CHECK(placed.curve.front().probes == placed.candidates);
    CHECK(placed.curve.front().error == 0.0);
    CHECK(placed.curve.back().probes == 40);
    for (size_t i = 1; i < placed.curve.size(); ++i) {
        CHECK(placed.curve[i].probes < placed.curve[i - 1].probes);
        CHECK(placed.curve[i].error >= placed.curve[i - 1].error - 0.02);  // monotone up to noise
    }
    CHECK(placed.curve.back().error > placed.curve[1].error);

    // A uniform subsample of the same candidates: every (n / 40)-th in grid order.
    CandidateRules rules = settings.rules;
    const Candidates all = find_candidates(scene, rules, 2, Progress{});
    const size_t n = all.positions.size() / 3;
    std::vector<float> uniform;
    for (size_t i = 0; i < 40; ++i) {
        const size_t k = (2 * i + 1) * n / 80;
        uniform.insert(uniform.end(), &all.positions[3 * k], &all.positions[3 * k] + 3);
    }
    // Independent test points in free space, baked at more rays.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.25f, 5.75f), v(0.25f, 2.75f);
    std::vector<float> points;
    while (points.size() < 3 * 300) {
        const float p[3] = {u(rng), v(rng), u(rng)};
        const float to_lamp = std::sqrt((p[0] - 0.6f) * (p[0] - 0.6f) + (p[1] - 2.4f) * (p[1] - 2.4f) + (p[2] - 0.6f) * (p[2] - 0.6f));
        if (!in_solid(p) && distance_to_scene(scene, p) > 0.2 && to_lamp > 0.5f) points.insert(points.end(), p, p + 3);
    }
    const double smart = true_error(scene, placed.positions, points);
    const double even = true_error(scene, uniform, points);
    WARN("40 probes of " << n << " candidates: placed error " << smart << ", uniform subsample " << even);
    CHECK(smart < even);
}

TEST_CASE("placement: an error bound stops pruning before the error exceeds it", "[placement]") {
    const Scene scene = lit_room();
    PlacementSettings settings = room_settings();
    settings.error_bound = 0.08;
    const Placement placed = place_probes(scene, settings);
    CHECK(placed.positions.size() / 3 < placed.candidates);
    CHECK(placed.curve.back().probes == placed.positions.size() / 3);
    for (const ErrorCurvePoint& point : placed.curve) CHECK(point.error <= 0.08);
    // A looser bound removes more.
    settings.error_bound = 0.2;
    CHECK(place_probes(scene, settings).positions.size() < placed.positions.size());
    // Neither target nor bound: the candidates themselves.
    settings.error_bound = 0;
    const Placement unpruned = place_probes(scene, settings);
    CHECK(unpruned.positions.size() / 3 == unpruned.candidates);
    CHECK(unpruned.curve.size() == 1);
}

TEST_CASE("placement: cancelling in any stage stops with Status::cancelled", "[placement]") {
    const Scene scene = lit_room();
    for (const char* stage : {"candidates", "bake", "prune"}) {
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

TEST_CASE("placement: bad input gets a clear status and message", "[placement]") {
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
    s = room_settings();
    s.target_count = 10000;
    CHECK(status_of([&] { place_probes(scene, s); }, &message) == Status::invalid_argument);
    CHECK(message.find("target_count 10000 is more than the") != std::string::npos);
    s = room_settings();
    s.rules.spacing = 0.01;
    CHECK(status_of([&] { placement_bound(scene, s); }, &message) == Status::invalid_argument);
    CHECK(message.find("raise the spacing") != std::string::npos);
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
