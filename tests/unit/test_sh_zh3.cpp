// ZH3's hallucinated zonal term: analytic zonal lobes, the luminance axis, and a golden irradiance
// from the paper's published listing.
#include "core/sh.h"
#include "core/sh_eval_options.h"
#include "core/sh_zh3.h"
#include "sh_test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

using namespace tetprobe;
using namespace tetprobe::sh_test;

TEST_CASE("ZH3 reproduces a zonal lobe whose L2 coefficient follows the curve fit", "[sh_eval]") {
    // Radiance L0 Y00 + q L0 a.(Y1) + z Y20(a . w) about an oblique axis, with z the fit's value.
    const Direction a = unit(0.3, -0.5, 0.8);
    double basis[9];
    sh_basis(a.x, a.y, a.z, basis);
    const double q = 1.2, addition = std::sqrt(4.0 * kPi / 5.0);
    float sh[27];
    for (int c = 0; c < 3; ++c) {
        const double l0 = 0.5 + 0.25 * c;
        const double z = l0 * q * (0.08 + 0.6 * q);
        sh[9 * c] = float(l0);
        for (int i = 1; i < 4; ++i) sh[9 * c + i] = float(l0 * q * basis[i] / kShY1);
        for (int i = 4; i < 9; ++i) sh[9 * c + i] = float(z * addition * basis[i]);
    }
    float zh3[27];
    std::memcpy(zh3, sh, sizeof sh);
    sh_apply_order(zh3, ShOrder::zh3);
    for (const Direction& d : fibonacci_sphere(2000))
        for (int c = 0; c < 3; ++c) {
            const double scale = term_scale(sh + 9 * c);
            REQUIRE(std::fabs(irradiance(zh3 + 9 * c, d) - irradiance(sh + 9 * c, d)) <= 1e-6 * scale);
        }
}

namespace {

// Zonal radiance about axis a with band coefficients k_l (radiance sum_l k_l P_l(a . w) (2l+1)/4pi):
// its SH are k_l Y_lm(a) by the addition theorem; ZH3 from its L1 against the true L2 irradiance.
// The error of either at normal n is (pi/4) (z_true - z_model) Y20(a . n) with z = zonal coefficient,
// so ZH3's error is exactly (1 - z_zh3 / z_true) times L1's at every normal.
void check_zonal_error_ratio(const double k[3], const double rgb[3], const Direction& a) {
    double basis[9];
    sh_basis(a.x, a.y, a.z, basis);
    float sh[27];
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 9; ++i) sh[9 * c + i] = float(rgb[c] * k[kShBandOfCoefficient[i]] * basis[i]);
    float l1[27], zh3[27];
    std::memcpy(l1, sh, sizeof sh);
    std::memcpy(zh3, sh, sizeof sh);
    sh_apply_order(l1, ShOrder::l1);
    sh_apply_order(zh3, ShOrder::zh3);

    // Zonal coefficients: z Y20(t) = k2 (5/4pi) P2(t) gives z_true = k2 sqrt(5/4pi); the fit from
    // L0 = k0 Y00 and |L1| = k1 Y1.
    const double l0 = k[0] * kShY00, ratio = std::fmin(k[1] * kShY1 / l0, std::sqrt(3.0));
    const double z_true = k[2] * std::sqrt(5.0 / (4.0 * kPi)), z_zh3 = l0 * ratio * (0.08 + 0.6 * ratio);
    const double expected_ratio = 1.0 - z_zh3 / z_true;

    double worst_l1 = 0, worst_zh3 = 0;
    for (const Direction& d : fibonacci_sphere(4000))
        for (int c = 0; c < 3; ++c) {
            const double truth = irradiance(sh + 9 * c, d);
            const double error_l1 = irradiance(l1 + 9 * c, d) - truth;
            const double error_zh3 = irradiance(zh3 + 9 * c, d) - truth;
            REQUIRE(std::fabs(error_zh3 - expected_ratio * error_l1) <= 1e-6 * term_scale(sh + 9 * c));
            worst_l1 = std::max(worst_l1, std::fabs(error_l1));
            worst_zh3 = std::max(worst_zh3, std::fabs(error_zh3));
        }
    REQUIRE(worst_zh3 <= (std::fabs(expected_ratio) + 1e-4) * worst_l1);
}

}  // namespace

