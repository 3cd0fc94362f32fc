// The C ABI's structs as bake/ sees them (capi/bake_structs.h, capi/struct_defaults.h): every field of
// a tp_light and a tp_material reaches the bake's own types, an unset struct_size is refused there,
// values are judged by bake/ alone, a C progress callback is called as it is, and what tp_*_init
// fills in equals the defaults of the bake's own types (both read core/option_defaults.h).
#include <catch2/catch.hpp>

#include "bake/lighting_bake.h"
#include "bake/probe_placement.h"
#include "bake/scene.h"
#include "bake/store_builder.h"
#include "capi/bake_structs.h"
#include "capi/struct_defaults.h"
#include "core/error.h"

#include <array>
#include <cstddef>
#include <functional>
#include <string>

using namespace tetprobe;

namespace {

Status status_of(const std::function<void()>& f, std::string* message = nullptr) {
    try {
        f();
    } catch (const Error& e) {
        if (message) *message = e.what();
        return e.status();
    }
    return Status::ok;
}

}  // namespace

TEST_CASE("C structs: tp_light_init and tp_material_init give the bake's own defaults", "[scene]") {
    const LightDescription from_c = light_from_c(default_light(), "light 0"), own;
    CHECK(from_c.type == own.type);
    CHECK(from_c.mode == own.mode);
    CHECK(from_c.shadows == own.shadows);
    CHECK(from_c.color == own.color);
    CHECK(from_c.intensity == own.intensity);
    CHECK(from_c.position == own.position);
    CHECK(from_c.direction == own.direction);
    CHECK(from_c.range == own.range);
    CHECK(from_c.inner_angle == own.inner_angle);
    CHECK(from_c.outer_angle == own.outer_angle);
    CHECK(from_c.near_distance == own.near_distance);

    const Material material = material_from_c(default_material(), "material 0"), own_material;
    CHECK(material.albedo == own_material.albedo);
    CHECK(material.emission == own_material.emission);
    CHECK(material.two_sided == own_material.two_sided);
}

TEST_CASE("C structs: the options' tp_*_init give the bake's own settings' defaults", "[scene]") {
    const tp_bake_options bake = default_bake_options();
    const BakeSettings bake_settings;
    CHECK(bake.rays == bake_settings.rays);
    CHECK(bake.bounces == bake_settings.bounces);
    CHECK(bake.seed == bake_settings.seed);
    CHECK(bake.threads == bake_settings.threads);
    CHECK(((bake.flags & TP_BAKE_NO_CULLING) == 0) == bake_settings.culling);
    CHECK((bake.progress == nullptr && bake_settings.progress.callback == nullptr));

    const tp_placement_options place = default_placement_options();
    const PlacementSettings place_settings;
    CHECK(place.mode == uint32_t(place_settings.rules.mode));
    CHECK(double(place.spacing) == place_settings.rules.spacing);
    CHECK(double(place.margin) == place_settings.rules.margin);
    CHECK(double(place.walk_min_height) == place_settings.rules.walk_min_height);
    CHECK(double(place.walk_max_height) == place_settings.rules.walk_max_height);
    CHECK(place.target_count == place_settings.target_count);
    CHECK(double(place.error_bound) == place_settings.error_bound);
    CHECK(place.rays == place_settings.rays);
    CHECK(place.bounces == place_settings.bounces);
    CHECK(place.seed == place_settings.seed);
    CHECK(place.threads == place_settings.threads);

    const tp_build_options build = default_build_options();
    const BuildSettings build_settings;
    CHECK(build.flags == build_settings.flags);
    CHECK(build.merge_tolerance == build_settings.merge_tolerance);
    CHECK(build.flat_tolerance == build_settings.flat_tolerance);
    CHECK((build.occlusion == nullptr && build_settings.occlusion == nullptr));
    CHECK((build.scene == nullptr && build_settings.scene == nullptr));
}

