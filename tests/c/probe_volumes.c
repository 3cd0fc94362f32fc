/* Probe volumes (tp_store_sample_volume): each point is the single query replayed in the documented walk with the
   carried hint, bit for bit; the L1 and Unity formats repack it as documented; strides leave every other byte alone;
   outside a store without extrapolation the first walked point is named; bad arguments are refused. */
#include "harness.h"

#include <stdint.h>

#define NX 6
#define NY 5
#define NZ 4
#define POINTS (NX * NY * NZ)

static const float kOrigin[3] = {-1.4f, -1.25f, -1.1f};
static const float kCell[3] = {0.55f, 0.6f, 0.7f};
static const uint32_t kDims[3] = {NX, NY, NZ};

/* Replays the walk of the header with tp_store_interpolate: out[27 * (x + NX (y + NY z))]. Returns the status of
   the first failing point in walk order (first[3] its point) and *first_cell the cell of point (0, 0, 0). */
static tp_status replay(const tp_store* store, int32_t start, float* out, uint32_t first[3], int32_t* first_cell) {
    uint32_t z, j, i, row = 0;
    int32_t hint = start;
    tp_status result = TP_OK;
    for (z = 0; z < NZ; ++z)
        for (j = 0; j < NY; ++j, ++row) {
            uint32_t y = z % 2 ? NY - 1 - j : j;
            for (i = 0; i < NX; ++i) {
                uint32_t x = row % 2 ? NX - 1 - i : i;
                uint32_t p[3];
                float world[3];
                int a;
                tp_status s;
                p[0] = x, p[1] = y, p[2] = z;
                for (a = 0; a < 3; ++a) world[a] = (float)((double)kOrigin[a] + (double)p[a] * (double)kCell[a]);
                s = tp_store_interpolate(store, world, &hint, out + 27 * (x + NX * (y + NY * z)));
                if (s != TP_OK && result == TP_OK) result = s, first[0] = x, first[1] = y, first[2] = z;
                if (row == 0 && i == 0) *first_cell = hint;
            }
        }
    return result;
}

/* Unity's constants of one SH as the header documents them. */
static void unity_constants(const float* c, float out[28]) {
    const double sp = sqrt(3.14159265358979323846);
    const float s[9] = {(float)(1 / (2 * sp)), (float)(sqrt(3.0) / (3 * sp)), (float)(sqrt(3.0) / (3 * sp)),
                        (float)(sqrt(3.0) / (3 * sp)), (float)(sqrt(15.0) / (8 * sp)), (float)(sqrt(15.0) / (8 * sp)),
                        (float)(sqrt(5.0) / (16 * sp)), (float)(sqrt(15.0) / (8 * sp)), (float)(sqrt(15.0) / (16 * sp))};
    int ch, i;
    for (ch = 0; ch < 3; ++ch) {
        float u[9];
        for (i = 0; i < 9; ++i) u[i] = c[9 * ch + i] * s[i];
        out[4 * ch + 0] = u[3], out[4 * ch + 1] = u[1], out[4 * ch + 2] = u[2], out[4 * ch + 3] = u[0] - u[6];
        out[12 + 4 * ch + 0] = u[4], out[12 + 4 * ch + 1] = u[5], out[12 + 4 * ch + 2] = 3.0f * u[6];
        out[12 + 4 * ch + 3] = u[7];
        out[24 + ch] = u[8];
    }
    out[27] = 1.0f;
}

