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
    CHECK(info.format_version == 6 && info.occlusion_lights == 1 && info.leak_edges > 0);
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

/* ---- Occlusion against shadow rays traced here, blends against the query's own weights, leak control
   against plain interpolation. The scene: the wall x = 0.37, y in [-10, 0.6], z in [-10, 10]. */

static const float kWall[12] = {0.37f, -10, -10, 0.37f, 0.6f, -10, 0.37f, 0.6f, 10, 0.37f, -10, 10};

static tp_scene* wall_scene(void) {
    static const uint32_t triangles[6] = {0, 1, 2, 0, 2, 3};
    tp_scene* scene = NULL;
    tp_material material;
    EXPECT_OK(tp_scene_create(&scene));
    if (!scene) return NULL;
    tp_material_init(&material);
    material.two_sided = 1;
    EXPECT_OK(tp_scene_add_mesh(scene, kWall, 4, triangles, 2, &material, 1, NULL, NULL));
    return scene;
}

/* Whether the segment from p to q crosses the wall; *margin receives how far (in y or z) the crossing
   is from the wall's edge, so that cases too close to call are left out. */
static int wall_blocks(const double p[3], const double q[3], double* margin) {
    double t, y, z;
    *margin = INFINITY;
    if ((p[0] - 0.37) * (q[0] - 0.37) >= 0.0) return 0;
    t = (0.37 - p[0]) / (q[0] - p[0]);
    y = p[1] + t * (q[1] - p[1]);
    z = p[2] + t * (q[2] - p[2]);
    *margin = fmin(fabs(y - 0.6), fabs(fabs(z) - 10.0));
    return y <= 0.6 && y >= -10.0 && fabs(z) <= 10.0;
}

static int cancel_now(void* user, float fraction, const char* stage) {
    (void)fraction;
    (void)stage;
    ++*(int*)user;
    return 1;
}

static void lattice(float* probes) {
    int i, j, k, n = 0;
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 5; ++j)
            for (k = 0; k < 5; ++k, ++n) {
                probes[3 * n] = (float)(i - 2);
                probes[3 * n + 1] = (float)(j - 2);
                probes[3 * n + 2] = (float)(k - 2);
            }
}