TEST_CASE("C structs: every field of a tp_light and a tp_material is carried over; struct_size is checked", "[scene]") {
    tp_light c = default_light();
    c.type = TP_LIGHT_SPOT;
    c.mode = TP_LIGHT_MODE_MIXED;
    c.shadows = 0;
    c.color[0] = 0.1f, c.color[1] = 0.2f, c.color[2] = 0.3f;
    c.intensity = 7.5f;
    c.position[0] = 1, c.position[1] = 2, c.position[2] = 3;
    c.direction[0] = 0.5f, c.direction[1] = -2, c.direction[2] = 0.25f;
    c.range = 12;
    c.inner_angle = 10, c.outer_angle = 70;
    c.near_distance = 0.5f;
    const LightDescription d = light_from_c(c, "light 0");
    CHECK(d.type == LightType::spot);
    CHECK(d.mode == LightMode::mixed);
    CHECK_FALSE(d.shadows);
    CHECK(d.color == std::array<float, 3>{{0.1f, 0.2f, 0.3f}});
    CHECK(d.intensity == 7.5f);
    CHECK(d.position == std::array<float, 3>{{1, 2, 3}});
    CHECK(d.direction == std::array<float, 3>{{0.5f, -2, 0.25f}});
    CHECK(d.range == 12);
    CHECK(d.inner_angle == 10);
    CHECK(d.outer_angle == 70);
    CHECK(d.near_distance == 0.5f);

    // An older caller's struct ends before near_distance: it reads as 0, and nothing past its end is read.
    tp_light older = c;
    older.struct_size = uint32_t(offsetof(tp_light, near_distance));
    CHECK(light_from_c(older, "light 1").near_distance == 0);
    CHECK(light_from_c(older, "light 1").outer_angle == 70);
    older.struct_size = uint32_t(offsetof(tp_light, outer_angle));  // shorter than any tp_light ever was
    CHECK(status_of([&] { light_from_c(older, "light 2"); }) == Status::invalid_argument);

    // A value C cannot check is passed through and refused by bake/, by the same rule as any caller's.
    Scene scene;
    c.type = 9;
    std::string message;
    CHECK(status_of([&] { scene.add_light(light_from_c(c, "light 0"), "light 0"); }, &message) == Status::scene);
    CHECK(message == "light 0: unknown type 9");
    c.struct_size = 0;
    CHECK(status_of([&] { light_from_c(c, "light 3"); }, &message) == Status::invalid_argument);
    CHECK(message == "light 3: struct_size is not set (call tp_light_init)");

    tp_material m = default_material();
    m.albedo[0] = 0.25f, m.albedo[1] = 0.5f, m.albedo[2] = 0.75f;
    m.emission[0] = 4, m.emission[1] = 5, m.emission[2] = 6;
    m.two_sided = 1;
    const Material material = material_from_c(m, "mesh 0, material 0");
    CHECK(material.albedo == std::array<float, 3>{{0.25f, 0.5f, 0.75f}});
    CHECK(material.emission == std::array<float, 3>{{4, 5, 6}});
    CHECK(material.two_sided);
    m.albedo[1] = 2;
    CHECK(status_of([&] { material_from_c(m, "mesh 0, material 0"); }, &message) == Status::scene);
    CHECK(message.find("mesh 0, material 0: albedo") == 0);
    m.struct_size = 0;
    CHECK(status_of([&] { material_from_c(m, "mesh 1, material 2"); }, &message) == Status::invalid_argument);
    CHECK(message == "mesh 1, material 2: struct_size is not set (call tp_material_init)");
}

TEST_CASE("C structs: a C progress callback is called as it is and cancels", "[scene]") {
    struct Log {
        float fraction = -1;
        std::string stage;
        int answer = 0;
    } log;
    const tp_progress_fn callback = [](void* user, float fraction, const char* stage) {
        Log& l = *static_cast<Log*>(user);
        l.fraction = fraction;
        l.stage = stage;
        return l.answer;
    };
    const Progress progress = progress_from_c(callback, &log).part(0.5, 1.0);
    progress.report(0.5, "bake");
    CHECK(log.fraction == 0.75f);
    CHECK(log.stage == "bake");
    log.answer = 1;
    std::string message;
    CHECK(status_of([&] { progress.report(1.0, "prune"); }, &message) == Status::cancelled);
    CHECK(message == "cancelled by the progress callback during prune");
    CHECK(status_of([&] { progress_from_c(nullptr, &log).report(1.0, "prune"); }) == Status::ok);
}
