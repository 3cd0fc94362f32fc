/* The run-time library: every bake-time entry point exists (both libraries export the same names) and
   refuses with TP_ERROR_UNSUPPORTED and a message naming itself, clearing its outputs. */
#include "harness.h"

static void expect_unsupported(tp_status status, const char* function, const char* call, int line) {
    harness_check_status(status, TP_ERROR_UNSUPPORTED, call, __FILE__, line);
    harness_check(strstr(tp_last_error(), function) != NULL, "the message names the function", __FILE__, line);
}

#define EXPECT_UNSUPPORTED(function, call) expect_unsupported((call), #function, #call, __LINE__)

void test_runtime_library_refuses_bake_time(void) {
    const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t indices[3] = {0, 1, 2};
    const float rgb[3] = {1, 1, 1};
    float sh[27], out[27];
    tp_store* store = (tp_store*)(void*)&out; /* a non-NULL garbage value the call must clear */
    tp_scene* scene = (tp_scene*)(void*)&out;
    tp_material material;
    tp_light light;
    tp_bake_options options;
    tp_effects_plan plan;
    const float* listed = positions;
    size_t listed_count = 7;
    uint32_t id = 0;
    char text[32] = "untouched";
    memset(sh, 0, sizeof sh);
    tp_material_init(&material);
    tp_light_init(&light);
    tp_bake_options_init(&options);
    memset(&plan, 0, sizeof plan);
    plan.struct_size = sizeof plan;

    EXPECT_UNSUPPORTED(tp_store_build, tp_store_build(positions, 0, NULL, 0, 4, NULL, &store));
    CHECK(store == NULL);
    EXPECT_UNSUPPORTED(tp_scene_create, tp_scene_create(&scene));
    CHECK(scene == NULL);
    scene = (tp_scene*)(void*)&out;
    EXPECT_UNSUPPORTED(tp_scene_load_file, tp_scene_load_file("scene.json", &scene));
    CHECK(scene == NULL);
    {
        tp_scene_load_options load_options;
        char notes[8] = "notes";
        size_t notes_size = 7;
        uint32_t up = 7;
        EXPECT_OK(tp_scene_load_options_init(&load_options));
        CHECK(load_options.struct_size == sizeof load_options && load_options.up == TP_UP_FILE);
        scene = (tp_scene*)(void*)&out;
        EXPECT_UNSUPPORTED(tp_scene_load_file_ex, tp_scene_load_file_ex("scene.gltf", &load_options, &scene));
        CHECK(scene == NULL);
        EXPECT_UNSUPPORTED(tp_scene_notes, tp_scene_notes(NULL, notes, sizeof notes, &notes_size));
        CHECK(notes[0] == '\0' && notes_size == 0);
        EXPECT_UNSUPPORTED(tp_scene_up, tp_scene_up(NULL, &up));
        CHECK(up == TP_UP_FILE);
        EXPECT_UNSUPPORTED(tp_scene_set_up, tp_scene_set_up(NULL, TP_UP_POS_Z));
    }
    EXPECT_OK(tp_scene_release(NULL));
    /* No scene can exist here, so every function taking one refuses whatever it is given. */
    EXPECT_UNSUPPORTED(tp_scene_add_mesh, tp_scene_add_mesh(NULL, positions, 4, indices, 1, &material, 1, NULL, &id));
    EXPECT_UNSUPPORTED(tp_scene_add_light, tp_scene_add_light(NULL, &light, &id));
    EXPECT_UNSUPPORTED(tp_scene_set_sky_color, tp_scene_set_sky_color(NULL, rgb));
    EXPECT_UNSUPPORTED(tp_scene_set_sky_sh, tp_scene_set_sky_sh(NULL, sh));
    EXPECT_UNSUPPORTED(tp_scene_probes, tp_scene_probes(NULL, &listed, &listed_count));
    CHECK(listed == NULL && listed_count == 0);
    EXPECT_UNSUPPORTED(tp_scene_set_probes, tp_scene_set_probes(NULL, positions, 4));
    EXPECT_UNSUPPORTED(tp_scene_set_playable_seeds, tp_scene_set_playable_seeds(NULL, positions, 4));
    EXPECT_UNSUPPORTED(tp_bake_plan, tp_bake_plan(NULL, positions, 0, 4, &options, &plan, text, sizeof text));
    CHECK(text[0] == '\0');
    EXPECT_UNSUPPORTED(tp_bake, tp_bake(NULL, positions, 0, 4, &options, out, 0));
    {
        unsigned char occlusion[16];
        uint32_t mixed_lights = 7;
        memset(occlusion, 0x5A, sizeof occlusion);
        EXPECT_UNSUPPORTED(tp_bake_occlusion,
                           tp_bake_occlusion(NULL, positions, 0, 4, &options, occlusion, 0, &mixed_lights));
        CHECK(occlusion[0] == 0x5A && mixed_lights == 0);
    }
    {
        tp_placement_options placement;
        float placed[6] = {42.0f, 0, 0, 0, 0, 0};
        uint32_t inside[2] = {99, 99};
        size_t bound = 7, count = 7, points = 7;
        EXPECT_OK(tp_placement_options_init(&placement));
        CHECK(placement.struct_size == sizeof placement && placement.spacing > 0.0f);
        EXPECT_UNSUPPORTED(tp_place_probes_bound, tp_place_probes_bound(NULL, &placement, &bound));
        CHECK(bound == 0);
        EXPECT_UNSUPPORTED(tp_place_probes, tp_place_probes(NULL, &placement, placed, 2, &count, NULL, 0, &points));
        CHECK(count == 0 && points == 0 && placed[0] == 42.0f);
        count = 7;
        EXPECT_UNSUPPORTED(tp_find_inside_probes, tp_find_inside_probes(NULL, positions, 0, 2, inside, 2, &count));
        CHECK(count == 0 && inside[0] == 99);
        count = 7;
        EXPECT_UNSUPPORTED(tp_fix_inside_probes,
                           tp_fix_inside_probes(NULL, positions, 0, 2, TP_INSIDE_DROP, 0.1f, placed, 2, &count));
        CHECK(count == 0 && placed[0] == 42.0f);
    }
    /* The run-time functions still work after a refusal, and the message is cleared. */
    EXPECT_OK(tp_sh_add_ambient(sh, rgb));
    CHECK(tp_last_error()[0] == '\0');
}
