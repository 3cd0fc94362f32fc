// The effects plan: what a scene asks for, decided before tracing, and its one-line summary.
#include <catch2/catch.hpp>

#include "bake/effects_plan.h"
#include "bake/inside_test.h"
#include "bake/scene.h"
#include "bake/scene_file.h"

#include <cmath>

using namespace tetprobe;

namespace {

Material grey(float albedo = 0.5f, float emission = 0.0f) {
    Material m;
    m.albedo = {albedo, albedo, albedo};
    m.emission = {emission, emission, emission};
    return m;
}

// A unit box mesh with its lower corner at (x, y, z).
void add_cube(Scene& scene, float x, float y, float z, const Material& m) {
    std::vector<float> v;
    for (int corner = 0; corner < 8; ++corner) {
        v.push_back(x + (corner & 1 ? 1.0f : 0.0f));
        v.push_back(y + (corner & 2 ? 1.0f : 0.0f));
        v.push_back(z + (corner & 4 ? 1.0f : 0.0f));
    }
    const uint32_t indices[36] = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                  2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
    scene.add_mesh(v.data(), 8, indices, 12, {m}, nullptr);
}

LightDescription point_light(float x, float y, float z, float range, LightMode mode = LightMode::baked) {
    LightDescription l;
    l.type = LightType::point;
    l.position[0] = x, l.position[1] = y, l.position[2] = z;
    l.range = range;
    l.mode = mode;
    return l;
}

const std::vector<float> kProbes = {0, 0, 0, 2, 1, 0, 0, 1, 2};

}  // namespace

TEST_CASE("effects plan: lights in and out of range, realtime, sky, emission, bounces", "[plan]") {
    Scene scene;
    add_cube(scene, -5, -3, -5, grey());
    add_cube(scene, 10, 0, 0, grey(0.5f, 2.0f));
    add_cube(scene, 0, 0, 10, grey(0.0f, 1.0f));
    scene.add_light(point_light(1, 5, 1, 10));                       // reaches the probes
    scene.add_light(point_light(40, 0, 0, 5));                       // reaches no probe and no mesh
    scene.add_light(point_light(14, 0, 0, 5));                       // reaches no probe but a mesh
    scene.add_light(point_light(0, 3, 0, INFINITY, LightMode::realtime));

    EffectsPlan plan = derive_effects_plan(scene, kProbes, 3, true);
    CHECK(plan.lights == 4);
    CHECK(plan.direct_lights == std::vector<uint32_t>{0});
    CHECK(plan.out_of_range_lights == 2);
    CHECK(plan.realtime_lights == 1);
    CHECK(plan.bounce_lights == std::vector<uint32_t>{0, 2, 3});  // light 1 lights nothing
    CHECK_FALSE(plan.sky);
    CHECK(plan.emissive_meshes == std::vector<uint32_t>{1, 2});
    CHECK(plan.bounces == 3);
    CHECK(plan.shadows);
    CHECK(plan.meshes == 3);
    CHECK(plan.summary() ==
          "direct: 1 light (2 out of range); realtime: 1 light (bounced only); sky: off; emissive: 2 meshes; "
          "bounces: 3; shadow casters: 0/3 meshes");  // nothing lies between the lamp and the probes

    // Zero requested bounces: no bounce lights either.
    plan = derive_effects_plan(scene, kProbes, 0, true);
    CHECK(plan.bounces == 0);
    CHECK(plan.bounce_lights.empty());
}

TEST_CASE("effects plan: bounces only when something can bounce", "[plan]") {
    // A black scene under a sky: nothing reflects.
    Scene black;
    add_cube(black, 0, -2, 0, grey(0.0f));
    const float sky[3] = {1, 1, 1};
    black.set_sky_color(sky);
    EffectsPlan plan = derive_effects_plan(black, kProbes, 2, true);
    CHECK(plan.sky);
    CHECK(plan.bounces == 0);
    CHECK(plan.sampled());  // the sky is still sampled

    // Reflective geometry but no light at all: nothing to bounce.
    Scene dark;
    add_cube(dark, 0, -2, 0, grey(0.8f));
    LightDescription far = point_light(100, 0, 0, 1);
    dark.add_light(far);
    plan = derive_effects_plan(dark, kProbes, 2, true);
    CHECK(plan.bounces == 0);
    CHECK_FALSE(plan.sampled());
    CHECK(plan.summary() == "direct: 0 lights (1 out of range); sky: off; emissive: 0 meshes; bounces: 0; "
                            "shadow casters: 0/0 meshes");

    // Only a sky and reflective geometry: bounces are simulated.
    dark.set_sky_color(sky);
    plan = derive_effects_plan(dark, kProbes, 2, true);
    CHECK(plan.bounces == 2);
}

