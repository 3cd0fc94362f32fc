// The C ABI's structs and callbacks translated into bake/'s own types, one function each and nowhere
// else (full library only; the options structs are read next to their entry points: api_build.cpp,
// api_scene.cpp, api_placement.cpp). Values are checked by bake/ (Scene::add_light,
// validate_material); here only what is C's own: struct_size.
#pragma once

#include "capi/tetprobe.h"

#include "bake/progress.h"
#include "bake/scene.h"
#include "bake/scene_file.h"
#include "core/error.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

namespace tetprobe {

// The C enumerations' values are bake/'s (an unknown value passes through and is refused there).
static_assert(TP_LIGHT_DIRECTIONAL == uint32_t(LightType::directional) && TP_LIGHT_POINT == uint32_t(LightType::point) &&
                  TP_LIGHT_SPOT == uint32_t(LightType::spot),
              "TP_LIGHT_* must equal LightType");
static_assert(TP_LIGHT_MODE_BAKED == uint32_t(LightMode::baked) && TP_LIGHT_MODE_REALTIME == uint32_t(LightMode::realtime) &&
                  TP_LIGHT_MODE_MIXED == uint32_t(LightMode::mixed),
              "TP_LIGHT_MODE_* must equal LightMode");

static_assert(TP_UP_FILE == uint32_t(UpAxis::file) && TP_UP_POS_X == uint32_t(UpAxis::pos_x) &&
                  TP_UP_NEG_X == uint32_t(UpAxis::neg_x) && TP_UP_POS_Y == uint32_t(UpAxis::pos_y) &&
                  TP_UP_NEG_Y == uint32_t(UpAxis::neg_y) && TP_UP_POS_Z == uint32_t(UpAxis::pos_z) &&
                  TP_UP_NEG_Z == uint32_t(UpAxis::neg_z),
              "TP_UP_* must equal UpAxis");

// tp_progress_fn has ProgressCallback's signature: the caller's callback is called as it is.
inline Progress progress_from_c(tp_progress_fn callback, void* user) {
    Progress progress;
    progress.callback = callback;
    progress.user = user;
    return progress;
}

// A C material (struct_size must be set), validated; `where` names it in messages.
inline Material material_from_c(const tp_material& material, const std::string& where) {
    if (material.struct_size < sizeof(tp_material))
        throw Error(Status::invalid_argument, where + ": struct_size is not set (call tp_material_init)");
    Material m;
    std::copy(material.albedo, material.albedo + 3, m.albedo.begin());
    std::copy(material.emission, material.emission + 3, m.emission.begin());
    m.two_sided = material.two_sided != 0;
    validate_material(m, where);
    return m;
}

// A C light (struct_size must be set), for Scene::add_light to validate; `where` names it in messages.
inline LightDescription light_from_c(const tp_light& light, const std::string& where) {
    // The first tp_light ended at outer_angle; near_distance grew at its end.
    constexpr size_t kFirstLightSize = offsetof(tp_light, outer_angle) + sizeof(float);
    if (light.struct_size < kFirstLightSize)
        throw Error(Status::invalid_argument, where + ": struct_size is not set (call tp_light_init)");
    LightDescription d;
    d.type = static_cast<LightType>(light.type);
    d.mode = static_cast<LightMode>(light.mode);
    d.shadows = light.shadows != 0;
    std::copy(light.color, light.color + 3, d.color.begin());
    d.intensity = light.intensity;
    std::copy(light.position, light.position + 3, d.position.begin());
    std::copy(light.direction, light.direction + 3, d.direction.begin());
    d.range = light.range;
    d.inner_angle = light.inner_angle;
    d.outer_angle = light.outer_angle;
    if (light.struct_size >= offsetof(tp_light, near_distance) + sizeof(float)) d.near_distance = light.near_distance;
    return d;
}

// C scene load options (NULL = defaults; struct_size must be set), for load_scene_file to check.
inline SceneLoadOptions scene_load_options_from_c(const tp_scene_load_options* options) {
    SceneLoadOptions o;
    if (!options) return o;
    if (options->struct_size < sizeof(tp_scene_load_options))
        throw Error(Status::invalid_argument, "options->struct_size is not set (call tp_scene_load_options_init)");
    o.up = static_cast<UpAxis>(options->up);
    o.scale = double(options->scale);
    return o;
}

}  // namespace tetprobe
