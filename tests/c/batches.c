/* Batch options (threads, chained hints) and batches outside a store without extrapolation. */
#include "harness.h"

void test_batch_options(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static float points[3 * BIG_BATCH], one[27 * BIG_BATCH], two[27 * BIG_BATCH];
    static int32_t hints_one[BIG_BATCH], hints_two[BIG_BATCH];
    static uint32_t probes_one[4 * BIG_BATCH], probes_two[4 * BIG_BATCH];
    static float weights_one[4 * BIG_BATCH], weights_two[4 * BIG_BATCH];
    tp_store* store = build_cloud(positions, sh, 0);
    tp_batch_options options;
    int i;
    if (!store) return;
    /* Scattered points, inside and outside the cube the probes span. */
    for (i = 0; i < 3 * BIG_BATCH; ++i) points[i] = uniform(-1.4, 1.4);

    /* Unknown flags and a struct_size below the three fields are refused by both batch calls. */
    tp_batch_options_init(&options);
    options.flags = 2u;
    EXPECT_STATUS(tp_store_interpolate_batch(store, 16, points, 0, NULL, 0, one, 0, &options),
                  TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_weights_batch(store, 16, points, 0, NULL, 0, probes_one, 0, weights_one, 0, &options),
                  TP_ERROR_INVALID_ARGUMENT);
    options.flags = 0x80000000u | TP_BATCH_CHAIN_HINTS;
    EXPECT_STATUS(tp_store_interpolate_batch(store, 16, points, 0, NULL, 0, one, 0, &options),
                  TP_ERROR_INVALID_ARGUMENT);
    tp_batch_options_init(&options);
    options.struct_size = 8;
    EXPECT_STATUS(tp_store_interpolate_batch(store, 16, points, 0, NULL, 0, one, 0, &options),
                  TP_ERROR_INVALID_ARGUMENT);
    options.struct_size = 0;
    EXPECT_STATUS(tp_store_weights_batch(store, 16, points, 0, NULL, 0, probes_one, 0, weights_one, 0, &options),
                  TP_ERROR_INVALID_ARGUMENT);

    /* threads = 2 gives the same bytes as threads = 1 (and as the defaults), hints included. */
    for (i = 0; i < BIG_BATCH; ++i) hints_one[i] = hints_two[i] = -1;
    tp_batch_options_init(&options);
    EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, hints_one, 0, one, 0, &options));
    options.threads = 2;
    EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, hints_two, 0, two, 0, &options));
    CHECK(memcmp(one, two, sizeof one) == 0);
    CHECK(memcmp(hints_one, hints_two, sizeof hints_one) == 0);
    EXPECT_OK(tp_store_weights_batch(store, BIG_BATCH, points, 0, NULL, 0, probes_two, 0, weights_two, 0, &options));
    options.threads = 1;
    EXPECT_OK(tp_store_weights_batch(store, BIG_BATCH, points, 0, NULL, 0, probes_one, 0, weights_one, 0, &options));
    CHECK(memcmp(probes_one, probes_two, sizeof probes_one) == 0);
    CHECK(memcmp(weights_one, weights_two, sizeof weights_one) == 0);
    EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, NULL, 0, two, 0, NULL));
    CHECK(memcmp(one, two, sizeof one) == 0);
    options.threads = 0; /* 0 = the calling thread */
    EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, NULL, 0, two, 0, &options));
    CHECK(memcmp(one, two, sizeof one) == 0);
    /* Each thread reads and writes only its own range of the hints: start them all from the answers. */
    memcpy(hints_two, hints_one, sizeof hints_one);
    options.threads = 2;
    EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, hints_two, 0, two, 0, &options));
    CHECK(memcmp(one, two, sizeof one) == 0);
    CHECK(memcmp(hints_one, hints_two, sizeof hints_one) == 0);

    /* TP_BATCH_CHAIN_HINTS without hints: the same answers as cold starts, scattered or coherent, on 1 and
       2 threads. Inside the hull the cell holding a point is decided exactly: the same bytes from any start.
       Outer cells accept a point within a weight tolerance, so near the face two of them share the start
       decides which answers, and the answer (continuous across that face) may differ a little. */
    {
        static uint32_t kinds[BIG_BATCH];
        int round, threads, same_inner = 1, inner_count = 0, located = 1;
        double worst_outer_sh = 0.0, worst_outer_weight = 0.0;
        for (round = 0; round < 2; ++round) {
            if (round == 1)
                for (i = 0; i < BIG_BATCH; ++i) {
                    const double t = (double)i / (BIG_BATCH - 1);
                    points[3 * i] = (float)(-1.2 + 2.4 * t);
                    points[3 * i + 1] = (float)(0.7 * sin(11.0 * t));
                    points[3 * i + 2] = (float)(0.8 * cos(7.0 * t));
                }
            for (i = 0; i < BIG_BATCH; ++i) {
                tp_location location;
                memset(&location, 0, sizeof location);
                location.struct_size = sizeof location;
                located &= tp_store_locate(store, points + 3 * i, NULL, &location) == TP_OK;
                kinds[i] = location.cell_kind;
                if (kinds[i] == TP_CELL_INNER) ++inner_count;
            }
            EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, NULL, 0, one, 0, NULL));
            EXPECT_OK(tp_store_weights_batch(store, BIG_BATCH, points, 0, NULL, 0, probes_one, 0, weights_one, 0,
                                             NULL));
            for (threads = 1; threads <= 2; ++threads) {
                tp_batch_options_init(&options);
                options.flags = TP_BATCH_CHAIN_HINTS;
                options.threads = (uint32_t)threads;
                memset(two, 0, sizeof two);
                EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, NULL, 0, two, 0, &options));
                EXPECT_OK(tp_store_weights_batch(store, BIG_BATCH, points, 0, NULL, 0, probes_two, 0, weights_two, 0,
                                                 &options));
                for (i = 0; i < BIG_BATCH; ++i) {
                    int k;
                    if (kinds[i] == TP_CELL_INNER) {
                        same_inner &= memcmp(one + 27 * i, two + 27 * i, 108) == 0;
                        same_inner &= memcmp(probes_one + 4 * i, probes_two + 4 * i, 16) == 0;
                        same_inner &= memcmp(weights_one + 4 * i, weights_two + 4 * i, 16) == 0;
                        continue;
                    }
                    for (k = 0; k < 27; ++k)
                        if (fabs(one[27 * i + k] - two[27 * i + k]) > worst_outer_sh)
                            worst_outer_sh = fabs(one[27 * i + k] - two[27 * i + k]);
                    for (k = 0; k < 8; ++k) {
                        const uint32_t probe = k < 4 ? probes_one[4 * i + k] : probes_two[4 * i + k - 4];
                        const double d = fabs(weight_of(probes_one + 4 * i, weights_one + 4 * i, probe) -
                                              weight_of(probes_two + 4 * i, weights_two + 4 * i, probe));
                        if (d > worst_outer_weight) worst_outer_weight = d;
                    }
                }
            }
        }
        CHECK(located);
        CHECK(inner_count > BIG_BATCH / 4 && inner_count < 2 * BIG_BATCH - BIG_BATCH / 4);
        CHECK(same_inner);
        CHECK_NEAR(worst_outer_sh, 0.0, 1e-4);
        CHECK_NEAR(worst_outer_weight, 0.0, 5e-5);
        /* With hints given the flag changes nothing: the hints are read and written as always. */
        for (i = 0; i < BIG_BATCH; ++i) hints_one[i] = -1;
        EXPECT_OK(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, hints_one, 0, two, 0, &options));
        CHECK(memcmp(one, two, sizeof one) == 0);
        CHECK(hints_one[0] >= 0 && hints_one[BIG_BATCH - 1] >= 0);
    }
    tp_store_release(store);
}

