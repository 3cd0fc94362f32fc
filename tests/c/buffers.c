/* Caller buffers: every size, count and stride that enters the library is checked before anything is read
   or written; one that overflows the address space is refused with TP_ERROR_INVALID_ARGUMENT naming the
   parameter. Strides need no alignment: odd strides at odd addresses answer byte for byte as packed
   buffers do (the library copies every element with memcpy; the sanitizer build would stop at a
   misaligned float access). */
#include "harness.h"

#include <stdint.h>

#define HUGE_STRIDE ((size_t)PTRDIFF_MAX) /* 2 elements at this stride span more than any object */

static void check_refused(tp_status got, const char* word, const char* call, const char* file, int line) {
    char what[512];
    harness_check_status(got, TP_ERROR_INVALID_ARGUMENT, call, file, line);
    snprintf(what, sizeof what, "%s names %s (message: %s)", call, word, tp_last_error());
    harness_check(strstr(tp_last_error(), word) != NULL, what, file, line);
}
#define EXPECT_REFUSED(call, word) check_refused((call), (word), #call, __FILE__, __LINE__)

static int all_equal(const float* values, size_t count, float value) {
    size_t i;
    for (i = 0; i < count; ++i)
        if (values[i] != value) return 0;
    return 1;
}

static void test_query_buffers(tp_store* store) {
    static float points[3 * 64], out[27 * 64], occlusion[4 * 64], weights[4 * 64];
    static uint32_t probes[4 * 64];
    static int32_t hints[64];
    const void* blob;
    size_t size, i;
    tp_store* copy = NULL;
    for (i = 0; i < 3 * 64; ++i) points[i] = uniform(-1.2, 1.2);
    for (i = 0; i < 27 * 64; ++i) out[i] = 7.0f;

    /* A size no object can have: refused before any copy (it used to wrap the allocation's size). */
    EXPECT_OK(tp_store_blob(store, &blob, &size));
    EXPECT_REFUSED(tp_store_load(blob, SIZE_MAX, &copy), "size");
    EXPECT_REFUSED(tp_store_load(blob, SIZE_MAX - 62, &copy), "size");
    EXPECT_REFUSED(tp_store_load(blob, (size_t)PTRDIFF_MAX + 1, &copy), "size");
    CHECK(copy == NULL);

    /* Count times stride that wraps or exceeds the largest object, for every buffer of every batch. */
    EXPECT_REFUSED(tp_store_interpolate_batch(store, 2, points, (size_t)-12, NULL, 0, out, 0, NULL), "position_stride");
    EXPECT_REFUSED(tp_store_interpolate_batch(store, 2, points, HUGE_STRIDE, NULL, 0, out, 0, NULL), "position_stride");
    EXPECT_REFUSED(tp_store_interpolate_batch(store, 2, points, 0, NULL, 0, out, (size_t)-108, NULL), "sh_stride");
    EXPECT_REFUSED(tp_store_interpolate_batch(store, 2, points, 0, hints, HUGE_STRIDE, out, 0, NULL), "hint_stride");
    EXPECT_REFUSED(tp_store_interpolate_batch(store, SIZE_MAX / 12 + 1, points, 0, NULL, 0, out, 0, NULL), "count");
    EXPECT_REFUSED(tp_store_interpolate_occlusion_batch(store, 2, points, 0, NULL, 0, out, 0, occlusion, (size_t)-16, NULL),
                   "occlusion_stride");
    EXPECT_REFUSED(tp_store_weights_batch(store, 2, points, (size_t)-12, NULL, 0, probes, 0, weights, 0, NULL),
                   "position_stride");
    EXPECT_REFUSED(tp_store_weights_batch(store, 2, points, 0, NULL, 0, probes, (size_t)-16, weights, 0, NULL),
                   "probes_stride");
    EXPECT_REFUSED(tp_store_weights_batch(store, 2, points, 0, NULL, 0, probes, 0, weights, HUGE_STRIDE, NULL),
                   "weights_stride");
    CHECK(all_equal(out, 27 * 64, 7.0f)); /* nothing was written */

    /* Strides of odd byte counts at odd addresses: the same answers as packed buffers. */
    {
        enum { N = 64, PS = 13, HS = 5, SS = 109, OS = 17, WS = 17, QS = 19 };
        static unsigned char p_bytes[1 + N * PS], h_bytes[3 + N * HS], s_bytes[1 + N * SS], o_bytes[3 + N * OS];
        static unsigned char w_bytes[1 + N * WS], q_bytes[3 + N * QS];
        static float packed_sh[27 * N], packed_occlusion[4 * N], packed_weights[4 * N];
        static uint32_t packed_probes[4 * N];
        static int32_t packed_hints[N];
        unsigned char *pp = p_bytes + 1, *hp = h_bytes + 3, *sp = s_bytes + 1, *op = o_bytes + 3, *wp = w_bytes + 1,
                      *qp = q_bytes + 3;
        int same = 1;
        for (i = 0; i < N; ++i) {
            const int32_t cold = -1;
            memcpy(pp + i * PS, points + 3 * i, 12);
            memcpy(hp + i * HS, &cold, 4);
            packed_hints[i] = -1;
        }
        EXPECT_OK(tp_store_interpolate_occlusion_batch(store, N, points, 0, packed_hints, 0, packed_sh, 0, packed_occlusion,
                                                       0, NULL));
        EXPECT_OK(tp_store_interpolate_occlusion_batch(store, N, (const float*)(void*)pp, PS, (int32_t*)(void*)hp, HS,
                                                       (float*)(void*)sp, SS, (float*)(void*)op, OS, NULL));
        for (i = 0; i < N; ++i) {
            int32_t hint;
            memcpy(&hint, hp + i * HS, 4);
            same &= memcmp(sp + i * SS, packed_sh + 27 * i, 108) == 0;
            same &= memcmp(op + i * OS, packed_occlusion + 4 * i, 16) == 0;
            same &= hint == packed_hints[i];
        }
        CHECK(same);
        EXPECT_OK(tp_store_interpolate_batch(store, N, (const float*)(void*)pp, PS, NULL, 0, (float*)(void*)sp, SS, NULL));
        for (i = 0; i < N; ++i) same &= memcmp(sp + i * SS, packed_sh + 27 * i, 108) == 0;
        CHECK(same);
        EXPECT_OK(tp_store_weights_batch(store, N, points, 0, NULL, 0, packed_probes, 0, packed_weights, 0, NULL));
        EXPECT_OK(tp_store_weights_batch(store, N, (const float*)(void*)pp, PS, (int32_t*)(void*)hp, HS,
                                         (uint32_t*)(void*)qp, QS, (float*)(void*)wp, WS, NULL));
        for (i = 0; i < N; ++i) {
            same &= memcmp(qp + i * QS, packed_probes + 4 * i, 16) == 0;
            same &= memcmp(wp + i * WS, packed_weights + 4 * i, 16) == 0;
        }
        CHECK(same);
    }
}

