/* tp_store_build: argument errors, progress and cancelling, info and struct_size, small sets. */
#include "harness.h"

void test_store_build_errors(void) {
    float positions[3 * 8], sh[27 * 8];
    tp_store* store = NULL;
    tp_build_options options;
    make_cloud(positions, sh, 8);
    EXPECT_STATUS(tp_store_build(NULL, 0, sh, 0, 8, NULL, &store), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, 8, NULL, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, 0, NULL, &store), TP_ERROR_DEGENERATE);
    EXPECT_STATUS(tp_store_build(positions, 8, sh, 0, 8, NULL, &store), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 100, 8, NULL, &store), TP_ERROR_INVALID_ARGUMENT);
    positions[4] = (float)NAN;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, 8, NULL, &store), TP_ERROR_INVALID_ARGUMENT);
    positions[4] = (float)INFINITY;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, 8, NULL, &store), TP_ERROR_INVALID_ARGUMENT);
    positions[4] = 1.0f;
    sh[30] = (float)NAN;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, 8, NULL, &store), TP_ERROR_INVALID_ARGUMENT);
    sh[30] = 0.0f;
    tp_build_options_init(&options);
    options.struct_size = 0;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, 8, &options, &store), TP_ERROR_INVALID_ARGUMENT);
    tp_build_options_init(&options);
    options.merge_tolerance = -1.0;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, 8, &options, &store), TP_ERROR_INVALID_ARGUMENT);
    CHECK(store == NULL);
    EXPECT_OK(tp_store_release(NULL));
}

static int cancel_after_first(void* user, float fraction, const char* stage) {
    int* calls = (int*)user;
    ++*calls;
    (void)stage;
    return fraction >= 0.0f ? 1 : 1;
}

static int count_progress(void* user, float fraction, const char* stage) {
    int* calls = (int*)user;
    if (fraction < 0.0f || fraction > 1.0f || stage == NULL) calls[1] = 1;
    ++calls[0];
    return 0;
}

void test_store_build_progress(void) {
    float positions[3 * CLOUD];
    tp_build_options options;
    tp_store* store = NULL;
    int calls[2] = {0, 0};
    int cancel_calls = 0;
    make_cloud(positions, NULL, CLOUD);
    tp_build_options_init(&options);
    options.progress = count_progress;
    options.progress_user = calls;
    EXPECT_OK(tp_store_build(positions, 0, NULL, 0, CLOUD, &options, &store));
    CHECK(calls[0] > 0);
    CHECK(calls[1] == 0);
    tp_store_release(store);
    store = NULL;
    options.progress = cancel_after_first;
    options.progress_user = &cancel_calls;
    EXPECT_STATUS(tp_store_build(positions, 0, NULL, 0, CLOUD, &options, &store), TP_ERROR_CANCELLED);
    CHECK(cancel_calls == 1);
    CHECK(store == NULL);
}

