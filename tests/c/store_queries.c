/* Queries on a built store: exactness at probes, linear fields, hints, outside the hull, batches equal singles, errors. */
#include "harness.h"

void test_store_queries(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    tp_store* store = build_cloud(positions, sh, 0);
    int i, k, worst_k = 0;
    double worst = 0.0;
    if (!store) return;

    /* Exact at every probe: the probe's own (half) SH, weight 1 on it. */
    for (i = 0; i < CLOUD; ++i) {
        float out[27], stored[27], weights[4];
        uint32_t probes[4];
        int32_t hint = -1;
        int slot, ones = 0;
        EXPECT_OK(tp_store_interpolate(store, positions + 3 * i, &hint, out));
        EXPECT_OK(tp_store_probe_sh(store, (uint32_t)i, stored));
        for (k = 0; k < 27; ++k) {
            double err = fabs(out[k] - stored[k]);
            if (err > worst) worst = err, worst_k = k;
            if (fabs(stored[k] - sh[27 * i + k]) > sh_tolerance(sh[27 * i + k])) {
                CHECK_NEAR(stored[k], sh[27 * i + k], sh_tolerance(sh[27 * i + k]));
            }
        }
        hint = -1;
        EXPECT_OK(tp_store_weights(store, positions + 3 * i, &hint, probes, weights));
        for (slot = 0; slot < 4; ++slot)
            if (probes[slot] == (uint32_t)i && fabs(weights[slot] - 1.0f) < 1e-5f) ++ones;
        CHECK(ones == 1);
    }
    CHECK_NEAR(worst, 0.0, 1e-5);
    (void)worst_k;

    /* The linear field is reproduced inside the hull; weights in [0, 1] sum to 1. */
    {
        int32_t hint = -1;
        double worst_linear = 0.0, worst_sum = 0.0;
        int weights_in_range = 1, kind_inner = 1;
        for (i = 0; i < 500; ++i) {
            float p[3], out[27], weights[4];
            uint32_t probes[4];
            tp_location location;
            int slot;
            p[0] = uniform(-0.99, 0.99);
            p[1] = uniform(-0.99, 0.99);
            p[2] = uniform(-0.99, 0.99);
            EXPECT_OK(tp_store_interpolate(store, p, &hint, out));
            CHECK(hint >= 0);
            for (k = 0; k < 27; ++k) {
                double err = fabs(out[k] - linear_field(k, p)) / sh_tolerance(linear_field(k, p));
                if (err > worst_linear) worst_linear = err;
            }
            EXPECT_OK(tp_store_weights(store, p, NULL, probes, weights));
            {
                double sum = 0.0;
                for (slot = 0; slot < 4; ++slot) {
                    sum += weights[slot];
                    if (weights[slot] < -1e-6f || weights[slot] > 1.0f + 1e-6f) weights_in_range = 0;
                    if (probes[slot] >= CLOUD) weights_in_range = 0;
                }
                if (fabs(sum - 1.0) > worst_sum) worst_sum = fabs(sum - 1.0);
            }
            memset(&location, 0, sizeof location);
            location.struct_size = sizeof location;
            EXPECT_OK(tp_store_locate(store, p, NULL, &location));
            if (location.cell_kind != TP_CELL_INNER || location.cell < 0) kind_inner = 0;
            for (slot = 0; slot < 4; ++slot) {
                if (location.weights[slot] != weights[slot] || location.probes[slot] != probes[slot]) kind_inner = 0;
            }
        }
        CHECK(worst_linear <= 1.0);
        CHECK_NEAR(worst_sum, 0.0, 1e-5);
        CHECK(weights_in_range);
        CHECK(kind_inner);
    }

    /* A moving object with a hint takes few steps; the hint names a cell and is reused. */
    {
        int32_t hint = -1;
        unsigned total_steps = 0;
        for (i = 0; i < 200; ++i) {
            float p[3];
            tp_location location;
            p[0] = -0.9f + 1.8f * (float)i / 199.0f;
            p[1] = 0.3f * (float)sin(i * 0.05);
            p[2] = 0.1f;
            memset(&location, 0, sizeof location);
            location.struct_size = sizeof location;
            EXPECT_OK(tp_store_locate(store, p, &hint, &location));
            CHECK(hint == location.cell);
            if (i > 0) total_steps += location.steps;
        }
        CHECK(total_steps / 199.0 < 3.0);
    }

    /* Outside the hull: outer cells extrapolate; far away too; the answer stays finite. */
    {
        const float outside[3] = {2.5f, 0.2f, -0.1f};
        const float far_away[3] = {1e9f, -1e9f, 3e8f};
        float out[27];
        tp_location location;
        int32_t hint = -1;
        int finite = 1;
        memset(&location, 0, sizeof location);
        location.struct_size = sizeof location;
        EXPECT_OK(tp_store_locate(store, outside, &hint, &location));
        CHECK(location.cell_kind == TP_CELL_OUTER);
        CHECK(location.t > 0.0f);
        EXPECT_OK(tp_store_interpolate(store, far_away, &hint, out));
        for (k = 0; k < 27; ++k) finite &= isfinite(out[k]) != 0;
        CHECK(finite);
    }

    /* Batch equals single, bit for bit, with packed and with padded strides. */
    {
        enum { M = 64 };
        float points[3 * M], single[27 * M], batch[27 * M];
        int32_t single_hints[M], batch_hints[M];
        uint32_t single_probes[4 * M], batch_probes[4 * M];
        float single_weights[4 * M], batch_weights[4 * M];
        /* Padded layouts: positions 16 bytes apart, hints 8, SH 120, probes 20, weights 24. */
        float padded_points[4 * M], padded_sh[30 * M], padded_weights[6 * M];
        int32_t padded_hints[2 * M];
        uint32_t padded_probes[5 * M];
        int same = 1, padding_kept = 1;
        for (i = 0; i < M; ++i) {
            float* p = points + 3 * i;
            p[0] = uniform(-1.5, 1.5);
            p[1] = uniform(-1.5, 1.5);
            p[2] = uniform(-1.5, 1.5);
            single_hints[i] = -1;
            batch_hints[i] = -1;
            EXPECT_OK(tp_store_interpolate(store, p, &single_hints[i], single + 27 * i));
            EXPECT_OK(tp_store_weights(store, p, NULL, single_probes + 4 * i, single_weights + 4 * i));
        }
        EXPECT_OK(tp_store_interpolate_batch(store, M, points, 0, batch_hints, 0, batch, 0, NULL));
        same &= memcmp(single, batch, sizeof single) == 0;
        same &= memcmp(single_hints, batch_hints, sizeof single_hints) == 0;
        EXPECT_OK(tp_store_interpolate_batch(store, M, points, 0, NULL, 0, batch, 0, NULL));
        same &= memcmp(single, batch, sizeof single) == 0;
        EXPECT_OK(tp_store_weights_batch(store, M, points, 0, NULL, 0, batch_probes, 0, batch_weights, 0, NULL));
        same &= memcmp(single_probes, batch_probes, sizeof single_probes) == 0;
        same &= memcmp(single_weights, batch_weights, sizeof single_weights) == 0;
        CHECK(same);

        for (i = 0; i < 4 * M; ++i) padded_points[i] = -7.0f;
        for (i = 0; i < 30 * M; ++i) padded_sh[i] = -7.0f;
        for (i = 0; i < 6 * M; ++i) padded_weights[i] = -7.0f;
        for (i = 0; i < 5 * M; ++i) padded_probes[i] = 777u;
        for (i = 0; i < M; ++i) {
            memcpy(padded_points + 4 * i, points + 3 * i, 12);
            padded_hints[2 * i] = -1;
            padded_hints[2 * i + 1] = 12345;
        }
        EXPECT_OK(tp_store_interpolate_batch(store, M, padded_points, 16, padded_hints, 8, padded_sh, 120, NULL));
        EXPECT_OK(tp_store_weights_batch(store, M, padded_points, 16, NULL, 0, padded_probes, 20,
                                         padded_weights, 24, NULL));
        same = 1;
        for (i = 0; i < M; ++i) {
            same &= memcmp(padded_sh + 30 * i, single + 27 * i, 108) == 0;
            same &= padded_hints[2 * i] == single_hints[i];
            same &= memcmp(padded_probes + 5 * i, single_probes + 4 * i, 16) == 0;
            same &= memcmp(padded_weights + 6 * i, single_weights + 4 * i, 16) == 0;
            padding_kept &= padded_hints[2 * i + 1] == 12345;
            padding_kept &= padded_sh[30 * i + 27] == -7.0f && padded_sh[30 * i + 29] == -7.0f;
            padding_kept &= padded_probes[5 * i + 4] == 777u;
            padding_kept &= padded_weights[6 * i + 4] == -7.0f && padded_weights[6 * i + 5] == -7.0f;
        }
        CHECK(same);
        CHECK(padding_kept);

        /* Strides too small for the element, a null buffer with a count, NaN among the points. */
        EXPECT_STATUS(tp_store_interpolate_batch(store, M, points, 8, NULL, 0, batch, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_batch(store, M, points, 0, batch_hints, 2, batch, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_batch(store, M, points, 0, NULL, 0, batch, 64, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_batch(store, M, NULL, 0, NULL, 0, batch, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_batch(store, M, points, 0, NULL, 0, NULL, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate_batch(NULL, M, points, 0, NULL, 0, batch, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights_batch(store, M, points, 0, NULL, 0, batch_probes, 8, batch_weights, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights_batch(store, M, points, 0, NULL, 0, NULL, 0, batch_weights, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights_batch(store, M, points, 0, NULL, 0, batch_probes, 0, NULL, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_OK(tp_store_interpolate_batch(store, 0, NULL, 0, NULL, 0, NULL, 0, NULL));
        points[3 * 5 + 1] = (float)NAN;
        EXPECT_STATUS(tp_store_interpolate_batch(store, M, points, 0, NULL, 0, batch, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights_batch(store, M, points, 0, NULL, 0, batch_probes, 0, batch_weights, 0, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
    }

    /* Single-query errors. */
    {
        float out[27], weights[4];
        uint32_t probes[4];
        float nan_point[3];
        const float inside[3] = {0.1f, 0.2f, 0.3f};
        tp_location location;
        int32_t hint = 1 << 30;
        nan_point[0] = 0.0f;
        nan_point[1] = (float)NAN;
        nan_point[2] = 0.0f;
        EXPECT_STATUS(tp_store_interpolate(NULL, inside, NULL, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate(store, NULL, NULL, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate(store, inside, NULL, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_interpolate(store, nan_point, NULL, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights(store, nan_point, NULL, probes, weights), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights(store, inside, NULL, NULL, weights), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights(store, inside, NULL, probes, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_weights(NULL, inside, NULL, probes, weights), TP_ERROR_INVALID_ARGUMENT);
        memset(&location, 0, sizeof location);
        location.struct_size = sizeof location;
        EXPECT_STATUS(tp_store_locate(store, nan_point, NULL, &location), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_locate(store, inside, NULL, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_locate(NULL, inside, NULL, &location), TP_ERROR_INVALID_ARGUMENT);
        location.struct_size = 0;
        EXPECT_STATUS(tp_store_locate(store, inside, NULL, &location), TP_ERROR_INVALID_ARGUMENT);
        /* A stale or foreign hint is not trusted: either refused or ignored, never followed. */
        {
            tp_status status = tp_store_interpolate(store, inside, &hint, out);
            CHECK(status == TP_OK || status == TP_ERROR_INVALID_ARGUMENT);
            if (status == TP_OK) CHECK_NEAR(out[3], linear_field(3, inside), sh_tolerance(linear_field(3, inside)));
        }
        EXPECT_STATUS(tp_store_probe_sh(store, CLOUD, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_probe_sh(store, 0, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_store_probe_sh(NULL, 0, out), TP_ERROR_INVALID_ARGUMENT);
    }
    tp_store_release(store);
}

void test_store_without_extrapolation(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    tp_store* store = build_cloud(positions, sh, TP_BUILD_NO_EXTRAPOLATION);
    const float outside[3] = {3.0f, 0.0f, 0.0f};
    const float inside[3] = {0.0f, 0.1f, 0.0f};
    float out[27];
    tp_store_info info;
    if (!store) return;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    EXPECT_OK(tp_store_get_info(store, &info));
    CHECK(info.outer_cells == 0);
    CHECK((info.flags & TP_BUILD_NO_EXTRAPOLATION) != 0);
    EXPECT_OK(tp_store_interpolate(store, inside, NULL, out));
    EXPECT_STATUS(tp_store_interpolate(store, outside, NULL, out), TP_ERROR_OUTSIDE);
    CHECK(strstr(tp_last_error(), "outside") != NULL);
    /* The next successful query clears the message (the query paths clear it without allocating). */
    EXPECT_OK(tp_store_interpolate(store, inside, NULL, out));
    CHECK(strcmp(tp_last_error(), "") == 0);
    tp_store_release(store);
}
