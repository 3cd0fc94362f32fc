/*
 * Format 4's scene data through the C ABI: occlusion probes of a mixed light behind a wall
 * (tp_bake_occlusion, the build options' occlusion and scene, tp_store_interpolate_occlusion and its
 * batch), leak control built from the scene, and the documented errors (a fifth mixed light, more
 * than four occlusion channels, a missing output).
 */
#include "harness.h"

/* Format 4 scene data: occlusion probes of a mixed light behind a wall, and leak control from the scene. */
void test_occlusion_and_leak_control(void) {
    tp_scene* scene = NULL;
    tp_material material;
    tp_light light;
    tp_build_options options;
    tp_store *plain = NULL, *store = NULL;
    tp_store_info info;
    float probes[125 * 3], sh[27], visible[4], batch_visible[2 * 4], batch_sh[2 * 27];
    unsigned char occlusion[125 * 4];
    const float wall[12] = {0.37f, -10, -10, 0.37f, 0.6f, -10, 0.37f, 0.6f, 10, 0.37f, -10, 10};
    const uint32_t triangles[6] = {0, 1, 2, 0, 2, 3};
    const float behind[3] = {1.5f, -1.5f, 0.2f}, lit[3] = {-1.5f, -1.5f, 0.2f}, both[6] = {1.5f, -1.5f, 0.2f, -1.5f, -1.5f, 0.2f};
    uint32_t lights = 9, index;
    int i, j, k, n = 0;
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 5; ++j)
            for (k = 0; k < 5; ++k, ++n) {
                probes[3 * n] = (float)(i - 2);
                probes[3 * n + 1] = (float)(j - 2);
                probes[3 * n + 2] = (float)(k - 2);
            }
    EXPECT_OK(tp_scene_create(&scene));
    EXPECT_OK(tp_material_init(&material));
    material.two_sided = 1;
    EXPECT_OK(tp_scene_add_mesh(scene, wall, 4, triangles, 2, &material, 1, NULL, &index));
    EXPECT_OK(tp_light_init(&light));
    light.type = TP_LIGHT_DIRECTIONAL;
    light.direction[0] = 1, light.direction[1] = 0, light.direction[2] = 0;
    light.mode = TP_LIGHT_MODE_MIXED;
    EXPECT_OK(tp_scene_add_light(scene, &light, &index));
    EXPECT_OK(tp_bake_occlusion(scene, probes, 0, 125, NULL, occlusion, 0, &lights));
    CHECK(lights == 1);
    /* (2,-2,-2) is behind the wall, (-2,-2,-2) before it, (2,2,2) above it. */
    CHECK(occlusion[4 * 100] == 0 && occlusion[0] == 255 && occlusion[4 * 124] == 255 && occlusion[4 * 100 + 1] == 255);

    EXPECT_OK(tp_build_options_init(&options));
    CHECK(options.occlusion == NULL && options.scene == NULL);
    options.occlusion = occlusion;
    options.occlusion_lights = lights;
    options.scene = scene;
    EXPECT_OK(tp_store_build(probes, 0, NULL, 0, 125, &options, &store));
    EXPECT_OK(tp_store_build(probes, 0, NULL, 0, 125, NULL, &plain));
    info.struct_size = sizeof info;
    EXPECT_OK(tp_store_get_info(store, &info));
    CHECK(info.format_version == 4 && info.occlusion_lights == 1 && info.leak_edges > 0);
    CHECK((info.flags & ~(uint32_t)(TP_BUILD_NO_EXTRAPOLATION | TP_BUILD_INDEX32 | TP_BUILD_COMPACT)) == 0);
    EXPECT_OK(tp_store_interpolate_occlusion(store, behind, NULL, sh, visible));
    CHECK(visible[0] == 0.0f && visible[1] == 1.0f && visible[3] == 1.0f);
    EXPECT_OK(tp_store_interpolate_occlusion(store, lit, NULL, sh, visible));
    CHECK_NEAR(visible[0], 1.0, 1e-6);
    EXPECT_OK(tp_store_interpolate_occlusion_batch(store, 2, both, 0, NULL, 0, batch_sh, 0, batch_visible, 0, NULL));
    CHECK(batch_visible[0] == 0.0f);
    CHECK_NEAR(batch_visible[4], 1.0, 1e-6);
    EXPECT_OK(tp_store_interpolate_occlusion(plain, behind, NULL, sh, visible));
    CHECK(visible[0] == 1.0f); /* no occlusion data: nothing known to shadow */
    EXPECT_STATUS(tp_store_interpolate_occlusion(store, behind, NULL, sh, NULL), TP_ERROR_INVALID_ARGUMENT);
    tp_store_release(plain);
    plain = NULL;
    options.occlusion_lights = 5;
    EXPECT_STATUS(tp_store_build(probes, 0, NULL, 0, 125, &options, &plain), TP_ERROR_INVALID_ARGUMENT);
    CHECK(plain == NULL);
    light.position[0] = 1;
    for (i = 0; i < 3; ++i) EXPECT_OK(tp_scene_add_light(scene, &light, &index));
    EXPECT_STATUS(tp_scene_add_light(scene, &light, &index), TP_ERROR_SCENE); /* a fifth mixed light */
    tp_store_release(store);
    tp_scene_release(scene);
}
