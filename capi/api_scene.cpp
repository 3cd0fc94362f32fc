// Scenes, the effects plan and the lighting bake (full library only).
#include "bake_structs.h"
#include "boundary.h"
#include "grown_structs.h"
#include "scene_handle.h"
#include "strides.h"

#include "bake/effects_plan.h"
#include "bake/lighting_bake.h"
#include "bake/occlusion_bake.h"
#include "bake/scene.h"
#include "bake/scene_file.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>

using tetprobe::fail;

namespace {

tp_status read_positions(const float* positions, size_t stride, size_t count, std::vector<float>& out) {
    if (count == 0) return fail(TP_ERROR_DEGENERATE, "no probe positions (count is 0)");
    tetprobe::copy_finite_positions(positions, stride, count, out);
    return TP_OK;
}

// The one reading of tp_bake_options (tp_bake, tp_bake_plan, tp_bake_occlusion).
tp_status read_options(const tp_bake_options* options, tetprobe::BakeSettings& settings) {
    if (!options) return TP_OK;
    if (options->struct_size < sizeof(tp_bake_options))
        return fail(TP_ERROR_INVALID_ARGUMENT, "options->struct_size is not set (call tp_bake_options_init)");
    if (options->flags & ~uint32_t(TP_BAKE_NO_CULLING))
        return fail(TP_ERROR_INVALID_ARGUMENT, "unknown bake flags " + std::to_string(options->flags));
    if (options->rays == 0) return fail(TP_ERROR_INVALID_ARGUMENT, "options->rays must be at least 1");
    settings.rays = options->rays;
    settings.bounces = options->bounces;
    settings.seed = options->seed;
    settings.threads = options->threads;
    settings.culling = !(options->flags & TP_BAKE_NO_CULLING);
    settings.progress = tetprobe::progress_from_c(options->progress, options->progress_user);
    return TP_OK;
}

}  // namespace