/* A batch with queries outside a store without extrapolation: TP_ERROR_OUTSIDE naming the first,
   zero SH and weights for those outside, the others answered. */
void test_outside_batch(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static float points[3 * BIG_BATCH], out[27 * BIG_BATCH], weights[4 * BIG_BATCH];
    static uint32_t probes[4 * BIG_BATCH];
    static int32_t hints[BIG_BATCH];
    tp_store* store = build_cloud(positions, sh, TP_BUILD_NO_EXTRAPOLATION);
    tp_batch_options options;
    int i, k, zeros = 1, answered = 1;
    if (!store) return;
    for (i = 0; i < 3 * BIG_BATCH; ++i) points[i] = uniform(-0.9, 0.9);
    for (i = 0; i < BIG_BATCH; ++i) hints[i] = -1;
    points[3 * 17] = 3.0f;
    points[3 * 29 + 1] = -2.5f;
    EXPECT_STATUS(tp_store_interpolate_batch(store, 40, points, 0, hints, 0, out, 0, NULL), TP_ERROR_OUTSIDE);
    CHECK(mentions_number(tp_last_error(), 17));
    CHECK(!mentions_number(tp_last_error(), 29));
    for (k = 0; k < 27; ++k) zeros &= out[27 * 17 + k] == 0.0f && out[27 * 29 + k] == 0.0f;
    for (i = 0; i < 40; ++i) {
        float single[27];
        if (i == 17 || i == 29) continue;
        EXPECT_OK(tp_store_interpolate(store, points + 3 * i, NULL, single));
        answered &= memcmp(single, out + 27 * i, sizeof single) == 0;
    }
    CHECK(zeros);
    CHECK(answered);
    EXPECT_STATUS(tp_store_weights_batch(store, 40, points, 0, NULL, 0, probes, 0, weights, 0, NULL), TP_ERROR_OUTSIDE);
    CHECK(mentions_number(tp_last_error(), 17));
    zeros = 1;
    for (k = 0; k < 4; ++k) zeros &= weights[4 * 17 + k] == 0.0f && weights[4 * 29 + k] == 0.0f;
    CHECK(zeros);
    CHECK_NEAR(weights[0] + weights[1] + weights[2] + weights[3], 1.0, 1e-5);

    /* Split over 2 threads: the first outside query of the whole batch is named, whichever range has it. */
    points[3 * 17] = 0.0f;
    points[3 * 29 + 1] = 0.0f;
    points[3 * 8000 + 2] = 4.0f; /* second range */
    tp_batch_options_init(&options);
    options.threads = 2;
    EXPECT_STATUS(tp_store_interpolate_batch(store, BIG_BATCH, points, 0, NULL, 0, out, 0, &options),
                  TP_ERROR_OUTSIDE);
    CHECK(mentions_number(tp_last_error(), 8000));
    points[3 * 3000] = -4.0f; /* first range */
    EXPECT_STATUS(tp_store_weights_batch(store, BIG_BATCH, points, 0, NULL, 0, probes, 0, weights, 0, &options),
                  TP_ERROR_OUTSIDE);
    CHECK(mentions_number(tp_last_error(), 3000));
    CHECK(!mentions_number(tp_last_error(), 8000));
    zeros = 1;
    for (k = 0; k < 4; ++k) zeros &= weights[4 * 3000 + k] == 0.0f && weights[4 * 8000 + k] == 0.0f;
    CHECK(zeros);
    tp_store_release(store);
}
