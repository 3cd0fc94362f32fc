/* SH helpers against the basis and the cosine lobes written in the header. */
#include "harness.h"

static const double kPi = 3.14159265358979323846;

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

void test_sh_basis_functions(void) {
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

void test_sh_ambient_and_directional(void) {
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
