// The run-time library builds no stores and has no scenes and no bake: these entry points exist so that the two libraries
// export the same symbols, and say why they fail. The struct initialisers are in api_defaults.cpp.
#include "boundary.h"

#include <cmath>
#include <cstring>
#include <string>

using tetprobe::fail;

namespace {

tp_status unavailable(const char* function) {
    return fail(TP_ERROR_UNSUPPORTED, std::string(function) +
                                          " is not available in the run-time library (load the full tetprobe library)");
}

}  // namespace

extern "C" {

TP_API tp_status tp_store_build(const float*, size_t, const float*, size_t, size_t, const tp_build_options*,
                                tp_store** out_store) {
    TP_API_BEGIN
    if (out_store) *out_store = nullptr;
    return unavailable("tp_store_build");
    TP_API_END
}

TP_API tp_status tp_scene_create(tp_scene** out_scene) {
    TP_API_BEGIN
    if (out_scene) *out_scene = nullptr;
    return unavailable("tp_scene_create");
    TP_API_END
}

TP_API tp_status tp_scene_release(tp_scene* scene) {
    TP_API_BEGIN
    if (!scene) return TP_OK;  // no scene can exist here; releasing NULL is always allowed
    return unavailable("tp_scene_release");
    TP_API_END
}

TP_API tp_status tp_scene_load_file(const char*, tp_scene** out_scene) {
    TP_API_BEGIN
    if (out_scene) *out_scene = nullptr;
    return unavailable("tp_scene_load_file");
    TP_API_END
}

TP_API tp_status tp_scene_load_file_ex(const char*, const tp_scene_load_options*, tp_scene** out_scene) {
    TP_API_BEGIN
    if (out_scene) *out_scene = nullptr;
    return unavailable("tp_scene_load_file_ex");
    TP_API_END
}

TP_API tp_status tp_scene_notes(const tp_scene*, char* text, size_t text_capacity, size_t* out_size) {
    TP_API_BEGIN
    if (text && text_capacity > 0) text[0] = '\0';
    if (out_size) *out_size = 0;
    return unavailable("tp_scene_notes");
    TP_API_END
}

TP_API tp_status tp_scene_up(const tp_scene*, uint32_t* out_up) {
    TP_API_BEGIN
    if (out_up) *out_up = TP_UP_FILE;
    return unavailable("tp_scene_up");
    TP_API_END
}

TP_API tp_status tp_scene_set_up(tp_scene*, uint32_t) {
    TP_API_BEGIN
    return unavailable("tp_scene_set_up");
    TP_API_END
}

TP_API tp_status tp_scene_add_mesh(tp_scene*, const float*, size_t, const uint32_t*, size_t, const tp_material*,
                                   size_t, const uint32_t*, uint32_t*) {
    TP_API_BEGIN
    return unavailable("tp_scene_add_mesh");
    TP_API_END
}

TP_API tp_status tp_scene_add_light(tp_scene*, const tp_light*, uint32_t*) {
    TP_API_BEGIN
    return unavailable("tp_scene_add_light");
    TP_API_END
}

TP_API tp_status tp_scene_set_sky_color(tp_scene*, const float*) {
    TP_API_BEGIN
    return unavailable("tp_scene_set_sky_color");
    TP_API_END
}

TP_API tp_status tp_scene_set_sky_sh(tp_scene*, const float*) {
    TP_API_BEGIN
    return unavailable("tp_scene_set_sky_sh");
    TP_API_END
}

TP_API tp_status tp_scene_probes(const tp_scene*, const float** out_positions, size_t* out_count) {
    TP_API_BEGIN
    if (out_positions) *out_positions = nullptr;
    if (out_count) *out_count = 0;
    return unavailable("tp_scene_probes");
    TP_API_END
}

TP_API tp_status tp_scene_set_probes(tp_scene*, const float*, size_t) {
    TP_API_BEGIN
    return unavailable("tp_scene_set_probes");
    TP_API_END
}

TP_API tp_status tp_scene_set_playable_seeds(tp_scene*, const float*, size_t) {
    TP_API_BEGIN
    return unavailable("tp_scene_set_playable_seeds");
    TP_API_END
}

TP_API tp_status tp_bake_plan(const tp_scene*, const float*, size_t, size_t, const tp_bake_options*, tp_effects_plan*,
                              char* text, size_t text_capacity) {
    TP_API_BEGIN
    if (text && text_capacity > 0) text[0] = '\0';
    return unavailable("tp_bake_plan");
    TP_API_END
}

TP_API tp_status tp_bake(const tp_scene*, const float*, size_t, size_t, const tp_bake_options*, float*, size_t) {
    TP_API_BEGIN
    return unavailable("tp_bake");
    TP_API_END
}

TP_API tp_status tp_bake_occlusion(const tp_scene*, const float*, size_t, size_t, const tp_bake_options*, uint8_t*,
                                   size_t, uint32_t* out_mixed_lights) {
    TP_API_BEGIN
    if (out_mixed_lights) *out_mixed_lights = 0;
    return unavailable("tp_bake_occlusion");
    TP_API_END
}

TP_API tp_status tp_place_probes_bound(const tp_scene*, const tp_placement_options*, size_t* out_bound) {
    TP_API_BEGIN
    if (out_bound) *out_bound = 0;
    return unavailable("tp_place_probes_bound");
    TP_API_END
}

TP_API tp_status tp_place_probes(const tp_scene*, const tp_placement_options*, float*, size_t, size_t* out_count, float*,
                                 size_t, size_t* out_curve_points) {
    TP_API_BEGIN
    if (out_count) *out_count = 0;
    if (out_curve_points) *out_curve_points = 0;
    return unavailable("tp_place_probes");
    TP_API_END
}

TP_API tp_status tp_find_inside_probes(const tp_scene*, const float*, size_t, size_t, uint32_t*, size_t,
                                       size_t* out_count) {
    TP_API_BEGIN
    if (out_count) *out_count = 0;
    return unavailable("tp_find_inside_probes");
    TP_API_END
}

TP_API tp_status tp_fix_inside_probes(const tp_scene*, const float*, size_t, size_t, uint32_t, float, float*, size_t,
                                      size_t* out_count) {
    TP_API_BEGIN
    if (out_count) *out_count = 0;
    return unavailable("tp_fix_inside_probes");
    TP_API_END
}

}  // extern "C"