extern "C" {

TP_API tp_status tp_scene_create(tp_scene** out_scene) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(out_scene);
    *out_scene = nullptr;
    *out_scene = new tp_scene();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_release(tp_scene* scene) {
    TP_API_BEGIN
    delete scene;
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_load_file(const char* path, tp_scene** out_scene) {
    return tp_scene_load_file_ex(path, nullptr, out_scene);
}

TP_API tp_status tp_scene_load_file_ex(const char* path, const tp_scene_load_options* options, tp_scene** out_scene) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(path);
    TP_REQUIRE_NOT_NULL(out_scene);
    *out_scene = nullptr;
    tetprobe::Scene loaded = tetprobe::load_scene_file(path, tetprobe::scene_load_options_from_c(options));
    *out_scene = new tp_scene{std::move(loaded)};
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_notes(const tp_scene* scene, char* text, size_t text_capacity, size_t* out_size) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    if (text && text_capacity > 0) text[0] = '\0';
    std::string notes;
    for (const std::string& note : scene->scene.notes()) notes += note + "\n";
    if (out_size) *out_size = notes.size() + 1;
    if (!text) return TP_OK;
    if (notes.size() + 1 > text_capacity)
        return fail(TP_ERROR_BUFFER_TOO_SMALL, "the notes need " + std::to_string(notes.size() + 1) +
                                                   " bytes, text_capacity is " + std::to_string(text_capacity));
    std::memcpy(text, notes.c_str(), notes.size() + 1);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_up(const tp_scene* scene, uint32_t* out_up) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_up);
    *out_up = uint32_t(scene->scene.up());
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_set_up(tp_scene* scene, uint32_t up) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    scene->scene.set_up(static_cast<tetprobe::UpAxis>(up));
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_add_mesh(tp_scene* scene, const float* vertices, size_t vertex_count,
                                   const uint32_t* indices, size_t triangle_count,
                                   const tp_material* materials, size_t material_count,
                                   const uint32_t* triangle_materials, uint32_t* out_mesh) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(vertices);
    TP_REQUIRE_NOT_NULL(indices);
    TP_REQUIRE_NOT_NULL(materials);
    if (material_count == 0) return fail(TP_ERROR_INVALID_ARGUMENT, "material_count is 0");
    tetprobe::checked_packed(vertices, "vertices", vertex_count, "vertex_count", 3 * sizeof(float));
    tetprobe::checked_packed(indices, "indices", triangle_count, "triangle_count", 3 * sizeof(uint32_t));
    tetprobe::checked_packed(materials, "materials", material_count, "material_count", sizeof(tp_material));
    if (triangle_materials)
        tetprobe::checked_packed(triangle_materials, "triangle_materials", triangle_count, "triangle_count",
                                 sizeof(uint32_t));
    const std::string label = "mesh " + std::to_string(scene->scene.meshes().size());
    std::vector<tetprobe::Material> converted;
    for (size_t m = 0; m < material_count; ++m)
        converted.push_back(tetprobe::material_from_c(materials[m], label + ", material " + std::to_string(m)));
    uint32_t index = scene->scene.add_mesh(vertices, vertex_count, indices, triangle_count, converted,
                                           triangle_materials, label);
    if (out_mesh) *out_mesh = index;
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_add_light(tp_scene* scene, const tp_light* light, uint32_t* out_light) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(light);
    const std::string label = "light " + std::to_string(scene->scene.lights().size());
    uint32_t index = scene->scene.add_light(tetprobe::light_from_c(*light, label), label);
    if (out_light) *out_light = index;
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_set_sky_color(tp_scene* scene, const float rgb[3]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(rgb);
    scene->scene.set_sky_color(rgb);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_set_sky_sh(tp_scene* scene, const float sh[27]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(sh);
    scene->scene.set_sky_sh(sh);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_probes(const tp_scene* scene, const float** out_positions, size_t* out_count) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_positions);
    TP_REQUIRE_NOT_NULL(out_count);
    *out_positions = scene->scene.probes().data();
    *out_count = scene->scene.probe_count();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_set_probes(tp_scene* scene, const float* positions, size_t count) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    tetprobe::checked_packed(positions, "positions", count, "count", 3 * sizeof(float));
    scene->scene.set_probes(positions, count);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_set_playable_seeds(tp_scene* scene, const float* positions, size_t count) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    if (count > 0) TP_REQUIRE_NOT_NULL(positions);
    scene->scene.set_playable_seeds(positions, count);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_bake_plan(const tp_scene* scene, const float* positions, size_t position_stride,
                              size_t count, const tp_bake_options* options, tp_effects_plan* plan,
                              char* text, size_t text_capacity) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(plan);
    // The plan grows at its end (inside_probes came later): an older caller's struct gets only its fields.
    constexpr size_t kFirstPlanSize = offsetof(tp_effects_plan, inside_probes);
    if (plan->struct_size < kFirstPlanSize)
        return fail(TP_ERROR_INVALID_ARGUMENT, "plan->struct_size is not set to sizeof(tp_effects_plan)");
    if (text) tetprobe::checked_packed(text, "text", text_capacity, "text_capacity", 1);
    if (text && text_capacity > 0) text[0] = '\0';
    tetprobe::BakeSettings settings;
    if (tp_status s = read_options(options, settings)) return s;
    std::vector<float> probes;
    if (tp_status s = read_positions(positions, position_stride, count, probes)) return s;
    if (scene->scene.empty()) return fail(TP_ERROR_SCENE, "the scene is empty (no mesh, light or sky)");

    tetprobe::EffectsPlan derived =
        tetprobe::derive_effects_plan(scene->scene, probes, settings.bounces, settings.culling);
    tetprobe::add_inside_probes(derived, scene->scene, probes, settings.threads);
    tp_effects_plan out{};
    out.struct_size = sizeof(tp_effects_plan);
    out.lights = derived.lights;
    out.direct_lights = uint32_t(derived.direct_lights.size());
    out.realtime_lights = derived.realtime_lights;
    out.out_of_range_lights = derived.out_of_range_lights;
    out.sky = derived.sky ? 1 : 0;
    out.emissive_meshes = uint32_t(derived.emissive_meshes.size());
    out.bounces = derived.bounces;
    out.shadows = derived.shadows ? 1 : 0;
    out.meshes = derived.meshes;
    out.shadow_casters = derived.shadow_casters;
    out.shadow_caster_candidates = derived.shadow_caster_candidates;
    out.inside_probes = uint32_t(derived.inside_probes.size());
    tetprobe::copy_fitting_fields(plan, out, plan->struct_size);

    if (text) {
        const std::string summary = derived.summary();
        if (summary.size() + 1 > text_capacity)
            return fail(TP_ERROR_BUFFER_TOO_SMALL, "the summary needs " + std::to_string(summary.size() + 1) +
                                                       " bytes, text_capacity is " + std::to_string(text_capacity));
        std::memcpy(text, summary.c_str(), summary.size() + 1);
    }
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_bake(const tp_scene* scene, const float* positions, size_t position_stride, size_t count,
                         const tp_bake_options* options, float* out_sh, size_t sh_stride) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_sh);
    tetprobe::BakeSettings settings;
    if (tp_status s = read_options(options, settings)) return s;
    std::vector<float> probes;
    if (tp_status s = read_positions(positions, position_stride, count, probes)) return s;
    sh_stride = tetprobe::checked_buffer(out_sh, "out_sh", count, "count", sh_stride, "sh_stride", 27 * sizeof(float));

    const std::vector<float> sh = tetprobe::bake_lighting(scene->scene, probes, settings);
    for (size_t i = 0; i < count; ++i)
        std::memcpy(tetprobe::element_at(out_sh, i, sh_stride), &sh[27 * i], 27 * sizeof(float));
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_bake_occlusion(const tp_scene* scene, const float* positions, size_t position_stride,
                                   size_t count, const tp_bake_options* options, uint8_t* out_occlusion,
                                   size_t occlusion_stride, uint32_t* out_mixed_lights) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_occlusion);
    tetprobe::BakeSettings settings;
    if (tp_status s = read_options(options, settings)) return s;
    std::vector<float> probes;
    if (tp_status s = read_positions(positions, position_stride, count, probes)) return s;
    occlusion_stride =
        tetprobe::checked_buffer(out_occlusion, "out_occlusion", count, "count", occlusion_stride, "occlusion_stride", 4);
    uint32_t lights = 0;
    const std::vector<uint8_t> occlusion = tetprobe::bake_occlusion(scene->scene, probes, settings, &lights);
    for (size_t i = 0; i < count; ++i) std::memcpy(tetprobe::element_at(out_occlusion, i, occlusion_stride), &occlusion[4 * i], 4);
    if (out_mixed_lights) *out_mixed_lights = lights;
    return TP_OK;
    TP_API_END
}

}  // extern "C"