void test_store_info_and_struct_size(void) {
    static float positions[3 * (CLOUD + 3)], sh[27 * (CLOUD + 3)];
    tp_store *store = NULL, *store32 = NULL;
    tp_store_info info;
    tp_build_options options;
    const void* blob;
    size_t size;
    int k;
    make_cloud(positions, sh, CLOUD);
    /* Three copy-pasted probes: they merge into their originals. */
    memcpy(positions + 3 * CLOUD, positions + 3 * 10, 12);
    memcpy(positions + 3 * (CLOUD + 1), positions + 3 * 20, 12);
    memcpy(positions + 3 * (CLOUD + 2), positions + 3 * 20, 12);
    memcpy(sh + 27 * CLOUD, sh + 27 * 10, 108);
    memcpy(sh + 27 * (CLOUD + 1), sh + 27 * 20, 108);
    memcpy(sh + 27 * (CLOUD + 2), sh + 27 * 20, 108);
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD + 3, NULL, &store));
    if (!store) return;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    EXPECT_OK(tp_store_get_info(store, &info));
    EXPECT_OK(tp_store_blob(store, &blob, &size));
    CHECK(info.format_version == 6);
    CHECK(info.dimension == 3);
    CHECK(info.input_probes == CLOUD + 3);
    CHECK(info.probes == CLOUD);
    CHECK(info.merged_probes == 3);
    CHECK(info.cells == info.inner_cells + info.outer_cells);
    CHECK(info.inner_cells > 0);
    CHECK(info.outer_cells == 12); /* the cube's hull: 6 faces, 2 triangles each */
    CHECK(info.index_bits == 16);
    CHECK(info.flags == 0);
    CHECK(info.grid[0] >= 1 && info.grid[1] >= 1 && info.grid[2] >= 1);
    CHECK(info.bytes == size);
    for (k = 0; k < 3; ++k) {
        CHECK_NEAR(info.bounds_min[k], -1.0, 1e-6);
        CHECK_NEAR(info.bounds_max[k], 1.0, 1e-6);
        CHECK(isfinite(info.origin[k]));
    }
    /* A merged probe reads its survivor's SH. */
    {
        float a[27], b[27];
        EXPECT_OK(tp_store_probe_sh(store, CLOUD + 2, a));
        EXPECT_OK(tp_store_probe_sh(store, 20, b));
        CHECK(memcmp(a, b, sizeof a) == 0);
    }

    /* struct_size: a shorter (older) struct gets only its own fields; a longer one keeps its tail. */
    {
        struct {
            tp_store_info info;
            uint32_t tail[4];
        } longer;
        unsigned char bytes[sizeof(tp_store_info)];
        size_t prefix = offsetof(tp_store_info, probes) + sizeof(uint32_t);
        size_t i;
        int untouched = 1;
        memset(bytes, 0xCD, sizeof bytes);
        ((tp_store_info*)(void*)bytes)->struct_size = (uint32_t)prefix;
        EXPECT_OK(tp_store_get_info(store, (tp_store_info*)(void*)bytes));
        CHECK(((tp_store_info*)(void*)bytes)->probes == CLOUD);
        CHECK(((tp_store_info*)(void*)bytes)->dimension == 3);
        for (i = prefix; i < sizeof bytes; ++i) untouched &= bytes[i] == 0xCD;
        CHECK(untouched);
        memset(&longer, 0xEE, sizeof longer);
        longer.info.struct_size = sizeof longer;
        EXPECT_OK(tp_store_get_info(store, &longer.info));
        CHECK(longer.info.probes == CLOUD);
        CHECK(longer.tail[0] == 0xEEEEEEEEu && longer.tail[3] == 0xEEEEEEEEu);
        info.struct_size = 0;
        EXPECT_STATUS(tp_store_get_info(store, &info), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_get_info(store, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_get_info(NULL, &longer.info), TP_ERROR_INVALID_ARGUMENT);
    }
    /* An older tp_build_options (only struct_size and flags) gets defaults for the rest. */
    tp_build_options_init(&options);
    options.struct_size = (uint32_t)(offsetof(tp_build_options, flags) + sizeof(uint32_t));
    options.flags = TP_BUILD_INDEX32;
    options.merge_tolerance = -5.0; /* beyond struct_size: must be ignored */
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD + 3, &options, &store32));
    if (store32) {
        float a[27], b[27];
        const float p[3] = {0.25f, -0.5f, 0.125f};
        memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        EXPECT_OK(tp_store_get_info(store32, &info));
        CHECK(info.index_bits == 32);
        CHECK(info.merged_probes == 3);
        CHECK((info.flags & TP_BUILD_INDEX32) != 0);
        EXPECT_OK(tp_store_interpolate(store, p, NULL, a));
        EXPECT_OK(tp_store_interpolate(store32, p, NULL, b));
        for (k = 0; k < 27; ++k) CHECK_NEAR(a[k], b[k], 1e-6);
    }
    tp_store_release(store32);
    tp_store_release(store);
}