TEST_CASE("effects plan: shadow casters are the meshes in the shadow caster volume of the probes", "[plan]") {
    Scene scene;
    // Probes in [0, 2] x [0, 1] x [0, 2]; a light straight above them.
    add_cube(scene, 0.5f, 4, 0.5f, grey());   // between the light and the probes: a caster
    add_cube(scene, 0.5f, -4, 0.5f, grey());  // below the probes: cannot shadow them
    add_cube(scene, 8, 4, 0, grey());         // beside the cone
    add_cube(scene, 0.5f, 12, 0.5f, grey());  // behind the light
    add_cube(scene, 0.2f, 0.2f, 0.2f, grey()); // among the probes
    scene.add_light(point_light(1, 8, 1, INFINITY));
    LightDescription sun;
    sun.type = LightType::directional;
    sun.direction[0] = 0, sun.direction[1] = -1, sun.direction[2] = 0;  // straight down
    scene.add_light(sun);
    LightDescription unshadowed = point_light(1, 8, 1, INFINITY);
    unshadowed.shadows = false;
    scene.add_light(unshadowed);

    EffectsPlan plan = derive_effects_plan(scene, kProbes, 1, true);
    CHECK(plan.occluders[0] == std::vector<uint32_t>{0, 4});
    CHECK(plan.occluders[1] == std::vector<uint32_t>{0, 3, 4});  // the sun: everything straight above
    CHECK(plan.occluders[2].empty());
    CHECK(plan.shadow_casters == 5);
    CHECK(plan.shadow_caster_candidates == 10);

    plan = derive_effects_plan(scene, kProbes, 1, false);
    CHECK(plan.occluders[0].size() == 5);
    CHECK(plan.shadow_casters == 10);
}

TEST_CASE("effects plan: a flat probe set and a single probe still bound a region", "[plan]") {
    Scene scene;
    add_cube(scene, 0, 3, 0, grey());
    LightDescription sun;
    sun.type = LightType::directional;
    scene.add_light(sun);
    for (const std::vector<float>& probes : {std::vector<float>{0, 1, 0, 5, 1, 0, 5, 1, 5}, std::vector<float>{0.5f, 1, 0.5f}}) {
        EffectsPlan plan = derive_effects_plan(scene, probes, 0, true);
        CHECK(plan.shadow_casters == 1);
        CHECK(plan.shadow_caster_candidates == 1);
    }
}

TEST_CASE("effects plan: the sample scenes", "[plan]") {
    const std::string root = std::string(TP_SOURCE_DIR) + "/samples/scenes/";
    Scene track = load_scene_file(root + "race_track.json");
    EffectsPlan plan = derive_effects_plan(track, track.probes(), 2, true);
    CHECK(plan.summary() == "direct: 1 light (1 out of range); realtime: 1 light (bounced only); sky: on; "
                            "emissive: 0 meshes; bounces: 2; shadow casters: 1/5 meshes");
    Scene box = load_scene_file(root + "cornell_box.json");
    plan = derive_effects_plan(box, box.probes(), 2, true);
    CHECK(plan.summary() == "direct: 0 lights; sky: off; emissive: 1 mesh; bounces: 2; shadow casters: 0/0 meshes");
}

TEST_CASE("effects plan: probes inside geometry are counted and named, or the test says it cannot decide", "[plan]") {
    Scene scene;
    add_cube(scene, 0, 0, 0, grey());   // one-sided, facing out: a solid
    add_cube(scene, 3, 0, 0, grey());
    const std::vector<float> probes = {0.5f, 0.5f, 0.5f, 2, 0.5f, 0.5f, 3.5f, 0.2f, 0.9f, -1, -1, -1};
    EffectsPlan plan = derive_effects_plan(scene, probes, 2, true);
    add_inside_probes(plan, scene, probes, 1);
    CHECK(plan.inside_probes == std::vector<uint32_t>{0, 2});
    CHECK(plan.summary().find("; inside geometry: 2 probes (0, 2)") != std::string::npos);

    Scene sheet;  // a two-sided open quad has no inside
    const float v[12] = {0, 0, 0, 0, 0, 1, 1, 0, 1, 1, 0, 0};
    const uint32_t t[6] = {0, 1, 2, 0, 2, 3};
    Material two_sided = grey();
    two_sided.two_sided = true;
    sheet.add_mesh(v, 4, t, 2, {two_sided}, nullptr);
    EffectsPlan open = derive_effects_plan(sheet, probes, 2, true);
    add_inside_probes(open, sheet, probes, 1);
    CHECK(open.inside_probes.empty());
    CHECK(open.summary().find("inside geometry: undecided (no mesh has an inside)") != std::string::npos);
}
