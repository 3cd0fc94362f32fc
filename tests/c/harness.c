/*
 * The C harness: the public header compiled as strict C99 and linked against the shared library
 * only. Exercises every exported function, its answers where they are known analytically, and its
 * error paths. Prints "N passed, N failed" last and exits non-zero on any failure.
 * argv[1]: the repository root (for the sample scenes); the working directory is a scratch dir.
 */
#include "tetprobe.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int g_passed = 0;
static int g_failed = 0;
static const char* g_repo_root = ".";

static void check(int ok, const char* what, const char* file, int line) {
    if (ok) {
        ++g_passed;
    } else {
        ++g_failed;
        printf("FAIL %s:%d: %s\n", file, line, what);
    }
}

#define CHECK(cond) check((cond) != 0, #cond, __FILE__, __LINE__)

/* A call must return exactly `expected`; a failure must also leave a non-empty message. */
static void check_status(tp_status got, tp_status expected, const char* call, const char* file, int line) {
    int ok = got == expected;
    if (ok && expected != TP_OK) ok = tp_last_error()[0] != '\0';
    if (!ok) {
        ++g_failed;
        printf("FAIL %s:%d: %s returned %s, expected %s (message: \"%s\")\n", file, line, call,
               tp_status_name(got), tp_status_name(expected), tp_last_error());
    } else {
        ++g_passed;
    }
}

/* A call must fail (any status but TP_OK) with a message; for cases the contract leaves open. */
static void check_fails(tp_status got, const char* call, const char* file, int line) {
    if (got != TP_OK && tp_last_error()[0] != '\0') {
        ++g_passed;
    } else {
        ++g_failed;
        printf("FAIL %s:%d: %s returned %s, expected a failure with a message\n", file, line, call,
               tp_status_name(got));
    }
}

#define EXPECT_OK(call) check_status((call), TP_OK, #call, __FILE__, __LINE__)
#define EXPECT_STATUS(call, expected) check_status((call), (expected), #call, __FILE__, __LINE__)
#define EXPECT_FAILS(call) check_fails((call), #call, __FILE__, __LINE__)

static void check_near(double got, double expected, double tolerance, const char* what, const char* file,
                       int line) {
    if (fabs(got - expected) <= tolerance) {
        ++g_passed;
    } else {
        ++g_failed;
        printf("FAIL %s:%d: %s = %.9g, expected %.9g +- %.3g\n", file, line, what, got, expected, tolerance);
    }
}

#define CHECK_NEAR(got, expected, tol) check_near((got), (expected), (tol), #got, __FILE__, __LINE__)

/* Deterministic random numbers (xorshift64*), so failures reproduce. */
static unsigned long long g_rng = 0x9E3779B97F4A7C15ull;