/* Small and degenerate probe sets (the header: 1, 2, collinear, flat and general are accepted). */
void test_small_sets(void) {
    float positions[3 * 5], sh[27 * 5], out[27];
    tp_store* store = NULL;
    tp_store_info info;
    int k;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;

    /* One probe: constant everywhere. */
    positions[0] = 5.0f, positions[1] = -2.0f, positions[2] = 1.0f;
    for (k = 0; k < 27; ++k) sh[k] = 0.25f * (float)k - 2.0f;
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, 1, NULL, &store));
    if (store) {
        const float far_point[3] = {-40.0f, 12.0f, 3.0f};
        EXPECT_OK(tp_store_get_info(store, &info));
        CHECK(info.dimension == 0 && info.probes == 1);
        EXPECT_OK(tp_store_interpolate(store, far_point, NULL, out));
        for (k = 0; k < 27; ++k) CHECK_NEAR(out[k], sh[k], sh_tolerance(sh[k]));
        tp_store_release(store);
        store = NULL;
    }

    /* Collinear: piecewise linear along the line, constant beyond its ends. */
    for (k = 0; k < 3; ++k) {
        int c;
        positions[3 * k] = (float)k;
        positions[3 * k + 1] = 0.0f;
        positions[3 * k + 2] = 0.0f;
        for (c = 0; c < 27; ++c) sh[27 * k + c] = (float)(k * k) + 0.01f * (float)c;
    }
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, 3, NULL, &store));
    if (store) {
        const float mid[3] = {1.5f, 0.0f, 0.0f};
        const float beyond[3] = {7.0f, 0.0f, 0.0f};
        EXPECT_OK(tp_store_get_info(store, &info));
        CHECK(info.dimension == 1);
        EXPECT_OK(tp_store_interpolate(store, mid, NULL, out));
        CHECK_NEAR(out[0], 2.5, sh_tolerance(2.5));
        EXPECT_OK(tp_store_interpolate(store, beyond, NULL, out));
        CHECK_NEAR(out[0], 4.0, sh_tolerance(4.0));
        tp_store_release(store);
        store = NULL;
    }

    /* Flat: a unit square of 4 probes plus its centre in the plane z = 2; linear within the square. */
    {
        static const float square[15] = {0, 0, 2, 1, 0, 2, 0, 1, 2, 1, 1, 2, 0.5f, 0.5f, 2};
        const float inside[3] = {0.3f, 0.6f, 2.0f};
        memcpy(positions, square, sizeof square);
        for (k = 0; k < 5; ++k) {
            int c;
            for (c = 0; c < 27; ++c) sh[27 * k + c] = 1.0f + square[3 * k] + 2.0f * square[3 * k + 1];
        }
        EXPECT_OK(tp_store_build(positions, 0, sh, 0, 5, NULL, &store));
        if (store) {
            EXPECT_OK(tp_store_get_info(store, &info));
            CHECK(info.dimension == 2);
            EXPECT_OK(tp_store_interpolate(store, inside, NULL, out));
            CHECK_NEAR(out[5], 2.5, sh_tolerance(2.5));
            tp_store_release(store);
        }
    }
}

/* Format 5's build options: each SH encoding at float and quantised positions. info reports the
   encoding, the quantisation and the bytes of each part (adding up to the blob); an input probe reads
   its decoded SH (band 2 zero in the L1 encodings, L0 within half rounding) and, at float positions, a
   query at it returns exactly that; an older tp_build_options (ending at `scene`) builds half floats at
   float positions; an unknown encoding is refused. */
