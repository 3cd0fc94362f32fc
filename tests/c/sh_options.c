/* SH evaluation options (order, window), the minimum irradiance and the non-negative window, against
   the formulas the header writes down, re-derived here in double, and the bit-for-bit identities it
   promises. */
#include "harness.h"

static const double kPi = 3.14159265358979323846;

/* The real orthonormal basis with exact constants (the header's are rounded to 6 digits). */
static void exact_basis(const double d[3], double out[9]) {
    const double y00 = 0.5 / sqrt(kPi), y1 = sqrt(3.0 / (4.0 * kPi)), y2 = sqrt(15.0 / (4.0 * kPi));
    const double y20 = sqrt(5.0 / (16.0 * kPi)), y22 = sqrt(15.0 / (16.0 * kPi));
    const double x = d[0], y = d[1], z = d[2];
    out[0] = y00;
    out[1] = y1 * y;
    out[2] = y1 * z;
    out[3] = y1 * x;
    out[4] = y2 * x * y;
    out[5] = y2 * y * z;
    out[6] = y20 * (3.0 * z * z - 1.0);
    out[7] = y2 * x * z;
    out[8] = y22 * (x * x - y * y);
}

/* The contract's irradiance of one channel in double: sum_i A_l(i) c_i Y_i(n). */
static double reference_irradiance(const float channel[9], const double n[3], int bands) {
    static const double lobe[3] = {3.14159265358979323846, 2.0943951023931957, 0.78539816339744831};
    double b[9], sum = 0.0;
    int i;
    exact_basis(n, b);
    for (i = 0; i < (bands == 3 ? 9 : 4); ++i) sum += lobe[i == 0 ? 0 : (i < 4 ? 1 : 2)] * channel[i] * b[i];
    return sum;
}

