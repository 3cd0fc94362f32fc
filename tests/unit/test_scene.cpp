// Scenes: validation names what is wrong and where (scene files: test_scene_import.cpp).
#include <catch2/catch.hpp>

#include "bake/scene.h"
#include "core/error.h"

#include <cmath>
#include <cstdio>

using namespace tetprobe;

namespace {

const float kQuad[12] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
const uint32_t kQuadIndices[6] = {0, 2, 1, 0, 3, 2};

// Runs f and returns the Error it throws (fails the test if it throws nothing).
template <class F>
Error error_of(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    FAIL("no error was thrown");
    return Error(tetprobe::Status::ok, "");
}

bool mentions(const Error& e, const std::string& text) {
    const bool found = std::string(e.what()).find(text) != std::string::npos;
    if (!found) WARN("message: " << e.what() << " (expected to mention '" << text << "')");
    return found;
}

}  // namespace

TEST_CASE("scene: meshes are validated with messages naming mesh and index", "[scene]") {
    Scene scene;
    const std::vector<Material> grey(1);
    CHECK(scene.add_mesh(kQuad, 4, kQuadIndices, 2, grey, nullptr) == 0);
    CHECK(scene.meshes()[0].triangle_count() == 2);
    CHECK(scene.meshes()[0].bounds_max[0] == 1.0f);

    float nan_vertex[12];
    std::copy(kQuad, kQuad + 12, nan_vertex);
    nan_vertex[7] = NAN;
    Error e = error_of([&] { scene.add_mesh(nan_vertex, 4, kQuadIndices, 2, grey, nullptr); });
    CHECK(e.status() == tetprobe::Status::scene);
    CHECK(mentions(e, "mesh 1"));
    CHECK(mentions(e, "vertex 2"));

    const uint32_t out_of_range[6] = {0, 2, 1, 0, 3, 4};
    e = error_of([&] { scene.add_mesh(kQuad, 4, out_of_range, 2, grey, nullptr); });
    CHECK(e.status() == tetprobe::Status::scene);
    CHECK(mentions(e, "triangle 1"));
    CHECK(mentions(e, "index 4"));

    const uint32_t bad_material[2] = {0, 1};
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 2, grey, bad_material); });
    CHECK(mentions(e, "material 1"));

    std::vector<Material> bright(1);
    bright[0].albedo = {0.5f, 1.5f, 0.5f};
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 2, bright, nullptr); });
    CHECK(mentions(e, "albedo"));
    std::vector<Material> negative(1);
    negative[0].emission = {0.0f, -1.0f, 0.0f};
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 2, negative, nullptr); });
    CHECK(mentions(e, "emission"));
    CHECK(scene.meshes().size() == 1);  // nothing half-added

    // Zero-area triangles (a repeated index, collinear points) are dropped and counted.
    const float line[12] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 1};
    const uint32_t some_degenerate[9] = {0, 1, 2, 0, 0, 3, 0, 3, 1};
    CHECK(scene.add_mesh(line, 4, some_degenerate, 3, grey, nullptr) == 1);
    CHECK(scene.meshes()[1].triangle_count() == 1);
    CHECK(scene.meshes()[1].dropped_triangles == 2);
    CHECK(scene.dropped_triangles() == 2);
    e = error_of([&] { scene.add_mesh(line, 4, some_degenerate, 1, grey, nullptr); });
    CHECK(mentions(e, "zero area"));
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 0, grey, nullptr); });
    CHECK(mentions(e, "no triangles"));
}

TEST_CASE("scene: lights, sky and probes are validated", "[scene]") {
    Scene scene;
    LightDescription light;
    CHECK(scene.add_light(light) == 0);
    light.intensity = -1;
    Error e = error_of([&] { scene.add_light(light); });
    CHECK(e.status() == tetprobe::Status::scene);
    CHECK(mentions(e, "light 1"));
    CHECK(mentions(e, "intensity"));
    light.intensity = 1;
    light.type = LightType::directional;
    light.direction = {0, 0, 0};
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "direction"));
    light.type = LightType::spot;
    light.direction[1] = -1;
    light.inner_angle = 50, light.outer_angle = 40;
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "spot angles"));
    light.type = LightType::point;
    light.range = 0;
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "range"));
    light.range = INFINITY;
    light.mode = static_cast<LightMode>(5);
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "mode"));
    light.mode = LightMode::realtime;
    light.color[2] = NAN;
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "colour"));
    light.color[2] = 1;
    light.type = static_cast<LightType>(7);
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "unknown type 7"));
    CHECK(scene.lights().size() == 1);

    const float sky[3] = {1, 2, 3}, bad_sky[3] = {1, -2, 3};
    scene.set_sky_color(sky);
    CHECK_FALSE(scene.sky().black());
    CHECK(mentions(error_of([&] { scene.set_sky_color(bad_sky); }), "sky"));
    const float black[3] = {0, 0, 0};
    scene.set_sky_color(black);
    CHECK(scene.sky().black());

    const float probes[6] = {0, 1, 2, 3, NAN, 5};
    CHECK(mentions(error_of([&] { scene.set_probes(probes, 2); }), "probe 1"));
    scene.set_probes(probes, 1);
    CHECK(scene.probe_count() == 1);
}