static void test_build_buffers(const float* positions) {
    tp_build_options options;
    tp_store *store = NULL, *packed = NULL;
    static unsigned char odd[1 + CLOUD * 13];
    static uint8_t occlusion[4 * CLOUD];
    size_t i;
    EXPECT_REFUSED(tp_store_build(positions, HUGE_STRIDE, NULL, 0, 2, NULL, &store), "position_stride");
    EXPECT_REFUSED(tp_store_build(positions, 0, positions, (size_t)-108, 2, NULL, &store), "sh_stride");
    EXPECT_REFUSED(tp_store_build(positions, 0, NULL, 0, SIZE_MAX / 12 + 1, NULL, &store), "probe_count");
    tp_build_options_init(&options);
    options.occlusion = occlusion;
    options.occlusion_lights = 1;
    options.occlusion_stride = (size_t)-4;
    EXPECT_REFUSED(tp_store_build(positions, 0, NULL, 0, CLOUD, &options, &store), "occlusion_stride");
    CHECK(store == NULL);
    /* Positions at an odd stride and address build the same store as packed ones. */
    for (i = 0; i < CLOUD; ++i) memcpy(odd + 1 + 13 * i, positions + 3 * i, 12);
    EXPECT_OK(tp_store_build(positions, 0, NULL, 0, CLOUD, NULL, &packed));
    EXPECT_OK(tp_store_build((const float*)(void*)(odd + 1), 13, NULL, 0, CLOUD, NULL, &store));
    if (store && packed) {
        const void *a, *b;
        size_t size_a = 0, size_b = 0;
        tp_store_blob(store, &a, &size_a);
        tp_store_blob(packed, &b, &size_b);
        CHECK(size_a == size_b && memcmp(a, b, size_a) == 0);
    }
    tp_store_release(store);
    tp_store_release(packed);
}