TEST_CASE("ZH3 of a directional light is within 13.3% of L1's error to the true L2 irradiance", "[sh_eval]") {
    // A delta of radiance: k_l = 1 for every band (sh_add_directional). |L1|/L0 = sqrt(3), the clamp,
    // so z_zh3 = Y1 (0.08 + 0.6 sqrt(3)) = 0.5469 against z_true = sqrt(5/4pi) = 0.6308: ratio 0.1330.
    const double k[3] = {1.0, 1.0, 1.0}, rgb[3] = {1.0, 2.0, 3.0};
    check_zonal_error_ratio(k, rgb, unit(-0.2, 0.9, 0.4));
    const double ratio = 1.0 - kShY1 * (0.08 + 0.6 * std::sqrt(3.0)) / std::sqrt(5.0 / (4.0 * kPi));
    REQUIRE(ratio == Approx(0.1330).margin(1e-4));

    // And through the public rewrite of sh_add_directional's projection, along an axis.
    float sh[27] = {};
    const float travel[3] = {0.0f, 0.0f, -1.0f}, colour[3] = {1.0f, 1.0f, 1.0f};
    sh_add_directional(sh, travel, colour);
    sh_apply_order(sh, ShOrder::zh3);
    const double z_expected = kShY1 * (0.08 + 0.6 * std::sqrt(3.0));
    REQUIRE(sh[6] == Approx(z_expected * std::sqrt(4.0 * kPi / 5.0) * 2.0 * kShY20).epsilon(1e-6));
    for (int i : {4, 5, 7, 8}) REQUIRE(std::fabs(sh[i]) <= 1e-7f);
}

TEST_CASE("ZH3 of a clamped-cosine lobe of radiance overshoots by 60% of L1's error", "[sh_eval]") {
    // Radiance max(0, a . w): k = (pi, 2pi/3, pi/4) (Funk-Hecke). |L1|/L0 = 2/sqrt(3); the fit gives
    // z_zh3 = 0.7907 against z_true = 0.4954: error -0.596 times L1's, still the smaller.
    const double k[3] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0}, rgb[3] = {0.5, 0.5, 0.5};
    check_zonal_error_ratio(k, rgb, unit(1.0, 1.0, 1.0));
}

TEST_CASE("ZH3's axis is the luminance L1 direction, shared by the channels", "[sh_eval]") {
    // Red from +x, green from +y, blue from +z, each a directional light; plus ambient.
    float sh[27] = {};
    const float ambient[3] = {0.5f, 0.5f, 0.5f};
    sh_add_ambient(sh, ambient);
    const float from_x[3] = {-1, 0, 0}, from_y[3] = {0, -1, 0}, from_z[3] = {0, 0, -1};
    const float red[3] = {1, 0, 0}, green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    sh_add_directional(sh, from_x, red);
    sh_add_directional(sh, from_y, green);
    sh_add_directional(sh, from_z, blue);
    float zh3[27];
    std::memcpy(zh3, sh, sizeof sh);
    sh_apply_order(zh3, ShOrder::zh3);

    const Direction a = unit(0.2126 * sh[3], 0.7152 * sh[9 + 1], 0.0722 * sh[18 + 2]);
    double basis[9];
    sh_basis(a.x, a.y, a.z, basis);
    for (int c = 0; c < 3; ++c) {
        const double l0 = sh[9 * c];
        const double along = std::fabs(sh[9 * c + 3] * a.x + sh[9 * c + 1] * a.y + sh[9 * c + 2] * a.z);
        const double ratio = along / l0;
        const double z = l0 * ratio * (0.08 + 0.6 * ratio);
        for (int i = 0; i < 4; ++i) REQUIRE(zh3[9 * c + i] == sh[9 * c + i]);
        for (int i = 4; i < 9; ++i)
            REQUIRE(zh3[9 * c + i] == Approx(z * std::sqrt(4.0 * kPi / 5.0) * basis[i]).margin(1e-6));
    }
}