static void random_unit(float out[3]) {
    double v[3], length;
    int k;
    do {
        for (k = 0; k < 3; ++k) v[k] = uniform(-1.0, 1.0);
        length = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (length < 0.1 || length > 1.0);
    for (k = 0; k < 3; ++k) out[k] = (float)(v[k] / length);
}

/* Band 0 in [0.5, 1.5], bands 1 and 2 in [-0.6, 0.6]: often negative somewhere. */
static void random_sh(float sh[27]) {
    int c, i;
    for (c = 0; c < 3; ++c) {
        sh[9 * c] = uniform(0.5, 1.5);
        for (i = 1; i < 9; ++i) sh[9 * c + i] = uniform(-0.6, 0.6);
    }
}

static tp_sh_eval_options make_options(uint32_t order, uint32_t window, float strength) {
    tp_sh_eval_options options;
    tp_sh_eval_options_init(&options);
    options.order = order;
    options.window = window;
    options.window_strength = strength;
    return options;
}

static int same_floats(const float* a, const float* b, int count) {
    int i;
    for (i = 0; i < count; ++i)
        if (!(a[i] == b[i])) return 0;
    return 1;
}

static double dot3(const float a[3], const float b[3]) {
    return (double)a[0] * b[0] + (double)a[1] * b[1] + (double)a[2] * b[2];
}

void test_sh_eval_options_orders_and_windows(void) {
    tp_sh_eval_options options;
    float sh[27], normal[3], plain[3], ex[3], applied[27];
    int trial, c, i;

    /* Defaults: L2, no window, strength 0. */
    memset(&options, 0xAB, sizeof options);
    EXPECT_OK(tp_sh_eval_options_init(&options));
    CHECK(options.struct_size == sizeof options);
    CHECK(options.order == TP_SH_ORDER_L2);
    CHECK(options.window == TP_SH_WINDOW_NONE);
    CHECK(options.window_strength == 0.0f);

    for (trial = 0; trial < 20; ++trial) {
        random_sh(sh);
        random_unit(normal);
        /* L2 without a window (options NULL or the defaults) is the plain evaluation bit for bit. */
        EXPECT_OK(tp_sh_eval_irradiance(sh, normal, plain));
        EXPECT_OK(tp_sh_eval_irradiance_ex(sh, normal, NULL, ex));
        CHECK(same_floats(ex, plain, 3));
        options = make_options(TP_SH_ORDER_L2, TP_SH_WINDOW_NONE, 0.0f);
        EXPECT_OK(tp_sh_eval_irradiance_ex(sh, normal, &options, ex));
        CHECK(same_floats(ex, plain, 3));
        /* The window's strength is read for TP_SH_WINDOW_SLOAN only. */
        options.window_strength = -1.0f;
        EXPECT_OK(tp_sh_eval_irradiance_ex(sh, normal, &options, ex));
        CHECK(same_floats(ex, plain, 3));
        /* Sloan at strength 0 is the identity. */
        options = make_options(TP_SH_ORDER_L2, TP_SH_WINDOW_SLOAN, 0.0f);
        EXPECT_OK(tp_sh_eval_irradiance_ex(sh, normal, &options, ex));
        CHECK(same_floats(ex, plain, 3));
        memcpy(applied, sh, sizeof sh);
        EXPECT_OK(tp_sh_apply_options(applied, &options));
        CHECK(same_floats(applied, sh, 27));
        EXPECT_OK(tp_sh_apply_options(applied, NULL));
        CHECK(same_floats(applied, sh, 27));
    }

    /* L1: band 2 is not read (NaN there changes nothing); the answer is that of band 2 zeroed, and
       the contract's two-band sum. apply_options writes zeros into band 2 and keeps bands 0 and 1. */
    for (trial = 0; trial < 10; ++trial) {
        float zeroed[27], with_nan[27];
        double n[3];
        random_sh(sh);
        random_unit(normal);
        memcpy(zeroed, sh, sizeof sh);
        memcpy(with_nan, sh, sizeof sh);
        for (c = 0; c < 3; ++c)
            for (i = 4; i < 9; ++i) {
                zeroed[9 * c + i] = 0.0f;
                with_nan[9 * c + i] = (float)NAN;
            }
        options = make_options(TP_SH_ORDER_L1, TP_SH_WINDOW_NONE, 0.0f);
        EXPECT_OK(tp_sh_eval_irradiance(zeroed, normal, plain));
        EXPECT_OK(tp_sh_eval_irradiance_ex(with_nan, normal, &options, ex));
        CHECK(same_floats(ex, plain, 3));
        EXPECT_OK(tp_sh_eval_irradiance_ex(sh, normal, &options, ex));
        CHECK(same_floats(ex, plain, 3));
        for (i = 0; i < 3; ++i) n[i] = normal[i];
        for (c = 0; c < 3; ++c) CHECK_NEAR(ex[c], reference_irradiance(sh + 9 * c, n, 2), 1e-5);
        memcpy(applied, with_nan, sizeof sh);
        EXPECT_OK(tp_sh_apply_options(applied, &options));
        CHECK(same_floats(applied, zeroed, 27));
    }

    /* Sloan's window: band 0 kept, band l scaled by 1 / (1 + s (l (l + 1))^2), each product rounded
       once to float (s l^2 (l+1)^2 is exact in double for a float s, so the expected bits are these). */
    {
        static const float strengths[4] = {0.37f, 0.001f, 5.0f, 1e30f};
        int k;
        for (k = 0; k < 4; ++k) {
            const double s = strengths[k];
            const double w1 = 1.0 / (1.0 + s * 4.0), w2 = 1.0 / (1.0 + s * 36.0);
            float expected[27];
            random_sh(sh);
            for (c = 0; c < 3; ++c) {
                expected[9 * c] = sh[9 * c];
                for (i = 1; i < 9; ++i) expected[9 * c + i] = (float)((double)sh[9 * c + i] * (i < 4 ? w1 : w2));
            }
            options = make_options(TP_SH_ORDER_L2, TP_SH_WINDOW_SLOAN, strengths[k]);
            memcpy(applied, sh, sizeof sh);
            EXPECT_OK(tp_sh_apply_options(applied, &options));
            CHECK(same_floats(applied, expected, 27));
            /* L1 then the window: band 2 zero, band 1 scaled the same. */
            options.order = TP_SH_ORDER_L1;
            memcpy(applied, sh, sizeof sh);
            EXPECT_OK(tp_sh_apply_options(applied, &options));
            for (c = 0; c < 3; ++c)
                for (i = 4; i < 9; ++i) expected[9 * c + i] = 0.0f;
            CHECK(same_floats(applied, expected, 27));
        }
    }

    /* Every order and window: apply_options, then the plain evaluation, is eval_ex bit for bit. */
    for (trial = 0; trial < 27; ++trial) {
        const uint32_t order = (uint32_t)(trial % 3), window = (uint32_t)((trial / 3) % 3);
        random_sh(sh);
        random_unit(normal);
        options = make_options(order, window, uniform(0.0, 0.5));
        memcpy(applied, sh, sizeof sh);
        EXPECT_OK(tp_sh_apply_options(applied, &options));
        EXPECT_OK(tp_sh_eval_irradiance(applied, normal, plain));
        EXPECT_OK(tp_sh_eval_irradiance_ex(sh, normal, &options, ex));
        CHECK(same_floats(ex, plain, 3));
    }
}

/* ZH3 as the header defines it: axis a = the L1 direction of Rec. 709 luminance; per channel
   q = min(|L1 . a| / L0, sqrt 3), z = L0 q (0.08 + 0.6 q), band 2 = z sqrt(4 pi / 5) Y2m(a). */
static void expected_zh3(const float sh[27], double out[27]) {
    static const double luminance[3] = {0.2126, 0.7152, 0.0722};
    double a[3] = {0.0, 0.0, 0.0}, b[9], length;
    int c, i;
    for (c = 0; c < 3; ++c) {
        a[0] += luminance[c] * sh[9 * c + 3];
        a[1] += luminance[c] * sh[9 * c + 1];
        a[2] += luminance[c] * sh[9 * c + 2];
    }
    length = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (i = 0; i < 27; ++i) out[i] = (i % 9) < 4 ? sh[i] : 0.0;
    if (!(length > 0.0)) return;
    for (i = 0; i < 3; ++i) a[i] /= length;
    exact_basis(a, b);
    for (c = 0; c < 3; ++c) {
        const double l0 = sh[9 * c];
        double q, z;
        if (!(l0 > 0.0)) continue;
        q = fabs(sh[9 * c + 3] * a[0] + sh[9 * c + 1] * a[1] + sh[9 * c + 2] * a[2]) / l0;
        if (q > sqrt(3.0)) q = sqrt(3.0);
        z = l0 * q * (0.08 + 0.6 * q);
        for (i = 4; i < 9; ++i) out[9 * c + i] = z * sqrt(4.0 * kPi / 5.0) * b[i];
    }
}

void test_sh_zh3(void) {
    tp_sh_eval_options options = make_options(TP_SH_ORDER_ZH3, TP_SH_WINDOW_NONE, 0.0f);
    const float travel_a[3] = {0.36f, -0.48f, 0.8f}, travel_b[3] = {-0.6f, 0.0f, -0.8f};
    const float colour_a[3] = {1.0f, 0.5f, 2.0f}, colour_b[3] = {0.2f, 1.5f, 0.1f};
    const float ambient[3] = {0.3f, 0.2f, 0.4f};
    float sh[27], applied[27], with_nan[27];
    double expected[27];
    int c, i, trial;

    /* One directional light: q is sqrt 3 (the largest), the axis the light's arriving direction. */
    memset(sh, 0, sizeof sh);
    EXPECT_OK(tp_sh_add_directional(sh, travel_a, colour_a));
    memcpy(applied, sh, sizeof sh);
    EXPECT_OK(tp_sh_apply_options(applied, &options));
    expected_zh3(sh, expected);
    for (i = 0; i < 27; ++i) CHECK_NEAR(applied[i], expected[i], 1e-5 * sh[9 * (i / 9)]);
    {
        double a[3], b[9];
        for (i = 0; i < 3; ++i) a[i] = -travel_a[i];
        exact_basis(a, b);
        for (c = 0; c < 3; ++c)
            CHECK_NEAR(applied[9 * c + 6],
                       sh[9 * c] * sqrt(3.0) * (0.08 + 0.6 * sqrt(3.0)) * sqrt(4.0 * kPi / 5.0) * b[6],
                       1e-5 * sh[9 * c]);
    }

    /* Two coloured lights and ambient: the channels' L1 directions differ, luminance picks the axis. */
    for (trial = 0; trial < 8; ++trial) {
        float normal[3], ex[3], plain[3];
        memset(sh, 0, sizeof sh);
        EXPECT_OK(tp_sh_add_directional(sh, travel_a, colour_a));
        EXPECT_OK(tp_sh_add_directional(sh, travel_b, colour_b));
        EXPECT_OK(tp_sh_add_ambient(sh, ambient));
        for (i = 0; i < 27; ++i) sh[i] += uniform(-0.05, 0.05);
        /* Band 2 of the input is not read. */
        memcpy(with_nan, sh, sizeof sh);
        for (c = 0; c < 3; ++c)
            for (i = 4; i < 9; ++i) with_nan[9 * c + i] = (float)NAN;
        memcpy(applied, with_nan, sizeof sh);
        EXPECT_OK(tp_sh_apply_options(applied, &options));
        expected_zh3(sh, expected);
        for (i = 0; i < 27; ++i) CHECK_NEAR(applied[i], expected[i], 1e-5 * sh[9 * (i / 9)]);
        random_unit(normal);
        EXPECT_OK(tp_sh_eval_irradiance(applied, normal, plain));
        EXPECT_OK(tp_sh_eval_irradiance_ex(with_nan, normal, &options, ex));
        CHECK(same_floats(ex, plain, 3));
    }

    /* No zonal term for a channel with L0 <= 0, nor anywhere without a luminance L1 direction. */
    memset(sh, 0, sizeof sh);
    EXPECT_OK(tp_sh_add_directional(sh, travel_a, colour_a));
    sh[9] = -sh[9];
    memcpy(applied, sh, sizeof sh);
    EXPECT_OK(tp_sh_apply_options(applied, &options));
    for (i = 4; i < 9; ++i) CHECK(applied[9 + i] == 0.0f);
    CHECK(applied[4 + 2] != 0.0f && applied[18 + 6] != 0.0f);
    memset(sh, 0, sizeof sh);
    EXPECT_OK(tp_sh_add_ambient(sh, ambient));
    for (c = 0; c < 3; ++c)
        for (i = 4; i < 9; ++i) sh[9 * c + i] = 0.25f;
    memcpy(applied, sh, sizeof sh);
    EXPECT_OK(tp_sh_apply_options(applied, &options));
    for (c = 0; c < 3; ++c) {
        CHECK(applied[9 * c] == sh[9 * c]);
        for (i = 4; i < 9; ++i) CHECK(applied[9 * c + i] == 0.0f);
    }
}

/* Smallest over c in [-1, 1] of the irradiance of a unit directional light at cos c between the normal
   and the light's arriving direction, band l weighted by w_l: 1/4 + w1 c / 2 + w2 (5/32) (3 c^2 - 1). */
static double directional_min(double w1, double w2) {
    const double a2 = 15.0 * w2 / 32.0, a1 = 0.5 * w1, a0 = 0.25 - 5.0 * w2 / 32.0;
    const double vertex = a2 > 0.0 ? -a1 / (2.0 * a2) : -2.0;
    const double at_ends = fmin(a0 - a1 + a2, a0 + a1 + a2);
    return vertex > -1.0 && vertex < 1.0 ? fmin(at_ends, a0 - a1 * a1 / (4.0 * a2)) : at_ends;
}

/* The smallest Sloan strength that keeps directional_min non-negative, by bisection in double. */
static double directional_nonnegative_strength(void) {
    double low = 0.0, high = 1.0;
    int k;
    for (k = 0; k < 200; ++k) {
        const double mid = 0.5 * (low + high);
        if (directional_min(1.0 / (1.0 + 4.0 * mid), 1.0 / (1.0 + 36.0 * mid)) >= 0.0)
            high = mid;
        else
            low = mid;
    }
    return high;
}

void test_sh_min_irradiance_and_nonnegative_window(void) {
    const float travel[3] = {0.36f, -0.48f, 0.8f}, colour[3] = {1.0f, 0.5f, 2.0f};
    const float ambient[3] = {0.5f, 1.0f, 2.0f};
    tp_sh_eval_options options;
    float sh[27], low[3], normal[3], strength = -1.0f;
    int c;

    /* Ambient only: the irradiance is pi L0 Y00 everywhere. */
    memset(sh, 0, sizeof sh);
    EXPECT_OK(tp_sh_add_ambient(sh, ambient));
    EXPECT_OK(tp_sh_min_irradiance(sh, NULL, low, normal));
    for (c = 0; c < 3; ++c) CHECK_NEAR(low[c], kPi * sh[9 * c] * 0.5 / sqrt(kPi), 1e-6 * sh[9 * c]);
    CHECK_NEAR(dot3(normal, normal), 1.0, 1e-6);
    EXPECT_OK(tp_sh_nonnegative_window_strength(sh, NULL, &strength));
    CHECK(strength == 0.0f);

    /* A directional light in L2: E (3/32 + c/2 + 15 c^2 / 32) has its minimum -19/480 E at c = -8/15,
       c the cosine to the arriving direction -travel; the normal reported is the bluest (largest E). */
    memset(sh, 0, sizeof sh);
    EXPECT_OK(tp_sh_add_directional(sh, travel, colour));
    EXPECT_OK(tp_sh_min_irradiance(sh, NULL, low, normal));
    for (c = 0; c < 3; ++c) CHECK_NEAR(low[c], -19.0 / 480.0 * colour[c], 1e-5 * colour[c]);
    CHECK_NEAR(directional_min(1.0, 1.0), -19.0 / 480.0, 1e-15);
    CHECK_NEAR(dot3(normal, normal), 1.0, 1e-6);
    CHECK_NEAR(-dot3(normal, travel), -8.0 / 15.0, 1e-4);
    options = make_options(TP_SH_ORDER_L2, TP_SH_WINDOW_NONE, 0.0f);
    EXPECT_OK(tp_sh_min_irradiance(sh, &options, low, normal));
    for (c = 0; c < 3; ++c) CHECK_NEAR(low[c], -19.0 / 480.0 * colour[c], 1e-5 * colour[c]);

    /* The same light in L1: E (1/4 + c/2), smallest -E/4 facing away (c = -1). */
    options = make_options(TP_SH_ORDER_L1, TP_SH_WINDOW_NONE, 0.0f);
    EXPECT_OK(tp_sh_min_irradiance(sh, &options, low, normal));
    for (c = 0; c < 3; ++c) CHECK_NEAR(low[c], -0.25 * colour[c], 1e-5 * colour[c]);
    CHECK_NEAR(dot3(normal, travel), 1.0, 1e-5);
    /* Its non-negative window: w1 = 1 / (1 + 4 s) <= 1/2, so s = 1/4. */
    EXPECT_OK(tp_sh_nonnegative_window_strength(sh, &options, &strength));
    CHECK_NEAR(strength, 0.25, 1e-5);
    options.window = TP_SH_WINDOW_NONNEGATIVE;
    EXPECT_OK(tp_sh_min_irradiance(sh, &options, low, normal));
    for (c = 0; c < 3; ++c) CHECK(low[c] >= 0.0f && low[c] <= 1e-5f * colour[c]);

    /* L2: the strength matches a bisection of the analytic minimum; it leaves the minimum >= 0, while
       a slightly weaker Sloan window leaves it negative. */
    EXPECT_OK(tp_sh_nonnegative_window_strength(sh, NULL, &strength));
    CHECK_NEAR(strength, directional_nonnegative_strength(), 1e-4 * directional_nonnegative_strength());
    options = make_options(TP_SH_ORDER_L2, TP_SH_WINDOW_NONNEGATIVE, 0.0f);
    EXPECT_OK(tp_sh_min_irradiance(sh, &options, low, normal));
    for (c = 0; c < 3; ++c) CHECK(low[c] >= 0.0f);
    options = make_options(TP_SH_ORDER_L2, TP_SH_WINDOW_SLOAN, strength);
    EXPECT_OK(tp_sh_min_irradiance(sh, &options, low, normal));
    for (c = 0; c < 3; ++c) CHECK(low[c] >= 0.0f);
    options.window_strength = strength * 0.999f;
    EXPECT_OK(tp_sh_min_irradiance(sh, &options, low, normal));
    for (c = 0; c < 3; ++c) CHECK(low[c] < 0.0f);

    /* Random SH: NONNEGATIVE leaves every channel's minimum >= 0 under every order; the minimum is
       never above the irradiance at the normal it reports or at any sampled normal. */
    {
        int trial, k;
        for (trial = 0; trial < 12; ++trial) {
            const uint32_t order = (uint32_t)(trial % 3);
            float plain_low[3], sample[3], out[3];
            double smallest;
            random_sh(sh);
            options = make_options(order, TP_SH_WINDOW_NONNEGATIVE, 0.0f);
            EXPECT_OK(tp_sh_min_irradiance(sh, &options, low, normal));
            for (c = 0; c < 3; ++c) CHECK(low[c] >= 0.0f);
            options.window = TP_SH_WINDOW_NONE;
            EXPECT_OK(tp_sh_min_irradiance(sh, &options, plain_low, normal));
            EXPECT_OK(tp_sh_nonnegative_window_strength(sh, &options, &strength));
            smallest = fmin(plain_low[0], fmin(plain_low[1], plain_low[2]));
            CHECK((strength > 0.0f) == (smallest < 0.0));
            EXPECT_OK(tp_sh_eval_irradiance_ex(sh, normal, &options, out));
            CHECK_NEAR(fmin(out[0], fmin(out[1], out[2])), smallest, 1e-5);
            for (k = 0; k < 200; ++k) {
                random_unit(sample);
                EXPECT_OK(tp_sh_eval_irradiance_ex(sh, sample, &options, out));
                for (c = 0; c < 3; ++c) CHECK(out[c] >= plain_low[c] - 1e-5f);
            }
        }
    }

    /* No window lifts a channel whose L0 <= 0, so a negative ambient asks for none. */
    memset(sh, 0, sizeof sh);
    {
        const float dark[3] = {-1.0f, -1.0f, -1.0f};
        EXPECT_OK(tp_sh_add_ambient(sh, dark));
        EXPECT_OK(tp_sh_add_directional(sh, travel, colour));
        EXPECT_OK(tp_sh_nonnegative_window_strength(sh, NULL, &strength));
        CHECK(strength == 0.0f);
    }
}

void test_sh_eval_options_errors(void) {
    const float up[3] = {0.0f, 0.0f, 1.0f}, zero[3] = {0.0f, 0.0f, 0.0f};
    float nan_normal[3], sh[27], before[27], out[3] = {7.0f, 7.0f, 7.0f}, normal[3], strength = 0.0f;
    tp_sh_eval_options options, bad;
    int k;
    nan_normal[0] = (float)NAN;
    nan_normal[1] = 0.0f;
    nan_normal[2] = 1.0f;
    random_sh(sh);
    memcpy(before, sh, sizeof sh);
    tp_sh_eval_options_init(&options);

    EXPECT_STATUS(tp_sh_eval_options_init(NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_eval_irradiance_ex(NULL, up, &options, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_eval_irradiance_ex(sh, NULL, &options, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_eval_irradiance_ex(sh, up, &options, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_eval_irradiance_ex(sh, nan_normal, &options, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_eval_irradiance_ex(sh, zero, &options, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_apply_options(NULL, &options), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_min_irradiance(NULL, &options, out, normal), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_min_irradiance(sh, &options, NULL, normal), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_min_irradiance(sh, &options, out, NULL), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_nonnegative_window_strength(NULL, &options, &strength), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_nonnegative_window_strength(sh, &options, NULL), TP_ERROR_INVALID_ARGUMENT);

    /* Bad options, each refused by every function that reads them; sh is left as it was. */
    for (k = 0; k < 8; ++k) {
        bad = options;
        switch (k) {
            case 0: bad.order = 3u; break;
            case 1: bad.order = 0xFFFFFFFFu; break;
            case 2: bad.window = 3u; break;
            case 3: bad.window = TP_SH_WINDOW_SLOAN, bad.window_strength = -0.5f; break;
            case 4: bad.window = TP_SH_WINDOW_SLOAN, bad.window_strength = (float)NAN; break;
            case 5: bad.window = TP_SH_WINDOW_SLOAN, bad.window_strength = (float)INFINITY; break;
            case 6: bad.struct_size = 0u; break;
            default: bad.struct_size = 4u; break; /* ends before order */
        }
        EXPECT_STATUS(tp_sh_eval_irradiance_ex(sh, up, &bad, out), TP_ERROR_INVALID_ARGUMENT);
        EXPECT_STATUS(tp_sh_apply_options(sh, &bad), TP_ERROR_INVALID_ARGUMENT);
        CHECK(same_floats(sh, before, 27));
        EXPECT_STATUS(tp_sh_min_irradiance(sh, &bad, out, normal), TP_ERROR_INVALID_ARGUMENT);
        if (k < 2 || k > 5) /* the window fields are documented as not read here */
            EXPECT_STATUS(tp_sh_nonnegative_window_strength(sh, &bad, &strength), TP_ERROR_INVALID_ARGUMENT);
        else
            EXPECT_OK(tp_sh_nonnegative_window_strength(sh, &bad, &strength));
    }

    /* Non-finite SH: the minimum and the non-negative window need finite coefficients. */
    sh[13] = (float)INFINITY;
    memcpy(before, sh, sizeof sh);
    EXPECT_STATUS(tp_sh_min_irradiance(sh, NULL, out, normal), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_nonnegative_window_strength(sh, NULL, &strength), TP_ERROR_INVALID_ARGUMENT);
    bad = options;
    bad.window = TP_SH_WINDOW_NONNEGATIVE;
    EXPECT_STATUS(tp_sh_eval_irradiance_ex(sh, up, &bad, out), TP_ERROR_INVALID_ARGUMENT);
    EXPECT_STATUS(tp_sh_apply_options(sh, &bad), TP_ERROR_INVALID_ARGUMENT);
    CHECK(same_floats(sh, before, 27));
}