void test_store_encodings_and_quantization(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static const uint64_t record_bytes[4] = {64, 32, 32, 16}; /* fast layout, by TP_SH_ENCODING_* */
    uint64_t bytes[4][2];
    uint32_t encoding, quantize;
    tp_build_options options;
    tp_store* store = NULL;
    tp_store_info info;
    make_cloud(positions, sh, CLOUD);
    for (encoding = 0; encoding < 4; ++encoding) {
        for (quantize = 0; quantize < 2; ++quantize) {
            const int l1 = encoding == TP_SH_ENCODING_HALF_L1 || encoding == TP_SH_ENCODING_UNORM8_L1;
            uint64_t parts = 0;
            int i, k, decoded_ok = 1, exact_at_probes = 1;
            tp_build_options_init(&options);
            options.sh_encoding = encoding;
            options.quantize_positions = quantize;
            store = NULL;
            EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store));
            if (!store) continue;
            info = info_of(store);
            bytes[encoding][quantize] = info.bytes;
            CHECK(info.sh_encoding == encoding && info.quantized_positions == quantize);
            CHECK(info.layout == TP_LAYOUT_FAST && info.probes == CLOUD);
            for (k = 0; k < 16; ++k) parts += info.section_bytes[k];
            CHECK(parts == info.bytes);
            CHECK(info.section_bytes[TP_STORE_SECTION_SH] == CLOUD * record_bytes[encoding]);
            CHECK(info.section_bytes[TP_STORE_SECTION_POSITIONS] == CLOUD * (quantize ? 6u : 12u));
            CHECK(info.section_bytes[TP_STORE_SECTION_NORMALS] == info.hull_probes * (quantize ? 4u : 12u));
            CHECK(info.section_bytes[TP_STORE_SECTION_INPUT_REMAP] == 0); /* nothing merged */
            CHECK(info.hull_probes >= 8 && info.hull_probes < CLOUD);
            for (k = 0; k < 3; ++k) {
                /* A power of two spanning the cube's extent 2 in at most 65,534 steps, less than twice that. */
                int exponent;
                const double mantissa = frexp(info.position_step[k], &exponent);
                CHECK(quantize ? mantissa == 0.5 && info.position_step[k] >= 2.0 / 65534 && info.position_step[k] < 4.0 / 65534
                               : info.position_step[k] == 0.0);
            }
            for (i = 0; i < CLOUD; ++i) {
                float decoded[27], out[27];
                EXPECT_OK(tp_store_probe_sh(store, (uint32_t)i, decoded));
                for (k = 0; k < 27; ++k) {
                    if (l1 && k % 9 >= 4) decoded_ok &= decoded[k] == 0.0f;
                    if (k % 9 == 0 || encoding == TP_SH_ENCODING_HALF)
                        decoded_ok &= fabs(decoded[k] - sh[27 * i + k]) <= sh_tolerance(sh[27 * i + k]);
                }
                if (quantize) continue; /* the stored probe moved (within half a step) */
                EXPECT_OK(tp_store_interpolate(store, positions + 3 * i, NULL, out));
                for (k = 0; k < 27; ++k) exact_at_probes &= out[k] == decoded[k];
            }
            CHECK(decoded_ok);
            CHECK(exact_at_probes);
            tp_store_release(store);
        }
    }
    CHECK(bytes[TP_SH_ENCODING_UNORM8_L1][1] < bytes[TP_SH_ENCODING_UNORM8][1]);
    CHECK(bytes[TP_SH_ENCODING_UNORM8][1] < bytes[TP_SH_ENCODING_HALF][1]);
    CHECK(bytes[TP_SH_ENCODING_HALF][1] < bytes[TP_SH_ENCODING_HALF][0]);

    /* An older struct that ends at `scene`: what lies beyond is never read. */
    tp_build_options_init(&options);
    options.struct_size = (uint32_t)(offsetof(tp_build_options, scene) + sizeof(options.scene));
    options.sh_encoding = 99;
    options.quantize_positions = 1;
    store = NULL;
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store));
    if (store) {
        info = info_of(store);
        CHECK(info.sh_encoding == TP_SH_ENCODING_HALF && info.quantized_positions == 0);
        tp_store_release(store);
    }
    tp_build_options_init(&options);
    options.sh_encoding = 4;
    store = NULL;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store), TP_ERROR_INVALID_ARGUMENT);
    CHECK(store == NULL && strstr(tp_last_error(), "sh_encoding") != NULL);
}