TEST_CASE("ZH3 adds nothing without an L1 direction or to a channel without positive band 0", "[sh_eval]") {
    float sh[27] = {};
    for (int c = 0; c < 3; ++c) {
        sh[9 * c] = 1.0f;
        sh[9 * c + 6] = 0.7f;  // band 2 of the input is not read
    }
    sh_apply_order(sh, ShOrder::zh3);
    for (int c = 0; c < 3; ++c)
        for (int i = 4; i < 9; ++i) REQUIRE(sh[9 * c + i] == 0.0f);

    float dark[27] = {};
    dark[0] = 1.0f;
    dark[2] = 0.5f;       // red has an L1 direction
    dark[9] = -0.1f;      // green's band 0 is negative
    dark[9 + 2] = 0.3f;
    sh_apply_order(dark, ShOrder::zh3);
    REQUIRE(dark[6] != 0.0f);
    for (int i = 4; i < 9; ++i) REQUIRE(dark[9 + i] == 0.0f);
}


TEST_CASE("ZH3 irradiance matches a golden value from the paper's listing", "[sh_eval]") {
    // shHallucinateZH3Irradiance (Roughton et al., I3D 2024, published listing) in normalised units
    // (irradiance / pi): L0 Y00 + (2/3) Y1 (L1 . n) + 0.25 z sqrt(5/16pi) (3 t^2 - 1), t = a . n, with
    // a the normalised luminance L1 and z = L0 (0.08 r + 0.6 r^2), r = |L1 . a| / L0. Here every L1
    // is along a = (2, 3, 6) / 7 (blue's opposite, so |.| matters): red L0 1, L1 0.7 a; green half of
    // red; blue L0 0.25, L1 -0.35 a. Normal n = (0, 0.6, 0.8): t = 6.6/7 = 0.942857142857,
    // 3t^2 - 1 = 1.666938775510, sqrt(5/16pi) (3t^2 - 1) = 0.315391565253 * 1.666938775510 = 0.525738429588.
    //   red:   r = 0.7, z = 0.056 + 0.294 = 0.35; L1 . n = 0.66;
    //          0.282094791774 + (2/3) 0.488602511903 0.66 = 0.497079897011; + 0.25 0.35 0.525738429588
    //          = 0.046002112589; sum 0.543082009600; times pi 1.706142451657.
    //   green: exactly half of red: 0.853071225828.
    //   blue:  r = 1.4, z = 0.25 (0.112 + 1.176) = 0.322; L1 . n = -0.33;
    //          0.070523697943 - 0.107492552619 = -0.036968854675; + 0.25 0.322 0.525738429588
    //          = 0.042321943582; sum 0.005353088907; times pi 0.016817224783.
    const float sh[27] = {1.0f,  0.3f,   0.6f,   0.2f,   5.0f, -5.0f, 5.0f, -5.0f, 5.0f,    // band 2 not read
                          0.5f,  0.15f,  0.3f,   0.1f,   0.0f, 0.0f,  0.0f, 0.0f,  0.0f,
                          0.25f, -0.15f, -0.3f, -0.1f,   0.0f, 0.0f,  0.0f, 0.0f,  0.0f};
    const float n[3] = {0.0f, 0.6f, 0.8f};
    float rgb[3];
    sh_eval_irradiance_with_options(sh, n, options(ShOrder::zh3), rgb);
    // The inputs' rounding to float (~1e-7 here) and the float evaluation (< 3e-6, its proven bound),
    // against 2.3e-4 on red for 0.08 off by 1% and over 1.2e-3 for 0.6 or 0.25 off by 1%.
    const double golden[3] = {1.706142451657, 0.853071225828, 0.016817224783};
    for (int c = 0; c < 3; ++c) REQUIRE(std::fabs(rgb[c] - golden[c]) <= 4e-6);
}