void test_probe_volumes(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static float expected[27 * POINTS], got[27 * POINTS], l1[12 * POINTS];
    static unsigned char interleaved[POINTS * 128 + 64];
    tp_store* store = build_cloud(positions, sh, 0);
    tp_store* bounded;
    tp_volume_layout layout;
    uint32_t first[3] = {0, 0, 0};
    int32_t hint, first_cell = -5;
    int p, k;
    if (!store) return;

    /* Plain L2 across the hull: the replay, bit for bit, and the hint of point (0, 0, 0) back. */
    EXPECT_OK(replay(store, -1, expected, first, &first_cell));
    hint = -1;
    EXPECT_OK(tp_store_sample_volume(store, kOrigin, kCell, kDims, &hint, NULL, got));
    CHECK(memcmp(got, expected, sizeof got) == 0);
    CHECK(hint == first_cell && hint >= 0);
    /* From that hint (the next frame) the same bits again; without a hint too. */
    EXPECT_OK(tp_store_sample_volume(store, kOrigin, kCell, kDims, &hint, NULL, got));
    CHECK(memcmp(got, expected, sizeof got) == 0);
    EXPECT_OK(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, NULL, got));
    CHECK(memcmp(got, expected, sizeof got) == 0);

    /* L1: the first 4 floats of each channel. */
    EXPECT_OK(tp_volume_layout_init(&layout));
    CHECK(layout.struct_size == sizeof layout && layout.format == TP_VOLUME_SH_L2 && layout.point_stride == 0);
    layout.format = TP_VOLUME_SH_L1;
    EXPECT_OK(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, l1));
    {
        int same = 1;
        for (p = 0; p < POINTS; ++p)
            for (k = 0; k < 12; ++k) same &= l1[12 * p + k] == expected[27 * p + 9 * (k / 4) + k % 4];
        CHECK(same);
    }

    /* Unity L2 with a pad after each float4 and after each point: the documented constants, nothing else touched. */
    memset(interleaved, 0xCD, sizeof interleaved);
    layout.format = TP_VOLUME_UNITY_L2;
    layout.vector_stride = 17;
    layout.point_stride = 7 * 17 + 5;
    layout.row_stride = NX * layout.point_stride;
    layout.slice_stride = NY * layout.row_stride;
    EXPECT_OK(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, (float*)(void*)interleaved));
    {
        static unsigned char written[sizeof interleaved];
        int same = 1, untouched = 1;
        size_t b;
        memset(written, 0, sizeof written);
        for (p = 0; p < POINTS; ++p) {
            float constants[28];
            unity_constants(expected + 27 * p, constants);
            for (k = 0; k < 7; ++k) {
                size_t at = (size_t)p * layout.point_stride + (size_t)k * layout.vector_stride;
                same &= memcmp(interleaved + at, constants + 4 * k, 16) == 0;
                memset(written + at, 1, 16);
            }
        }
        for (b = 0; b < sizeof interleaved; ++b)
            if (!written[b]) untouched &= interleaved[b] == 0xCD;
        CHECK(same);
        CHECK(untouched);
    }

    /* Bad arguments: each refused with a message, nothing written. */
    {
        float origin_nan[3], cell_zero[3], cell_inf[3];
        uint32_t dims_zero[3] = {NX, 0, NZ}, dims_big[3] = {NX, NY, 33};
        memcpy(origin_nan, kOrigin, sizeof origin_nan);
        origin_nan[1] = (float)NAN;
        memcpy(cell_zero, kCell, sizeof cell_zero);
        cell_zero[2] = 0.0f;
        memcpy(cell_inf, kCell, sizeof cell_inf);
        cell_inf[0] = (float)INFINITY;
        got[0] = 12345.0f;
        EXPECT_STATUS(tp_store_sample_volume(NULL, kOrigin, kCell, kDims, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_sample_volume(store, NULL, kCell, kDims, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, NULL, kDims, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, NULL, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, NULL, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, dims_zero, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        CHECK(strstr(tp_last_error(), "dims[1]") != NULL);
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, dims_big, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        CHECK(mentions_number(tp_last_error(), 33) && mentions_number(tp_last_error(), 32));
        EXPECT_STATUS(tp_store_sample_volume(store, origin_nan, kCell, kDims, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        CHECK(strstr(tp_last_error(), "origin[1]") != NULL);
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, cell_zero, kDims, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, cell_inf, kDims, NULL, NULL, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_OK(tp_volume_layout_init(&layout));
        layout.format = 4;
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, got), TP_ERROR_INVALID_ARGUMENT);
        layout.format = TP_VOLUME_SH_L2;
        layout.struct_size = 0;
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_OK(tp_volume_layout_init(&layout));
        layout.point_stride = 100; /* below one point's 108 bytes */
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, got), TP_ERROR_INVALID_ARGUMENT);
        CHECK(strstr(tp_last_error(), "point_stride") != NULL);
        layout.point_stride = SIZE_MAX / 4; /* 6 points overflow */
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, got), TP_ERROR_INVALID_ARGUMENT);
        layout.point_stride = (size_t)PTRDIFF_MAX / 8; /* each axis fits, their sum does not */
        layout.row_stride = (size_t)PTRDIFF_MAX / 8;
        layout.slice_stride = (size_t)PTRDIFF_MAX / 8;
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, got), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_OK(tp_volume_layout_init(&layout));
        layout.format = TP_VOLUME_UNITY_L1;
        layout.vector_stride = 8; /* below a float4 */
        EXPECT_STATUS(tp_store_sample_volume(store, kOrigin, kCell, kDims, NULL, &layout, got), TP_ERROR_INVALID_ARGUMENT);
        CHECK(strstr(tp_last_error(), "vector_stride") != NULL);
        CHECK(got[0] == 12345.0f);
        EXPECT_STATUS(tp_volume_layout_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    }

    /* Without extrapolation: the whole volume is filled, failing points zero, the first walked one named. */
    bounded = build_cloud(positions, sh, TP_BUILD_NO_EXTRAPOLATION);
    if (bounded) {
        uint32_t want[3] = {9, 9, 9};
        char where[64];
        tp_status replayed = replay(bounded, -1, expected, want, &first_cell);
        CHECK(replayed == TP_ERROR_OUTSIDE);
        EXPECT_STATUS(tp_store_sample_volume(bounded, kOrigin, kCell, kDims, NULL, NULL, got), TP_ERROR_OUTSIDE);
        sprintf(where, "(%u, %u, %u)", (unsigned)want[0], (unsigned)want[1], (unsigned)want[2]);
        CHECK(strstr(tp_last_error(), where) != NULL);
        CHECK(memcmp(got, expected, sizeof got) == 0);
        tp_store_release(bounded);
    }
    tp_store_release(store);
}