static void test_scene_buffers(void) {
    tp_scene* scene = NULL;
    tp_material material;
    const float vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t indices[3] = {0, 1, 2};
    float positions[6] = {0.2f, 0.2f, 1, 0.3f, 0.2f, 1}, out[27 * 2], planes[4 * 8];
    uint8_t occlusion[8];
    uint32_t found[2];
    char text[16];
    size_t count = 0, points = 0;
    tp_material_init(&material);
    EXPECT_OK(tp_scene_create(&scene));
    if (!scene) return;
    EXPECT_REFUSED(tp_scene_add_mesh(scene, vertices, SIZE_MAX / 8, indices, 1, &material, 1, NULL, NULL), "vertex_count");
    EXPECT_REFUSED(tp_scene_add_mesh(scene, vertices, 3, indices, SIZE_MAX / 8, &material, 1, NULL, NULL), "triangle_count");
    EXPECT_REFUSED(tp_scene_add_mesh(scene, vertices, 3, indices, 1, &material, SIZE_MAX / 8, NULL, NULL), "material_count");
    EXPECT_REFUSED(tp_scene_set_probes(scene, positions, SIZE_MAX / 8), "count");
    EXPECT_OK(tp_scene_add_mesh(scene, vertices, 3, indices, 1, &material, 1, NULL, NULL));
    EXPECT_REFUSED(tp_bake(scene, positions, 0, 2, NULL, out, HUGE_STRIDE), "sh_stride");
    EXPECT_REFUSED(tp_bake(scene, positions, HUGE_STRIDE, 2, NULL, out, 0), "position_stride");
    EXPECT_REFUSED(tp_bake_occlusion(scene, positions, 0, 2, NULL, occlusion, (size_t)-4, NULL), "occlusion_stride");
    {
        tp_effects_plan plan;
        memset(&plan, 0, sizeof plan);
        plan.struct_size = sizeof plan;
        EXPECT_REFUSED(tp_bake_plan(scene, positions, 0, 2, NULL, &plan, text, SIZE_MAX), "text_capacity");
    }
    EXPECT_REFUSED(tp_find_inside_probes(scene, positions, 0, 2, found, SIZE_MAX / 2, &count), "capacity");
    EXPECT_REFUSED(tp_fix_inside_probes(scene, positions, 0, 2, TP_INSIDE_DROP, 0.1f, positions, SIZE_MAX / 8, &count),
                   "capacity");
    EXPECT_REFUSED(tp_place_probes(scene, NULL, positions, SIZE_MAX / 8, &count, NULL, 0, &points), "capacity");
    EXPECT_REFUSED(tp_place_probes(scene, NULL, positions, 2, &count, out, SIZE_MAX / 4, &points), "curve_capacity");
    tp_scene_release(scene);

    /* Volumes: plane counts and capacities; the bound saturates instead of wrapping. */
    {
        const float box_min[3] = {0, 0, 0}, box_max[3] = {1, 1, 1}, light[3] = {0, -1, 0};
        int hit = 0;
        memset(planes, 0, sizeof planes);
        EXPECT_REFUSED(tp_volume_test_aabb(planes, SIZE_MAX / 8, box_min, box_max, &hit), "plane_count");
        EXPECT_REFUSED(tp_volume_test_sphere(planes, SIZE_MAX / 8, box_min, 1.0f, &hit), "plane_count");
        EXPECT_REFUSED(tp_shadow_caster_volume(planes, 2, TP_LIGHT_DIRECTIONAL, light, planes, SIZE_MAX / 8, &count),
                       "capacity");
        CHECK(tp_shadow_caster_volume_bound(SIZE_MAX / 2) == SIZE_MAX);
        CHECK(tp_shadow_caster_volume_bound(6) == 25);
    }
}

void test_buffer_sizes_and_strides(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    tp_store* store = build_cloud(positions, sh, 0);
    if (!store) return;
    test_query_buffers(store);
    test_build_buffers(positions);
    test_scene_buffers();
    tp_store_release(store);
}