static double uniform01(void) {
    g_rng ^= g_rng >> 12;
    g_rng ^= g_rng << 25;
    g_rng ^= g_rng >> 27;
    return (double)((g_rng * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

static float uniform(double lo, double hi) { return (float)(lo + (hi - lo) * uniform01()); }

static const double kPi = 3.14159265358979323846;

/* ---------------------------------------------------------------------------------------------- */

static void test_version_and_status_names(void) {
    static const char* const names[] = {
        "TP_OK", "TP_ERROR_INVALID_ARGUMENT", "TP_ERROR_OUT_OF_MEMORY", "TP_ERROR_IO", "TP_ERROR_INVALID_BLOB",
        "TP_ERROR_VERSION", "TP_ERROR_DEGENERATE", "TP_ERROR_TETGEN", "TP_ERROR_CANCELLED", "TP_ERROR_OUTSIDE",
        "TP_ERROR_SCENE", "TP_ERROR_UNSUPPORTED", "TP_ERROR_BUFFER_TOO_SMALL", "TP_ERROR_INTERNAL"};
    int i;
    uint32_t version = tp_version();
    CHECK(version == TP_VERSION);
    CHECK((version >> 16) == TP_VERSION_MAJOR);
    CHECK(((version >> 8) & 0xFFu) == TP_VERSION_MINOR);
    CHECK((version & 0xFFu) == TP_VERSION_PATCH);
    for (i = 0; i <= (int)TP_ERROR_INTERNAL; ++i) CHECK(strcmp(tp_status_name((tp_status)i), names[i]) == 0);
    CHECK(tp_status_name((tp_status)1234) != NULL);
    CHECK(tp_last_error() != NULL);
}

static void test_last_error_is_per_call(void) {
    tp_build_options options;
    EXPECT_STATUS(tp_build_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    CHECK(strlen(tp_last_error()) > 0);
    EXPECT_OK(tp_build_options_init(&options));
    CHECK(strcmp(tp_last_error(), "") == 0);
}

static void test_option_struct_defaults(void) {
    tp_build_options build;
    tp_batch_options batch;
    tp_bake_options bake;
    tp_material material;
    tp_light light;
    memset(&build, 0xAB, sizeof build);
    memset(&bake, 0xAB, sizeof bake);
    memset(&material, 0xAB, sizeof material);
    memset(&light, 0xAB, sizeof light);
    memset(&batch, 0xAB, sizeof batch);
    EXPECT_OK(tp_batch_options_init(&batch));
    CHECK(sizeof batch == 12);
    CHECK(batch.struct_size == sizeof batch);
    CHECK(batch.flags == 0);
    CHECK(batch.threads == 1);
    EXPECT_STATUS(tp_batch_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_OK(tp_build_options_init(&build));
    CHECK(build.struct_size == sizeof build);
    CHECK(build.flags == 0);
    CHECK_NEAR(build.merge_tolerance, 1e-6, 1e-12);
    CHECK_NEAR(build.flat_tolerance, 1e-4, 1e-12);
    CHECK(build.progress == NULL);
    CHECK(build.progress_user == NULL);
    EXPECT_OK(tp_bake_options_init(&bake));
    CHECK(bake.struct_size == sizeof bake);
    CHECK(bake.flags == 0);
    CHECK(bake.rays == 256);
    CHECK(bake.bounces == 2);
    CHECK(bake.seed == 0);
    CHECK(bake.threads == 0);
    CHECK(bake.progress == NULL);
    EXPECT_OK(tp_material_init(&material));
    CHECK(material.struct_size == sizeof material);
    CHECK(material.albedo[0] >= 0.0f && material.albedo[0] <= 1.0f);
    CHECK(material.emission[0] == 0.0f && material.emission[1] == 0.0f && material.emission[2] == 0.0f);
    EXPECT_OK(tp_light_init(&light));
    CHECK(light.struct_size == sizeof light);
    CHECK(light.mode == TP_LIGHT_MODE_BAKED);
    CHECK(light.intensity > 0.0f);
    EXPECT_STATUS(tp_bake_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_material_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_light_init(NULL), TP_ERROR_INVALID_ARGUMENT);
}

/* ---------------------------------------------------------------------------------------------- */
/* SH helpers against the basis written in the header. */

static void basis(const float d[3], double out[9]) {
    double x = d[0], y = d[1], z = d[2];
    out[0] = 0.282095;
    out[1] = 0.488603 * y;
    out[2] = 0.488603 * z;
    out[3] = 0.488603 * x;
    out[4] = 1.092548 * x * y;
    out[5] = 1.092548 * y * z;
    out[6] = 0.315392 * (3.0 * z * z - 1.0);
    out[7] = 1.092548 * x * z;
    out[8] = 0.546274 * (x * x - y * y);
}

static int band_of(int i) { return i == 0 ? 0 : (i < 4 ? 1 : 2); }

static void test_sh_basis_functions(void) {
    static const double lobe[3] = {3.14159265358979323846, 2.0943951023931957, 0.78539816339744831};
    float d[3];
    double b[9], n;
    int channel, i, c;
    d[0] = 0.3f;
    d[1] = -0.5f;
    d[2] = 0.7f;
    n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (c = 0; c < 3; ++c) d[c] = (float)(d[c] / n);
    basis(d, b);
    for (channel = 0; channel < 3; ++channel) {
        for (i = 0; i < 9; ++i) {
            float sh[27], radiance[3], irradiance[3];
            memset(sh, 0, sizeof sh);
            sh[channel * 9 + i] = 1.0f;
            EXPECT_OK(tp_sh_eval_radiance(sh, d, radiance));
            EXPECT_OK(tp_sh_eval_irradiance(sh, d, irradiance));
            for (c = 0; c < 3; ++c) {
                CHECK_NEAR(radiance[c], c == channel ? b[i] : 0.0, 1e-5);
                CHECK_NEAR(irradiance[c], c == channel ? lobe[band_of(i)] * b[i] : 0.0, 1e-5);
            }
        }
    }
}

static void test_sh_ambient_and_directional(void) {
    float sh[27], out[3];
    const float rgb[3] = {0.5f, 1.0f, 2.0f};
    const float up[3] = {0.0f, 0.0f, 1.0f};
    const float down[3] = {0.0f, 0.0f, -1.0f};
    const float side[3] = {1.0f, 0.0f, 0.0f};
    int c;

    memset(sh, 0, sizeof sh);
    EXPECT_OK(tp_sh_add_ambient(sh, rgb));
    /* Uniform radiance L: radiance L everywhere, irradiance pi L on any surface. */
    EXPECT_OK(tp_sh_eval_radiance(sh, side, out));
    for (c = 0; c < 3; ++c) CHECK_NEAR(out[c], rgb[c], 1e-5 * rgb[c]);
    EXPECT_OK(tp_sh_eval_irradiance(sh, up, out));
    for (c = 0; c < 3; ++c) CHECK_NEAR(out[c], kPi * rgb[c], 1e-5 * kPi * rgb[c]);
    for (c = 0; c < 3; ++c) CHECK_NEAR(sh[c * 9], rgb[c] * sqrt(4.0 * kPi), 1e-5);

    /* A delta of irradiance E arriving from +z (travelling along -z): the L2 projection gives
       E * sum_l A_l (2l+1)/(4 pi) P_l(cos) = E * (1/4 + 1/2 cos + 5/16 (3 cos^2 - 1)). */
    memset(sh, 0, sizeof sh);
    EXPECT_OK(tp_sh_add_directional(sh, down, rgb));
    EXPECT_OK(tp_sh_eval_irradiance(sh, up, out));
    for (c = 0; c < 3; ++c) CHECK_NEAR(out[c], 1.0625 * rgb[c], 1e-4 * rgb[c]);
    EXPECT_OK(tp_sh_eval_irradiance(sh, down, out));
    for (c = 0; c < 3; ++c) CHECK_NEAR(out[c], 0.0625 * rgb[c], 1e-4 * rgb[c]);
    EXPECT_OK(tp_sh_eval_irradiance(sh, side, out));
    for (c = 0; c < 3; ++c) CHECK_NEAR(out[c], 0.09375 * rgb[c], 1e-4 * rgb[c]);

    /* Errors: null pointers, non-finite directions. */
    {
        float nan_dir[3];
        nan_dir[0] = (float)NAN;
        nan_dir[1] = 0.0f;
        nan_dir[2] = 1.0f;
        EXPECT_STATUS(tp_sh_eval_radiance(NULL, up, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_eval_radiance(sh, NULL, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_eval_radiance(sh, up, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_eval_irradiance(NULL, up, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_eval_irradiance(sh, NULL, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_eval_irradiance(sh, up, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_add_ambient(NULL, rgb), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_add_ambient(sh, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_add_directional(NULL, up, rgb), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_add_directional(sh, NULL, rgb), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_add_directional(sh, up, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_eval_radiance(sh, nan_dir, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_add_directional(sh, nan_dir, rgb), TP_ERROR_INVALID_ARGUMENT);
    }
}

/* ---------------------------------------------------------------------------------------------- */
/* Stores. */

#define CLOUD 160

/* A linear field: SH coefficient k at p is a_k + b_k . p. */
static float linear_field(int k, const float p[3]) {
    return (float)(0.1 * (k % 7) + 0.5 + 0.2 * p[0] * ((k % 3) - 1) + 0.15 * p[1] * ((k % 5) - 2) / 2.0 -
                   0.1 * p[2] * ((k % 4) - 1.5));
}

/* CLOUD probes in the cube [-1, 1]^3 with its 8 corners first (so the hull is the cube). */
static void make_cloud(float* positions, float* sh, int count) {
    int i, k;
    for (i = 0; i < count; ++i) {
        float* p = positions + 3 * i;
        if (i < 8) {
            p[0] = (i & 1) ? 1.0f : -1.0f;
            p[1] = (i & 2) ? 1.0f : -1.0f;
            p[2] = (i & 4) ? 1.0f : -1.0f;
        } else {
            p[0] = uniform(-1, 1);
            p[1] = uniform(-1, 1);
            p[2] = uniform(-1, 1);
        }
        if (sh)
            for (k = 0; k < 27; ++k) sh[27 * i + k] = linear_field(k, p);
    }
}

static tp_store* build_cloud(float* positions, float* sh, uint32_t flags) {
    tp_build_options options;
    tp_store* store = NULL;
    tp_build_options_init(&options);
    options.flags = flags;
    make_cloud(positions, sh, CLOUD);
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, CLOUD, &options, &store));
    CHECK(store != NULL);
    return store;
}

/* Half-precision SH: a relative error of 2^-11 per value, plus float rounding in the blend. */
static double sh_tolerance(double value) { return 2e-3 * fabs(value) + 1e-4; }

static void test_store_build_errors(void) {
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

static void test_store_build_progress(void) {
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

static void test_store_queries(void) {
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

static void test_store_info_and_struct_size(void) {
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
    CHECK(info.format_version == 4);
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

/* The blob checksum of store_format.h, to forge a consistent blob: FNV-1a 64 over little-endian 64-bit
   words, each step followed by hash ^= hash >> 29 (seeded with the size, the last word zero-padded),
   the checksum field read as zero. */
#define CHECKSUM_OFFSET 104 /* formats 3 and 4: after magic, 9 uint32 (axis included), grid, origin, bounds */
static void repair_checksum(unsigned char* data, size_t size) {
    uint64_t hash = 14695981039346656037ull ^ (uint64_t)size;
    size_t i, k;
    for (i = 0; i < size; i += 8) {
        uint64_t word = 0;
        for (k = 0; k < 8 && i + k < size; ++k) {
            const size_t at = i + k;
            const unsigned char byte = (at >= CHECKSUM_OFFSET && at < CHECKSUM_OFFSET + 8) ? 0 : data[at];
            word |= (uint64_t)byte << (8 * k);
        }
        hash ^= word;
        hash *= 1099511628211ull;
        hash ^= hash >> 29;
    }
    for (i = 0; i < 8; ++i) data[CHECKSUM_OFFSET + i] = (unsigned char)(hash >> (8 * i));
}

static void test_store_blobs_and_files(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    tp_store *store = build_cloud(positions, sh, 0), *copy = NULL;
    const void* blob;
    const void* blob2;
    size_t size = 0, size2 = 0, cut;
    unsigned char* bytes;
    int rejected = 1, intact = 1;
    char path[256];
    if (!store) return;
    EXPECT_OK(tp_store_blob(store, &blob, &size));
    CHECK(size > 112);
    EXPECT_STATUS(tp_store_blob(NULL, &blob, &size), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_blob(store, NULL, &size), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_blob(store, &blob, NULL), TP_ERROR_INVALID_ARGUMENT);

    /* Round trip through memory: identical bytes and identical answers. */
    EXPECT_OK(tp_store_load(blob, size, &copy));
    if (copy) {
        float a[27], b[27];
        const float p[3] = {0.3f, -0.2f, 0.6f};
        EXPECT_OK(tp_store_blob(copy, &blob2, &size2));
        CHECK(size2 == size && memcmp(blob, blob2, size) == 0);
        EXPECT_OK(tp_store_interpolate(store, p, NULL, a));
        EXPECT_OK(tp_store_interpolate(copy, p, NULL, b));
        CHECK(memcmp(a, b, sizeof a) == 0);
        tp_store_release(copy);
        copy = NULL;
    }

    /* Round trip through a file, written atomically. */
    sprintf(path, "harness_store_%d.tpb", (int)(size % 1000));
    EXPECT_OK(tp_store_save_file(store, path));
    EXPECT_OK(tp_store_load_file(path, &copy));
    if (copy) {
        EXPECT_OK(tp_store_blob(copy, &blob2, &size2));
        CHECK(size2 == size && memcmp(blob, blob2, size) == 0);
        tp_store_release(copy);
        copy = NULL;
    }
    remove(path);
    EXPECT_STATUS(tp_store_save_file(store, "/nonexistent-dir/sub/store.tpb"), TP_ERROR_IO);
    EXPECT_STATUS(tp_store_save_file(store, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_save_file(NULL, path), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load_file("/nonexistent-dir/store.tpb", &copy), TP_ERROR_IO);
    EXPECT_STATUS(tp_store_load_file(NULL, &copy), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load_file(path, NULL), TP_ERROR_INVALID_ARGUMENT);
    CHECK(copy == NULL);

    /* Bad blobs: empty, null, every truncated prefix, one extra byte, flipped bytes, an unknown version. */
    EXPECT_STATUS(tp_store_load(blob, 0, &copy), TP_ERROR_INVALID_BLOB);
    EXPECT_STATUS(tp_store_load(NULL, size, &copy), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_store_load(blob, size, NULL), TP_ERROR_INVALID_ARGUMENT);
    bytes = (unsigned char*)malloc(size + 1);
    if (!bytes) return;
    memcpy(bytes, blob, size);
    for (cut = 0; cut < size; cut += (cut < 256 ? 1 : 97)) {
        tp_status status = tp_store_load(bytes, cut, &copy);
        if (status != TP_ERROR_INVALID_BLOB || copy != NULL) rejected = 0;
    }
    CHECK(rejected);
    bytes[size] = 0;
    EXPECT_STATUS(tp_store_load(bytes, size + 1, &copy), TP_ERROR_INVALID_BLOB);
    for (cut = 0; cut < size; cut += 61) {
        tp_status status;
        bytes[cut] ^= 0x5A;
        status = tp_store_load(bytes, size, &copy);
        if (status == TP_OK) {
            intact = 0;
            tp_store_release(copy);
            copy = NULL;
        }
        bytes[cut] ^= 0x5A;
    }
    CHECK(intact);
    bytes[0] = 'X';
    EXPECT_STATUS(tp_store_load(bytes, size, &copy), TP_ERROR_INVALID_BLOB);
    bytes[0] = 'T';
    {
        const unsigned char version = bytes[8]; /* format_version, little-endian uint32 after the magic */
        bytes[8] = 99;
        repair_checksum(bytes, size);
        EXPECT_STATUS(tp_store_load(bytes, size, &copy), TP_ERROR_VERSION);
        bytes[8] = version;
    }
    repair_checksum(bytes, size);
    EXPECT_OK(tp_store_load(bytes, size, &copy));
    tp_store_release(copy);
    copy = NULL;
    /* A file that is not a store. */
    {
        FILE* f = fopen(path, "wb");
        if (f) {
            fputs("not a store\n", f);
            fclose(f);
            EXPECT_STATUS(tp_store_load_file(path, &copy), TP_ERROR_INVALID_BLOB);
            remove(path);
        }
    }
    free(bytes);
    tp_store_release(store);
}

static void test_store_without_extrapolation(void) {
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
    tp_store_release(store);
}

/* ---------------------------------------------------------------------------------------------- */
/* Format 3: batch options (threads, chained hints), the compact layout, old formats refused. */

/* 1 if text holds the decimal number n with no digit directly before or after it. */
static int mentions_number(const char* text, unsigned long n) {
    char digits[32];
    const char* at = text;
    size_t length;
    sprintf(digits, "%lu", n);
    length = strlen(digits);
    while ((at = strstr(at, digits)) != NULL) {
        int before = at > text && at[-1] >= '0' && at[-1] <= '9';
        int after = at[length] >= '0' && at[length] <= '9';
        if (!before && !after) return 1;
        ++at;
    }
    return 0;
}

/* Weight of probe in the 4 slots (slots that repeat a probe add up). */
static double weight_of(const uint32_t probes[4], const float weights[4], uint32_t probe) {
    double sum = 0.0;
    int k;
    for (k = 0; k < 4; ++k)
        if (probes[k] == probe) sum += weights[k];
    return sum;
}

#define BIG_BATCH 10000

static void test_batch_options(void) {
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

static tp_store* build_with_flags(const float* positions, const float* sh, size_t count, uint32_t flags) {
    tp_build_options options;
    tp_store* store = NULL;
    tp_build_options_init(&options);
    options.flags = flags;
    EXPECT_OK(tp_store_build(positions, 0, sh, 0, count, &options, &store));
    return store;
}

static tp_store_info info_of(const tp_store* store) {
    tp_store_info info;
    memset(&info, 0, sizeof info);
    info.struct_size = sizeof info;
    EXPECT_OK(tp_store_get_info(store, &info));
    return info;
}

static void test_compact_layout(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static const uint32_t extra_flags[3] = {0u, TP_BUILD_INDEX32, TP_BUILD_NO_EXTRAPOLATION};
    int variant;
    make_cloud(positions, sh, CLOUD);
    for (variant = 0; variant < 3; ++variant) {
        const uint32_t extra = extra_flags[variant];
        tp_store* fast = build_with_flags(positions, sh, CLOUD, extra);
        tp_store* compact = build_with_flags(positions, sh, CLOUD, extra | TP_BUILD_COMPACT);
        tp_store* reloaded = NULL;
        tp_store_info fast_info, compact_info;
        const void *fast_blob, *compact_blob, *reloaded_blob;
        size_t fast_size = 0, compact_size = 0, reloaded_size = 0;
        int i, k, same_cells = 1, same_kinds = 1, same_status = 1, walked_same = 1;
        double worst = 0.0;
        int32_t fast_hint = -1, compact_hint = -1;
        if (!fast || !compact) {
            tp_store_release(fast);
            tp_store_release(compact);
            return;
        }
        fast_info = info_of(fast);
        compact_info = info_of(compact);
        CHECK(fast_info.format_version == 4 && compact_info.format_version == 4);
        CHECK(fast_info.flags == extra);
        CHECK(compact_info.flags == (extra | TP_BUILD_COMPACT));
        CHECK(compact_info.index_bits == fast_info.index_bits);
        CHECK(compact_info.cells == fast_info.cells && compact_info.inner_cells == fast_info.inner_cells);
        EXPECT_OK(tp_store_blob(fast, &fast_blob, &fast_size));
        EXPECT_OK(tp_store_blob(compact, &compact_blob, &compact_size));
        CHECK(compact_size < fast_size);
        CHECK(compact_info.bytes == compact_size);

        /* The same cell and weights within 1e-6, cold and walking, inside and outside the hull. */
        for (i = 0; i < 2000; ++i) {
            float p[3];
            tp_location a, b;
            tp_status sa, sb;
            p[0] = uniform(-1.5, 1.5);
            p[1] = uniform(-1.5, 1.5);
            p[2] = uniform(-1.5, 1.5);
            memset(&a, 0, sizeof a);
            memset(&b, 0, sizeof b);
            a.struct_size = b.struct_size = sizeof a;
            sa = tp_store_locate(fast, p, NULL, &a);
            sb = tp_store_locate(compact, p, NULL, &b);
            if (sa != sb || (sa != TP_OK && sa != TP_ERROR_OUTSIDE)) same_status = 0;
            if (sa != TP_OK || sb != TP_OK) continue;
            if (a.cell != b.cell) same_cells = 0;
            if (a.cell_kind != b.cell_kind) same_kinds = 0;
            for (k = 0; k < 4; ++k) {
                double d1 = fabs(weight_of(a.probes, a.weights, a.probes[k]) -
                                 weight_of(b.probes, b.weights, a.probes[k]));
                double d2 = fabs(weight_of(a.probes, a.weights, b.probes[k]) -
                                 weight_of(b.probes, b.weights, b.probes[k]));
                if (d1 > worst) worst = d1;
                if (d2 > worst) worst = d2;
            }
            {
                tp_status wa = tp_store_locate(fast, p, &fast_hint, &a);
                tp_status wb = tp_store_locate(compact, p, &compact_hint, &b);
                if (wa != wb || (wa == TP_OK && (a.cell != b.cell || fast_hint != compact_hint))) walked_same = 0;
            }
        }
        CHECK(same_status);
        CHECK(same_cells);
        CHECK(same_kinds);
        CHECK(walked_same);
        CHECK_NEAR(worst, 0.0, 1e-6);

        /* The compact blob round-trips byte for byte and stays compact. */
        EXPECT_OK(tp_store_load(compact_blob, compact_size, &reloaded));
        if (reloaded) {
            const float p[3] = {0.2f, -0.3f, 0.4f};
            float x[27], y[27];
            EXPECT_OK(tp_store_blob(reloaded, &reloaded_blob, &reloaded_size));
            CHECK(reloaded_size == compact_size && memcmp(reloaded_blob, compact_blob, compact_size) == 0);
            CHECK((info_of(reloaded).flags & TP_BUILD_COMPACT) != 0);
            EXPECT_OK(tp_store_interpolate(compact, p, NULL, x));
            EXPECT_OK(tp_store_interpolate(reloaded, p, NULL, y));
            CHECK(memcmp(x, y, sizeof x) == 0);
            tp_store_release(reloaded);
        }
        tp_store_release(compact);
        tp_store_release(fast);
    }
}

/* A blob of another format version (only the uint32 at byte 8 changed, nothing repaired) is refused
   as a version, not as corruption, and the message says to rebuild. */
static void test_old_format_refused(void) {
    static float positions[3 * CLOUD], sh[27 * CLOUD];
    static const uint32_t versions[5] = {3u, 2u, 1u, 5u, 0u};
    int layout, v;
    make_cloud(positions, sh, CLOUD);
    for (layout = 0; layout < 2; ++layout) {
        tp_store* store = build_with_flags(positions, sh, CLOUD, layout ? TP_BUILD_COMPACT : 0u);
        const void* blob;
        size_t size = 0;
        unsigned char* bytes;
        if (!store) return;
        EXPECT_OK(tp_store_blob(store, &blob, &size));
        bytes = (unsigned char*)malloc(size);
        if (!bytes) {
            tp_store_release(store);
            return;
        }
        memcpy(bytes, blob, size);
        CHECK(bytes[8] == 4 && bytes[9] == 0 && bytes[10] == 0 && bytes[11] == 0);
        for (v = 0; v < 5; ++v) {
            tp_store* old = NULL;
            bytes[8] = (unsigned char)versions[v];
            EXPECT_STATUS(tp_store_load(bytes, size, &old), TP_ERROR_VERSION);
            CHECK(strstr(tp_last_error(), "rebuild") != NULL);
            CHECK(mentions_number(tp_last_error(), versions[v]));
            CHECK(old == NULL);
            tp_store_release(old);
        }
        bytes[8] = 4;
        {
            tp_store* again = NULL;
            EXPECT_OK(tp_store_load(bytes, size, &again));
            tp_store_release(again);
        }
        free(bytes);
        tp_store_release(store);
    }
}

/* A batch with queries outside a store without extrapolation: TP_ERROR_OUTSIDE naming the first,
   zero SH and weights for those outside, the others answered. */
static void test_outside_batch(void) {
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

/* Small and degenerate probe sets (the header: 1, 2, collinear, flat and general are accepted). */
static void test_small_sets(void) {
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

/* ---------------------------------------------------------------------------------------------- */
/* Shadow caster volumes. */

static const float kCubePlanes[24] = {1, 0, 0, 1, -1, 0, 0, 1, 0, 1, 0, 1, 0, -1, 0, 1, 0, 0, 1, 1, 0, 0, -1, 1};

static int inside_all(const float* planes, size_t count, const float p[3], float slack) {
    size_t i;
    for (i = 0; i < count; ++i) {
        const float* q = planes + 4 * i;
        float n = sqrtf(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        if (q[0] * p[0] + q[1] * p[1] + q[2] * p[2] + q[3] < -slack * n) return 0;
    }
    return 1;
}

static int sphere_hits(const float* planes, size_t count, float x, float y, float z, float r) {
    float c[3];
    int hit = -1;
    c[0] = x, c[1] = y, c[2] = z;
    EXPECT_OK(tp_volume_test_sphere(planes, count, c, r, &hit));
    return hit;
}

static int box_hits(const float* planes, size_t count, float x, float y, float z, float half) {
    float lo[3], hi[3];
    int hit = -1;
    lo[0] = x - half, lo[1] = y - half, lo[2] = z - half;
    hi[0] = x + half, hi[1] = y + half, hi[2] = z + half;
    EXPECT_OK(tp_volume_test_aabb(planes, count, lo, hi, &hit));
    return hit;
}

static void test_shadow_caster_volumes(void) {
    size_t bound = tp_shadow_caster_volume_bound(6), count = 0;
    float* planes;
    const float light_position[3] = {0.0f, 5.0f, 0.0f};
    const float down[3] = {0.0f, -1.0f, 0.0f};
    int corner, contained = 1;
    CHECK(bound >= 6);
    CHECK(tp_shadow_caster_volume_bound(12) >= bound);
    planes = (float*)malloc(4 * bound * sizeof(float));
    if (!planes) return;

    /* Point light above the cube [-1, 1]^3: the volume is the hull of the cube and the light. */
    EXPECT_OK(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, planes, bound, &count));
    CHECK(count >= 5 && count <= bound);
    for (corner = 0; corner < 8; ++corner) {
        float p[3];
        p[0] = (corner & 1) ? 1.0f : -1.0f;
        p[1] = (corner & 2) ? 1.0f : -1.0f;
        p[2] = (corner & 4) ? 1.0f : -1.0f;
        contained &= inside_all(planes, count, p, 1e-4f);
    }
    contained &= inside_all(planes, count, light_position, 1e-4f);
    CHECK(contained);
    CHECK(sphere_hits(planes, count, 0.0f, 3.0f, 0.0f, 0.1f) == 1);  /* between light and cube */
    CHECK(sphere_hits(planes, count, 0.0f, 0.0f, 0.0f, 0.1f) == 1);  /* inside the cube */
    CHECK(sphere_hits(planes, count, 3.0f, 3.0f, 0.0f, 0.5f) == 0);  /* beside the cone */
    CHECK(sphere_hits(planes, count, 0.0f, 7.0f, 0.0f, 0.5f) == 0);  /* behind the light */
    CHECK(sphere_hits(planes, count, 0.0f, -3.0f, 0.0f, 0.5f) == 0); /* below the cube */
    CHECK(box_hits(planes, count, 0.2f, 2.0f, -0.2f, 0.2f) == 1);
    CHECK(box_hits(planes, count, 4.0f, 0.0f, 4.0f, 0.5f) == 0);
    CHECK(box_hits(planes, count, 0.0f, 8.0f, 0.0f, 0.5f) == 0);
    CHECK(box_hits(planes, count, 0.0f, 5.0f, 0.0f, 10.0f) == 1);    /* a box containing everything */

    /* Directional light travelling down: the cube swept up to infinity. */
    EXPECT_OK(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_DIRECTIONAL, down, planes, bound, &count));
    CHECK(count >= 5 && count <= bound);
    CHECK(sphere_hits(planes, count, 0.0f, 1000.0f, 0.0f, 0.5f) == 1);
    CHECK(sphere_hits(planes, count, 0.5f, 3.0f, -0.5f, 0.1f) == 1);
    CHECK(sphere_hits(planes, count, 5.0f, 3.0f, 0.0f, 0.5f) == 0);
    CHECK(sphere_hits(planes, count, 0.0f, -5.0f, 0.0f, 1.0f) == 0);
    CHECK(box_hits(planes, count, 0.0f, 50.0f, 0.0f, 2.0f) == 1);
    CHECK(box_hits(planes, count, 0.0f, 50.0f, 10.0f, 2.0f) == 0);

    /* Errors. */
    {
        float nan_light[3];
        const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
        int hit;
        nan_light[0] = (float)NAN, nan_light[1] = 0.0f, nan_light[2] = 0.0f;
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, planes, 2, &count),
                      TP_ERROR_BUFFER_TOO_SMALL);
        EXPECT_STATUS(tp_shadow_caster_volume(NULL, 6, TP_LIGHT_POINT, light_position, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, NULL, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, NULL, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, light_position, planes, bound, NULL),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, 77u, light_position, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_shadow_caster_volume(kCubePlanes, 6, TP_LIGHT_POINT, nan_light, planes, bound, &count),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_FAILS(tp_shadow_caster_volume(kCubePlanes, 0, TP_LIGHT_POINT, light_position, planes, bound, &count));
        EXPECT_STATUS(tp_volume_test_aabb(NULL, 6, lo, hi, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_aabb(kCubePlanes, 6, NULL, hi, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_aabb(kCubePlanes, 6, lo, hi, NULL), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_aabb(kCubePlanes, 6, lo, nan_light, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(NULL, 6, lo, 1.0f, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(kCubePlanes, 6, lo, -1.0f, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(kCubePlanes, 6, lo, (float)NAN, &hit), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_volume_test_sphere(kCubePlanes, 6, lo, 1.0f, NULL), TP_ERROR_INVALID_ARGUMENT);
    }
    free(planes);
}

/* ---------------------------------------------------------------------------------------------- */
/* Scenes and the bake. */

static int cancel_bake(void* user, float fraction, const char* stage) {
    int* calls = (int*)user;
    (void)fraction;
    (void)stage;
    ++*calls;
    return 1;
}

static void test_scene_and_bake(void) {
    tp_scene* scene = NULL;
    const float sky[3] = {0.5f, 0.25f, 1.0f};
    float positions[6] = {0, 0, 0, 3, -0.5f, 2};
    float baked[54], expected[27];
    const float* listed = NULL;
    size_t listed_count = 0;
    tp_bake_options options;
    tp_effects_plan plan;
    char text[256];
    int k, p;

    EXPECT_OK(tp_scene_release(NULL));
    EXPECT_STATUS(tp_scene_create(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_OK(tp_scene_create(&scene));
    if (!scene) return;

    /* Uniform sky, nothing else: every probe holds exactly the constant-radiance SH. */
    EXPECT_OK(tp_scene_set_sky_color(scene, sky));
    EXPECT_OK(tp_scene_set_probes(scene, positions, 2));
    EXPECT_OK(tp_scene_probes(scene, &listed, &listed_count));
    CHECK(listed_count == 2 && listed != NULL && memcmp(listed, positions, sizeof positions) == 0);
    tp_bake_options_init(&options);
    options.rays = 64;
    options.bounces = 1;
    memset(&plan, 0, sizeof plan);
    plan.struct_size = sizeof plan;
    text[0] = '\0';
    EXPECT_OK(tp_bake_plan(scene, positions, 0, 2, &options, &plan, text, sizeof text));
    CHECK(plan.sky == 1);
    CHECK(plan.lights == 0 && plan.direct_lights == 0 && plan.meshes == 0);
    CHECK(plan.bounces == 0); /* nothing to bounce off */
    CHECK(strlen(text) > 0 && strstr(text, "sky") != NULL);
    EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, baked, 0));
    memset(expected, 0, sizeof expected);
    tp_sh_add_ambient(expected, sky);
    for (p = 0; p < 2; ++p)
        for (k = 0; k < 27; ++k) CHECK_NEAR(baked[27 * p + k], expected[k], 1e-3 * expected[k - k % 9] + 1e-4);

    /* The same through an SH sky. */
    EXPECT_OK(tp_scene_set_sky_sh(scene, expected));
    EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, baked, 0));
    for (k = 0; k < 27; ++k) CHECK_NEAR(baked[k], expected[k], 1e-3 * expected[k - k % 9] + 1e-4);

    /* A floor and a directional sun: the plan counts them; baking with a strided output works. */
    {
        static const float floor_vertices[12] = {-10, -1, -10, 10, -1, -10, 10, -1, 10, -10, -1, 10};
        static const uint32_t floor_indices[6] = {0, 2, 1, 0, 3, 2};
        static const uint32_t bad_indices[6] = {0, 2, 1, 0, 3, 9};
        float nan_vertices[12];
        tp_material material;
        tp_light sun;
        uint32_t mesh_id = 99, light_id = 99;
        float strided[2 * 30];
        const float black[3] = {0, 0, 0};
        float up[3] = {0, 1, 0}, irradiance[3];
        int calls = 0;
        tp_material_init(&material);
        material.albedo[0] = material.albedo[1] = material.albedo[2] = 0.5f;
        EXPECT_OK(tp_scene_add_mesh(scene, floor_vertices, 4, floor_indices, 2, &material, 1, NULL, &mesh_id));
        CHECK(mesh_id == 0);
        tp_light_init(&sun);
        sun.type = TP_LIGHT_DIRECTIONAL;
        sun.direction[0] = 0.0f, sun.direction[1] = -1.0f, sun.direction[2] = 0.0f;
        sun.color[0] = sun.color[1] = sun.color[2] = 1.0f;
        sun.intensity = 2.0f;
        EXPECT_OK(tp_scene_add_light(scene, &sun, &light_id));
        CHECK(light_id == 0);
        EXPECT_OK(tp_scene_set_sky_color(scene, black));
        EXPECT_OK(tp_bake_plan(scene, positions, 0, 2, &options, &plan, NULL, 0));
        CHECK(plan.lights == 1 && plan.direct_lights == 1 && plan.meshes == 1 && plan.sky == 0);
        CHECK(plan.bounces == 1);
        for (k = 0; k < 60; ++k) strided[k] = -3.0f;
        EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, strided, 120));
        CHECK(strided[27] == -3.0f && strided[59] == -3.0f);
        /* Facing the sun: its direct irradiance (with the L2 overshoot, 1.0625 E) plus light from the floor. */
        EXPECT_OK(tp_sh_eval_irradiance(strided, up, irradiance));
        CHECK(irradiance[0] > 2.0f && irradiance[0] < 2.5f);

        /* Culling of shadow casters changes nothing in the result. */
        options.flags = TP_BAKE_NO_CULLING;
        EXPECT_OK(tp_bake(scene, positions, 0, 2, &options, baked, 0));
        CHECK(memcmp(baked, strided, 108) == 0);
        options.flags = 0;

        options.progress = cancel_bake;
        options.progress_user = &calls;
        EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, baked, 0), TP_ERROR_CANCELLED);
        CHECK(calls >= 1);
        options.progress = NULL;

        /* Errors: naming what is wrong, nothing added. */
        memcpy(nan_vertices, floor_vertices, sizeof nan_vertices);
        nan_vertices[4] = (float)NAN;
        EXPECT_FAILS(tp_scene_add_mesh(scene, floor_vertices, 4, bad_indices, 2, &material, 1, NULL, &mesh_id));
        EXPECT_FAILS(tp_scene_add_mesh(scene, nan_vertices, 4, floor_indices, 2, &material, 1, NULL, &mesh_id));
        EXPECT_STATUS(tp_scene_add_mesh(NULL, floor_vertices, 4, floor_indices, 2, &material, 1, NULL, &mesh_id),
                      TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_scene_add_mesh(scene, NULL, 4, floor_indices, 2, &material, 1, NULL, &mesh_id),
                      TP_ERROR_INVALID_ARGUMENT);
        sun.intensity = -1.0f;
        EXPECT_FAILS(tp_scene_add_light(scene, &sun, &light_id));
        sun.intensity = 1.0f;
        sun.type = 42u;
        EXPECT_FAILS(tp_scene_add_light(scene, &sun, &light_id));
        EXPECT_STATUS(tp_scene_add_light(scene, NULL, &light_id), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_OK(tp_bake_plan(scene, positions, 0, 2, &options, &plan, NULL, 0));
        CHECK(plan.lights == 1 && plan.meshes == 1);
    }

    EXPECT_STATUS(tp_scene_set_sky_color(NULL, sky), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_set_sky_color(scene, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_set_sky_sh(scene, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_probes(NULL, &listed, &listed_count), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_scene_set_probes(scene, NULL, 2), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(NULL, positions, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(scene, NULL, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, NULL, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake(scene, positions, 4, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_FAILS(tp_bake(scene, positions, 0, 0, &options, baked, 0));
    EXPECT_STATUS(tp_bake_plan(NULL, positions, 0, 2, &options, &plan, NULL, 0), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_bake_plan(scene, positions, 0, 2, &options, NULL, NULL, 0), TP_ERROR_INVALID_ARGUMENT);
    options.rays = 0;
    EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    tp_bake_options_init(&options);
    positions[4] = (float)NAN;
    EXPECT_STATUS(tp_bake(scene, positions, 0, 2, &options, baked, 0), TP_ERROR_INVALID_ARGUMENT);
    tp_scene_release(scene);
}

static void test_scene_files(void) {
    tp_scene* scene = NULL;
    char path[1024];
    const char* bad_path = "harness_bad_scene.json";
    static const char* const samples[] = {"cornell_box.json", "two_rooms.json", "race_track.json"};
    size_t i;
    FILE* f;
    EXPECT_STATUS(tp_scene_load_file(NULL, &scene), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_FAILS(tp_scene_load_file("/nonexistent-dir/scene.json", &scene));
    f = fopen(bad_path, "w");
    if (f) {
        fputs("{ \"meshes\": [ { \"vertices\": [1, 2,", f);
        fclose(f);
        EXPECT_STATUS(tp_scene_load_file(bad_path, &scene), TP_ERROR_SCENE);
        CHECK(strstr(tp_last_error(), bad_path) != NULL);
        remove(bad_path);
    }
    CHECK(scene == NULL);
    /* The sample scenes of the repository that are present: each loads, lists probes, plans. */
    for (i = 0; i < sizeof samples / sizeof samples[0]; ++i) {
        sprintf(path, "%.900s/samples/scenes/%s", g_repo_root, samples[i]);
        const float* probes = NULL;
        size_t count = 0;
        tp_effects_plan plan;
        f = fopen(path, "r");
        if (!f) continue;
        fclose(f);
        EXPECT_OK(tp_scene_load_file(path, &scene));
        if (scene) {
            EXPECT_OK(tp_scene_probes(scene, &probes, &count));
            CHECK(count > 0);
            memset(&plan, 0, sizeof plan);
            plan.struct_size = sizeof plan;
            EXPECT_OK(tp_bake_plan(scene, probes, 0, count, NULL, &plan, NULL, 0));
            CHECK(plan.meshes > 0);
            tp_scene_release(scene);
            scene = NULL;
        }
    }
}

/* Format 4 scene data: occlusion probes of a mixed light behind a wall, and leak control from the scene. */
static void test_occlusion_and_leak_control(void) {
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
    options.occlusion_lights = 5;
    EXPECT_STATUS(tp_store_build(probes, 0, NULL, 0, 125, &options, &plain), TP_ERROR_INVALID_ARGUMENT);
    CHECK(plain == NULL);
    light.position[0] = 1;
    for (i = 0; i < 3; ++i) EXPECT_OK(tp_scene_add_light(scene, &light, &index));
    EXPECT_STATUS(tp_scene_add_light(scene, &light, &index), TP_ERROR_SCENE); /* a fifth mixed light */
    tp_store_release(store);
    tp_scene_release(scene);
}

int main(int argc, char** argv) {
    if (argc > 1) g_repo_root = argv[1];
    test_version_and_status_names();
    test_last_error_is_per_call();
    test_option_struct_defaults();
    test_sh_basis_functions();
    test_sh_ambient_and_directional();
    test_store_build_errors();
    test_store_build_progress();
    test_store_queries();
    test_store_info_and_struct_size();
    test_store_blobs_and_files();
    test_store_without_extrapolation();
    test_batch_options();
    test_compact_layout();
    test_old_format_refused();
    test_outside_batch();
    test_small_sets();
    test_shadow_caster_volumes();
    test_scene_and_bake();
    test_scene_files();
    test_occlusion_and_leak_control();
    printf("%d passed, %d failed\n", g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}