void test_occlusion_bake_and_blend(void) {
    tp_scene* scene = wall_scene();
    tp_light light;
    tp_bake_options bake;
    tp_build_options options;
    tp_store *store = NULL, *bounded = NULL;
    float probes[125 * 3], sh[125 * 27], strided[125 * 4];
    unsigned char occlusion[125 * 4], wide[125 * 8];
    const float point[3] = {3.0f, -1.5f, 0.5f};
    uint32_t lights = 99;
    int n, c, checked = 0;
    if (!scene) return;
    lattice(probes);
    for (n = 0; n < 125; ++n) {
        memcpy(strided + 4 * n, probes + 3 * n, 3 * sizeof(float));
        strided[4 * n + 3] = -1.0f;
        for (c = 0; c < 27; ++c) sh[27 * n + c] = linear_field(c, probes + 3 * n);
    }

    /* Mixed lights, in this order: a sun travelling +x, a point light behind the wall, a point light
       without shadows; a baked light between them is not a channel. */
    tp_light_init(&light);
    light.type = TP_LIGHT_DIRECTIONAL;
    light.mode = TP_LIGHT_MODE_MIXED;
    light.direction[0] = 1.0f, light.direction[1] = 0.0f, light.direction[2] = 0.0f;
    EXPECT_OK(tp_scene_add_light(scene, &light, NULL));
    tp_light_init(&light);
    light.mode = TP_LIGHT_MODE_BAKED;
    EXPECT_OK(tp_scene_add_light(scene, &light, NULL));
    tp_light_init(&light);
    light.mode = TP_LIGHT_MODE_MIXED;
    memcpy(light.position, point, sizeof point);
    EXPECT_OK(tp_scene_add_light(scene, &light, NULL));
    light.shadows = 0;
    EXPECT_OK(tp_scene_add_light(scene, &light, NULL));

    memset(occlusion, 0x5A, sizeof occlusion);
    EXPECT_OK(tp_bake_occlusion(scene, probes, 0, 125, NULL, occlusion, 0, &lights));
    CHECK(lights == 3);
    for (n = 0; n < 125; ++n) {
        const double p[3] = {probes[3 * n], probes[3 * n + 1], probes[3 * n + 2]};
        const double sun[3] = {p[0] - 100.0, p[1], p[2]};
        const double lamp[3] = {point[0], point[1], point[2]};
        double margin_sun, margin_lamp;
        const int sun_blocked = wall_blocks(p, sun, &margin_sun), lamp_blocked = wall_blocks(p, lamp, &margin_lamp);
        if (margin_sun > 1e-3) CHECK(occlusion[4 * n] == (sun_blocked ? 0 : 255));
        if (margin_lamp > 1e-3) CHECK(occlusion[4 * n + 1] == (lamp_blocked ? 0 : 255));
        checked += margin_sun > 1e-3 && margin_lamp > 1e-3 && sun_blocked != lamp_blocked;
        CHECK(occlusion[4 * n + 2] == 255 && occlusion[4 * n + 3] == 255);
    }
    CHECK(checked > 10); /* the two shadowing lights disagree on many probes */
    /* Strided positions and output: the same bytes, the gaps untouched. */
    memset(wide, 0x5A, sizeof wide);
    EXPECT_OK(tp_bake_occlusion(scene, strided, 16, 125, NULL, wide, 8, NULL));
    for (n = 0; n < 125; ++n) {
        CHECK(memcmp(wide + 8 * n, occlusion + 4 * n, 4) == 0);
        CHECK(wide[8 * n + 4] == 0x5A && wide[8 * n + 7] == 0x5A);
    }

    /* Errors; a cancel writes nothing. */
    {
        int calls = 0;
        unsigned char untouched[125 * 4];
        float bad[3] = {0.0f, 0.0f, 0.0f};
        bad[1] = (float)NAN;
        memset(untouched, 0x5A, sizeof untouched);
        uint32_t cancelled_lights = 99;
        memcpy(wide, untouched, sizeof untouched);
        tp_bake_options_init(&bake);
        bake.progress = cancel_now;
        bake.progress_user = &calls;
        EXPECT_STATUS(tp_bake_occlusion(scene, probes, 0, 125, &bake, wide, 0, &cancelled_lights), TP_ERROR_CANCELLED);
        CHECK(calls >= 1 && cancelled_lights == 99 && memcmp(wide, untouched, sizeof untouched) == 0);
        EXPECT_STATUS(tp_bake_occlusion(NULL, probes, 0, 125, NULL, wide, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_bake_occlusion(scene, probes, 0, 125, NULL, NULL, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_bake_occlusion(scene, NULL, 0, 125, NULL, wide, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_bake_occlusion(scene, bad, 0, 1, NULL, wide, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_bake_occlusion(scene, probes, 0, 125, NULL, wide, 2, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_bake_occlusion(scene, probes, 8, 125, NULL, wide, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
        CHECK(memcmp(wide, untouched, sizeof untouched) == 0);
    }

    /* A store with the occlusion, no scene: queries blend the bytes with the query's own weights, and
       the SH is tp_store_interpolate's bit for bit. */
    tp_build_options_init(&options);
    options.occlusion = occlusion;
    options.occlusion_lights = lights;
    options.flags = TP_BUILD_NO_EXTRAPOLATION;
    EXPECT_OK(tp_store_build(probes, 0, sh, 0, 125, &options, &store));
    if (!store) {
        tp_scene_release(scene);
        return;
    }
    CHECK(info_of(store).occlusion_lights == 3 && info_of(store).leak_edges == 0 && info_of(store).format_version == 6);
    {
        float queries[64 * 3], batch_sh[64 * 27], batch_occ[64 * 8], one_sh[27], plain_sh[27], occ[4];
        int32_t hint = -1;
        int q, k;
        for (q = 0; q < 64; ++q)
            for (k = 0; k < 3; ++k) queries[3 * q + k] = uniform(-1.95, 1.95);
        for (q = 0; q < 64; ++q) {
            uint32_t slots[4];
            float weights[4];
            EXPECT_OK(tp_store_interpolate_occlusion(store, queries + 3 * q, &hint, one_sh, occ));
            EXPECT_OK(tp_store_interpolate(store, queries + 3 * q, NULL, plain_sh));
            CHECK(memcmp(one_sh, plain_sh, sizeof plain_sh) == 0);
            EXPECT_OK(tp_store_weights(store, queries + 3 * q, NULL, slots, weights));
            for (c = 0; c < 4; ++c) {
                double expected = 0.0;
                for (k = 0; k < 4; ++k) expected += weights[k] * (occlusion[4 * slots[k] + c] / 255.0);
                CHECK_NEAR(occ[c], expected, 1e-6);
                CHECK(occ[c] >= 0.0f && occ[c] <= 1.0f);
            }
            CHECK(occ[3] == 1.0f); /* no mixed light: exactly 1 */
        }
        /* The batch, strided (8 floats per occlusion), answers as the single queries, bit for bit. */
        memset(batch_occ, 0, sizeof batch_occ);
        EXPECT_OK(tp_store_interpolate_occlusion_batch(store, 64, queries, 0, NULL, 0, batch_sh, 0, batch_occ, 32, NULL));
        for (q = 0; q < 64; ++q) {
            EXPECT_OK(tp_store_interpolate_occlusion(store, queries + 3 * q, NULL, one_sh, occ));
            CHECK(memcmp(batch_sh + 27 * q, one_sh, sizeof one_sh) == 0);
            CHECK(memcmp(batch_occ + 8 * q, occ, sizeof occ) == 0);
            CHECK(batch_occ[8 * q + 4] == 0.0f);
        }
        /* At a probe: its own byte. */
        EXPECT_OK(tp_store_interpolate_occlusion(store, probes + 3 * 100, NULL, one_sh, occ));
        CHECK_NEAR(occ[0], occlusion[400] / 255.0, 1e-6);
        /* Outside (no extrapolation): TP_ERROR_OUTSIDE, SH and occlusion zero. */
        {
            const float far[3] = {5.0f, 0.0f, 0.0f};
            float outside_pair[6] = {0.5f, 0.5f, 0.5f, 5.0f, 0.0f, 0.0f};
            for (c = 0; c < 4; ++c) occ[c] = 7.0f;
            EXPECT_STATUS(tp_store_interpolate_occlusion(store, far, NULL, one_sh, occ), TP_ERROR_OUTSIDE);
            CHECK(occ[0] == 0.0f && occ[1] == 0.0f && occ[2] == 0.0f && occ[3] == 0.0f && one_sh[0] == 0.0f);
            EXPECT_STATUS(tp_store_interpolate_occlusion_batch(store, 2, outside_pair, 0, NULL, 0, batch_sh, 0, batch_occ,
                                                               0, NULL),
                          TP_ERROR_OUTSIDE);
            CHECK(batch_occ[4] == 0.0f && batch_occ[7] == 0.0f && batch_occ[0] > 0.0f);
        }
        /* Errors. */
        EXPECT_STATUS(tp_store_interpolate_occlusion(NULL, queries, NULL, one_sh, occ), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_occlusion(store, NULL, NULL, one_sh, occ), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_occlusion(store, queries, NULL, NULL, occ), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_occlusion_batch(store, 64, queries, 0, NULL, 0, batch_sh, 0, NULL, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_occlusion_batch(store, 64, queries, 0, NULL, 0, batch_sh, 0, batch_occ, 8, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_occlusion_batch(NULL, 64, queries, 0, NULL, 0, batch_sh, 0, batch_occ, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
    }
    /* Build errors: no channel, a stride below 4 bytes; the store pointer is cleared. */
    bounded = (tp_store*)(void*)&options;
    options.occlusion_lights = 0;
    EXPECT_FAILS(tp_store_build(probes, 0, sh, 0, 125, &options, &bounded));
    CHECK(bounded == NULL);
    options.occlusion_lights = 3;
    options.occlusion_stride = 2;
    EXPECT_STATUS(tp_store_build(probes, 0, sh, 0, 125, &options, &bounded), TP_ERROR_INVALID_ARGUMENT);
    CHECK(bounded == NULL);
    tp_store_release(store);
    tp_scene_release(scene);
}

/* Leak control against the same store without it: cells with no blocked pair answer bit for bit, probes
   answer exactly, and next to the wall the field leans to the query's own side. */
void test_leak_control_queries(void) {
    tp_scene* scene = wall_scene();
    tp_build_options options;
    tp_store *leaky = NULL, *guarded = NULL;
    float probes[125 * 3], sh[125 * 27], a[27], b[27], stored[27];
    int n, c;
    if (!scene) return;
    lattice(probes);
    /* Coefficient 0 of every channel is x: the plain interpolation reproduces it exactly. */
    for (n = 0; n < 125; ++n)
        for (c = 0; c < 27; ++c) sh[27 * n + c] = c % 9 == 0 ? probes[3 * n] : linear_field(c, probes + 3 * n);
    EXPECT_OK(tp_store_build(probes, 0, sh, 0, 125, NULL, &leaky));
    tp_build_options_init(&options);
    options.scene = scene;
    EXPECT_OK(tp_store_build(probes, 0, sh, 0, 125, &options, &guarded));
    if (!leaky || !guarded) {
        tp_store_release(leaky);
        tp_store_release(guarded);
        tp_scene_release(scene);
        return;
    }
    CHECK(info_of(guarded).leak_edges > 0 && info_of(leaky).leak_edges == 0);
    {
        /* Far from the wall (x < -1 or above y = 1): no cell has a blocked pair. */
        int q;
        for (q = 0; q < 40; ++q) {
            float p[3];
            p[0] = uniform(-2.0, -1.05);
            p[1] = uniform(-2.0, 2.0);
            p[2] = uniform(-2.0, 2.0);
            if (q % 2) p[0] = uniform(-2.0, 2.0), p[1] = uniform(1.05, 2.0);
            EXPECT_OK(tp_store_interpolate(leaky, p, NULL, a));
            EXPECT_OK(tp_store_interpolate(guarded, p, NULL, b));
            CHECK(memcmp(a, b, sizeof a) == 0);
        }
        /* At every probe: the probe's own SH (half precision), with and without leak control. */
        for (n = 0; n < 125; ++n) {
            EXPECT_OK(tp_store_probe_sh(guarded, (uint32_t)n, stored));
            EXPECT_OK(tp_store_interpolate(guarded, probes + 3 * n, NULL, b));
            for (c = 0; c < 27; c += 9) CHECK_NEAR(b[c], stored[c], 1e-6);
        }
        /* Beside the wall, below its top: x before it leans to x = 0, behind it to x = 1. */
        {
            const float before[3] = {0.2f, -1.5f, 0.3f}, after[3] = {0.6f, -1.5f, 0.3f};
            EXPECT_OK(tp_store_interpolate(leaky, before, NULL, a));
            EXPECT_OK(tp_store_interpolate(guarded, before, NULL, b));
            CHECK_NEAR(a[0], 0.2, sh_tolerance(0.2));
            CHECK(b[0] < a[0] - 0.01f && b[0] >= -1e-3f);
            EXPECT_OK(tp_store_interpolate(leaky, after, NULL, a));
            EXPECT_OK(tp_store_interpolate(guarded, after, NULL, b));
            CHECK_NEAR(a[0], 0.6, sh_tolerance(0.6));
            CHECK(b[0] > a[0] + 0.01f && b[0] <= 1.0f + 1e-3f);
        }
        /* Continuous along x except at the wall's plane, where the answer steps from the side of x = 0 to
           that of x = 1: away from it halving the step halves the largest jump; the step at the wall stays. */
        {
            double jump[2] = {0.0, 0.0}, wall_step[2] = {0.0, 0.0};
            int level, i;
            for (level = 0; level < 2; ++level) {
                const int steps = 400 << level;
                float previous = 0.0f;
                for (i = 0; i <= steps; ++i) {
                    float p[3];
                    p[0] = (float)(i / (double)steps);
                    p[1] = -1.5f;
                    p[2] = 0.3f;
                    if (p[0] == 0.37f) continue; /* on the wall's plane: behind it from both sides */
                    EXPECT_OK(tp_store_interpolate(guarded, p, NULL, b));
                    if (i > 0 && (i - 1) / (double)steps < 0.37f && p[0] > 0.37f)
                        wall_step[level] = b[0] - previous;
                    else if (i > 0)
                        jump[level] = fmax(jump[level], fabs(b[0] - previous));
                    previous = b[0];
                }
            }
            CHECK(jump[1] < 0.75 * jump[0] && jump[0] < 0.2);
            CHECK(wall_step[0] > 0.2 && wall_step[1] > 0.2);
        }
    }
    tp_store_release(leaky);
    tp_store_release(guarded);
    tp_scene_release(scene);
}