/* The rebuilt layout: no cells or start grid in the blob; loaded (from the build and from its bytes) it
   answers as the compact layout, bit for bit: the same cell hints, probes and weights. */
void test_store_rebuilt_layout(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    tp_build_options options;
    tp_store *compact = NULL, *rebuilt = NULL, *loaded = NULL, *store = NULL;
    tp_store_info info;
    const void* blob = NULL;
    size_t size = 0;
    int i, k, same = 1;
    make_cloud(positions, sh, CLOUD);
    tp_build_options_init(&options);
    CHECK(options.layout == TP_LAYOUT_FAST);
    options.layout = TP_LAYOUT_COMPACT;
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &compact));
    options.layout = TP_LAYOUT_REBUILT;
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &rebuilt));
    if (!compact || !rebuilt) {
        tp_store_release(compact);
        tp_store_release(rebuilt);
        return;
    }
    info = info_of(rebuilt);
    CHECK(info.layout == TP_LAYOUT_REBUILT && info_of(compact).layout == TP_LAYOUT_COMPACT);
    CHECK(info.section_bytes[TP_STORE_SECTION_CELLS] == 0 && info.section_bytes[TP_STORE_SECTION_GRID] == 0);
    CHECK(info.cells == info_of(compact).cells && info.bytes < info_of(compact).bytes);
    EXPECT_OK(tp_store_blob(rebuilt, &blob, &size));
    EXPECT_OK(tp_store_load(blob, size, &loaded));
    for (i = 0; i < 64 && loaded; ++i) {
        const float p[3] = {(float)(i % 4) * 0.7f - 1.2f, (float)(i / 4 % 4) * 0.7f - 1.1f, (float)(i / 16) * 0.8f - 1.3f};
        uint32_t pa[4], pb[4], pc[4];
        float wa[4], wb[4], wc[4];
        int32_t ha = -1, hb = -1, hc = -1;
        EXPECT_OK(tp_store_weights(compact, p, &ha, pa, wa));
        EXPECT_OK(tp_store_weights(rebuilt, p, &hb, pb, wb));
        EXPECT_OK(tp_store_weights(loaded, p, &hc, pc, wc));
        same &= ha == hb && ha == hc;
        for (k = 0; k < 4; ++k) same &= pa[k] == pb[k] && pa[k] == pc[k] && wa[k] == wb[k] && wa[k] == wc[k];
    }
    CHECK(same);
    tp_store_release(loaded);
    tp_store_release(compact);
    tp_store_release(rebuilt);

    /* An unknown layout, and TP_BUILD_COMPACT with another layout, are refused; an older struct that ends
       at quantize_positions builds the fast layout. */
    tp_build_options_init(&options);
    options.layout = 3;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store), TP_ERROR_INVALID_ARGUMENT);
    CHECK(store == NULL && strstr(tp_last_error(), "layout") != NULL);
    options.layout = TP_LAYOUT_REBUILT;
    options.flags = TP_BUILD_COMPACT;
    EXPECT_STATUS(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store), TP_ERROR_INVALID_ARGUMENT);
    CHECK(store == NULL && strstr(tp_last_error(), "TP_BUILD_COMPACT") != NULL);
    tp_build_options_init(&options);
    options.struct_size = (uint32_t)(offsetof(tp_build_options, quantize_positions) + sizeof(options.quantize_positions));
    options.layout = TP_LAYOUT_REBUILT;
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store));
    if (store) CHECK(info_of(store).layout == TP_LAYOUT_FAST);
    tp_store_release(store);
}
