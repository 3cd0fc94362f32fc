// The initialisers of the public structs, in both libraries (core/option_defaults.h holds the values).
#include "capi/boundary.h"
#include "capi/sh_eval_options_struct.h"
#include "capi/struct_defaults.h"

extern "C" {

TP_API tp_status tp_build_options_init(tp_build_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(options);
    *options = tetprobe::default_build_options();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_bake_options_init(tp_bake_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(options);
    *options = tetprobe::default_bake_options();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_placement_options_init(tp_placement_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(options);
    *options = tetprobe::default_placement_options();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_load_options_init(tp_store_load_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(options);
    *options = tetprobe::default_store_load_options();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_material_init(tp_material* material) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(material);
    *material = tetprobe::default_material();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_light_init(tp_light* light) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(light);
    *light = tetprobe::default_light();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_scene_load_options_init(tp_scene_load_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(options);
    *options = tetprobe::default_scene_load_options();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_eval_options_init(tp_sh_eval_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(options);
    *options = tetprobe::default_sh_eval_options();
    return TP_OK;
    TP_API_END
}

}  // extern "C"
