// The public structs as tp_*_init fills them in (the initialisers of both libraries), from the values
// in core/option_defaults.h, which bake/'s own settings and scene types read too
// (tp_sh_eval_options: capi/sh_eval_options_struct.h, next to its reading).
#pragma once

#include "capi/tetprobe.h"
#include "core/option_defaults.h"

namespace tetprobe {

inline tp_build_options default_build_options() {
    tp_build_options options{};
    options.struct_size = sizeof(tp_build_options);
    options.merge_tolerance = kDefaultMergeTolerance;
    options.flat_tolerance = kDefaultFlatTolerance;
    return options;
}

inline tp_bake_options default_bake_options() {
    tp_bake_options options{};
    options.struct_size = sizeof(tp_bake_options);
    options.rays = kDefaultBakeRays;
    options.bounces = kDefaultBakeBounces;
    return options;
}

inline tp_placement_options default_placement_options() {
    tp_placement_options options{};
    options.struct_size = sizeof(tp_placement_options);
    options.mode = TP_PLACEMENT_WHOLE;
    options.spacing = kDefaultPlacementSpacing;
    options.margin = kDefaultPlacementMargin;
    options.walk_min_height = kDefaultWalkMinHeight;
    options.walk_max_height = kDefaultWalkMaxHeight;
    options.error_bound = kDefaultPlacementErrorBound;
    options.rays = kDefaultPlacementRays;
    options.bounces = kDefaultBakeBounces;
    options.light_clearance = kDefaultPlacementLightClearance;
    return options;
}

inline tp_store_load_options default_store_load_options() {
    tp_store_load_options options{};
    options.struct_size = sizeof(tp_store_load_options);
    options.max_file_bytes = kDefaultMaxStoreFileBytes;
    return options;
}

// The file's own unit and up.
inline tp_scene_load_options default_scene_load_options() {
    tp_scene_load_options options{};
    options.struct_size = sizeof(tp_scene_load_options);
    options.up = TP_UP_FILE;
    options.scale = 0.0f;
    return options;
}

// Grey, one-sided, not emissive.
inline tp_material default_material() {
    tp_material material{};
    material.struct_size = sizeof(tp_material);
    material.albedo[0] = material.albedo[1] = material.albedo[2] = kDefaultAlbedo;
    return material;
}

// A baked, shadowing point light (the rest from core/option_defaults.h).
inline tp_light default_light() {
    tp_light light{};
    light.struct_size = sizeof(tp_light);
    light.type = TP_LIGHT_POINT;
    light.mode = TP_LIGHT_MODE_BAKED;
    light.shadows = 1;
    light.color[0] = light.color[1] = light.color[2] = kDefaultLightColor;
    light.intensity = kDefaultLightIntensity;
    for (int a = 0; a < 3; ++a) light.direction[a] = kDefaultLightDirection[a];
    light.range = kDefaultLightRange;
    light.inner_angle = kDefaultSpotInnerAngle;
    light.outer_angle = kDefaultSpotOuterAngle;
    light.near_distance = 0;
    return light;
}

}  // namespace tetprobe
