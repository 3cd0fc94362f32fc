// SH evaluation options (order, ZH3, windows) and the minimum irradiance, against analytic answers,
// bit-exact identities and brute-force sampling of the sphere.
#include "core/sh.h"
#include "core/sh_eval_options.h"
#include "core/sh_min_irradiance.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace tetprobe;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Direction {
    double x, y, z;
};

// N points spread evenly over the sphere (the Fibonacci lattice).
std::vector<Direction> fibonacci_sphere(int count) {
    std::vector<Direction> out;
    out.reserve(count);
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double z = 1.0 - (i + 0.5) * 2.0 / count;
        const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
        out.push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
    }
    return out;
}

// The contract's irradiance in double, from the float coefficients: the slow reference.
double irradiance(const float channel[9], const Direction& n) {
    double basis[9];
    sh_basis(n.x, n.y, n.z, basis);
    double sum = 0;
    for (int i = 0; i < 9; ++i) sum += sh_cosine_lobe_band(kShBandOfCoefficient[i]) * channel[i] * basis[i];
    return sum;
}

double sampled_min(const float channel[9], const std::vector<Direction>& directions) {
    double smallest = INFINITY;
    for (const Direction& d : directions) smallest = std::min(smallest, irradiance(channel, d));
    return smallest;
}

// Random SH with band 0 in [0.5, 1.5] and bands 1-2 in [-spread, spread]: often negative somewhere.
void random_sh(std::mt19937& rng, float sh[27], float spread = 0.6f) {
    std::uniform_real_distribution<float> l0(0.5f, 1.5f), rest(-spread, spread);
    for (int c = 0; c < 3; ++c) {
        sh[9 * c] = l0(rng);
        for (int i = 1; i < 9; ++i) sh[9 * c + i] = rest(rng);
    }
}

Direction unit(double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    return {x / l, y / l, z / l};
}

void to_float(const Direction& d, float out[3]) {
    out[0] = float(d.x);
    out[1] = float(d.y);
    out[2] = float(d.z);
}

// Largest magnitude of one channel's irradiance terms: the scale float rounding is measured against.
double term_scale(const float channel[9]) {
    double sum = 0;
    for (int i = 0; i < 9; ++i) sum += sh_cosine_lobe_band(kShBandOfCoefficient[i]) * std::fabs(channel[i]) * 1.1;
    return sum;
}

ShEvalOptions options(ShOrder order, ShWindow window = ShWindow::none, float strength = 0.0f) {
    ShEvalOptions o;
    o.order = order;
    o.window = window;
    o.window_strength = strength;
    return o;
}

}  // namespace

TEST_CASE("L2 without a window is sh_eval_irradiance bit for bit", "[sh_eval]") {
    std::mt19937 rng(1);
    for (int trial = 0; trial < 50; ++trial) {
        float sh[27];
        random_sh(rng, sh, 3.0f);
        for (const Direction& d : fibonacci_sphere(40)) {
            float n[3], plain[3], with_options[3];
            to_float(d, n);
            sh_eval_irradiance(sh, n, plain);
            sh_eval_irradiance_with_options(sh, n, ShEvalOptions{}, with_options);
            REQUIRE(std::memcmp(plain, with_options, sizeof plain) == 0);
        }
    }
}

TEST_CASE("L1 ignores band 2 exactly and equals the plain evaluation with band 2 zeroed", "[sh_eval]") {
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> noise(-5.0f, 5.0f);
    for (int trial = 0; trial < 50; ++trial) {
        float sh[27], other[27], zeroed[27];
        random_sh(rng, sh);
        std::memcpy(other, sh, sizeof sh);
        std::memcpy(zeroed, sh, sizeof sh);
        for (int c = 0; c < 3; ++c)
            for (int i = 4; i < 9; ++i) {
                other[9 * c + i] = noise(rng);
                zeroed[9 * c + i] = 0.0f;
            }
        for (const Direction& d : fibonacci_sphere(40)) {
            float n[3], a[3], b[3], plain[3];
            to_float(d, n);
            sh_eval_irradiance_with_options(sh, n, options(ShOrder::l1), a);
            sh_eval_irradiance_with_options(other, n, options(ShOrder::l1), b);
            sh_eval_irradiance(zeroed, n, plain);
            for (int c = 0; c < 3; ++c) {
                REQUIRE(a[c] == b[c]);
                REQUIRE(a[c] == plain[c]);
            }
        }
    }
}

TEST_CASE("Applying the options, then the plain evaluation, is the evaluation with options bit for bit",
          "[sh_eval]") {
    std::mt19937 rng(3);
    const ShOrder orders[] = {ShOrder::l2, ShOrder::l1, ShOrder::zh3};
    const ShEvalOptions windows[] = {options(ShOrder::l2), options(ShOrder::l2, ShWindow::sloan, 0.03f),
                                     options(ShOrder::l2, ShWindow::nonnegative)};
    for (int trial = 0; trial < 10; ++trial) {
        float sh[27];
        random_sh(rng, sh);
        for (ShOrder order : orders)
            for (ShEvalOptions o : windows) {
                o.order = order;
                float applied[27];
                std::memcpy(applied, sh, sizeof sh);
                sh_apply_eval_options(applied, o);
                for (const Direction& d : fibonacci_sphere(20)) {
                    float n[3], plain[3], with_options[3];
                    to_float(d, n);
                    sh_eval_irradiance(applied, n, plain);
                    sh_eval_irradiance_with_options(sh, n, o, with_options);
                    for (int c = 0; c < 3; ++c) REQUIRE(plain[c] == with_options[c]);
                }
            }
    }
}

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

TEST_CASE("The Sloan window: strength 0 is the identity, band 0 never changes, bands scale by 1/(1+s(l(l+1))^2)",
          "[sh_eval]") {
    std::mt19937 rng(4);
    float sh[27];
    random_sh(rng, sh);
    float same[27];
    std::memcpy(same, sh, sizeof sh);
    sh_apply_sloan_window(same, 0.0);
    REQUIRE(std::memcmp(same, sh, sizeof sh) == 0);

    for (double s : {0.01, 0.25, 3.0}) {
        float windowed[27];
        std::memcpy(windowed, sh, sizeof sh);
        sh_apply_sloan_window(windowed, s);
        for (int c = 0; c < 3; ++c) {
            REQUIRE(windowed[9 * c] == sh[9 * c]);
            for (int i = 1; i < 4; ++i) REQUIRE(windowed[9 * c + i] == float(sh[9 * c + i] / (1.0 + 4.0 * s)));
            for (int i = 4; i < 9; ++i) REQUIRE(windowed[9 * c + i] == float(sh[9 * c + i] / (1.0 + 36.0 * s)));
        }
    }
    float flat[27];
    std::memcpy(flat, sh, sizeof sh);
    sh_apply_sloan_window(flat, INFINITY);
    for (int c = 0; c < 3; ++c) {
        REQUIRE(flat[9 * c] == sh[9 * c]);
        for (int i = 1; i < 9; ++i) REQUIRE(flat[9 * c + i] == 0.0f);
    }
}

TEST_CASE("The non-negative window of L1 of a directional light is strength 1/4", "[sh_eval]") {
    // L1 irradiance of a delta: E (1/4 + w1 (1/2) cos): non-negative exactly when w1 = 1/(1+4s) <= 1/2.
    float sh[27] = {};
    const float travel[3] = {0.36f, -0.48f, 0.8f}, colour[3] = {1.0f, 0.5f, 2.0f};
    sh_add_directional(sh, travel, colour);
    sh_apply_order(sh, ShOrder::l1);
    const double strength = sh_nonnegative_window_strength(sh);
    REQUIRE(strength == Approx(0.25).epsilon(1e-5));
}

TEST_CASE("The non-negative window leaves no negative irradiance and is the smallest that does", "[sh_eval]") {
    std::mt19937 rng(5);
    const std::vector<Direction> dense = fibonacci_sphere(20000);
    int windowed_cases = 0;
    for (int trial = 0; trial < 20; ++trial) {
        float sh[27];
        random_sh(rng, sh);
        const ShOrder order = trial % 3 == 0 ? ShOrder::l2 : trial % 3 == 1 ? ShOrder::l1 : ShOrder::zh3;
        float ordered[27];
        std::memcpy(ordered, sh, sizeof sh);
        sh_apply_order(ordered, order);
        const double strength = sh_nonnegative_window_strength(ordered);

        float result[27];
        std::memcpy(result, sh, sizeof sh);
        sh_apply_eval_options(result, options(order, ShWindow::nonnegative));
        for (int c = 0; c < 3; ++c) REQUIRE(sampled_min(result + 9 * c, dense) >= 0.0);

        float min_before[3], normal[3];
        sh_min_irradiance(ordered, min_before, normal);
        const bool was_negative = std::min({min_before[0], min_before[1], min_before[2]}) < 0;
        REQUIRE((strength > 0) == was_negative);
        if (!was_negative) continue;
        ++windowed_cases;
        // A slightly weaker window leaves a negative value, at the normal the minimum search reports.
        float weaker[27];
        std::memcpy(weaker, ordered, sizeof ordered);
        sh_apply_sloan_window(weaker, strength * (1.0 - 1e-3));
        float min_weaker[3];
        sh_min_irradiance(weaker, min_weaker, normal);
        const Direction n{normal[0], normal[1], normal[2]};
        double smallest = INFINITY;
        for (int c = 0; c < 3; ++c) smallest = std::min(smallest, irradiance(weaker + 9 * c, n));
        REQUIRE(smallest < 0.0);
    }
    REQUIRE(windowed_cases >= 5);
}

TEST_CASE("Minimum irradiance against brute-force sampling of 100k directions", "[sh_eval]") {
    // The sampled minimum exceeds the true one by at most M h^2 / 2: along any great circle through the
    // minimiser f' = 0 and |f''| <= |b| + 4 |A|, and every direction is within angle h of a sample.
    const std::vector<Direction> dense = fibonacci_sphere(100000);
    const double h = 2.0 * std::sqrt(4.0 * kPi / 100000.0);
    std::mt19937 rng(6);
    for (int trial = 0; trial < 12; ++trial) {
        float sh[27];
        random_sh(rng, sh, trial < 6 ? 0.6f : 2.0f);
        float found[3], normal[3];
        sh_min_irradiance(sh, found, normal);
        REQUIRE(std::fabs(std::sqrt(double(normal[0]) * normal[0] + double(normal[1]) * normal[1] +
                                    double(normal[2]) * normal[2]) - 1.0) < 1e-6);
        for (int c = 0; c < 3; ++c) {
            const float* s = sh + 9 * c;
            const double brute = sampled_min(s, dense);
            const double scale = term_scale(s);
            const double b = (2.0 * kPi / 3.0) * kShY1 * std::sqrt(double(s[1]) * s[1] + double(s[2]) * s[2] + double(s[3]) * s[3]);
            const double a = (kPi / 4.0) * (kShY2 * (std::fabs(s[4]) + std::fabs(s[5]) + std::fabs(s[7])) +
                                            2.0 * kShY22 * std::fabs(s[8]) + 3.0 * kShY20 * std::fabs(s[6]));
            REQUIRE(found[c] <= brute + 1e-6 * scale);
            REQUIRE(found[c] >= brute - 0.5 * (b + 4.0 * a) * h * h - 1e-6 * scale);
            const ShChannelMinimum m = sh_channel_min_irradiance(s);
            REQUIRE(m.lower_bound <= m.value);
            REQUIRE(m.value - m.lower_bound <= 1e-9 * scale);
            REQUIRE(irradiance(s, {m.normal[0], m.normal[1], m.normal[2]}) == Approx(m.value).margin(1e-12 * scale));
        }
        // out_normal is where the smallest channel minimum occurs.
        const int smallest = int(std::min_element(found, found + 3) - found);
        const Direction n{normal[0], normal[1], normal[2]};
        REQUIRE(irradiance(sh + 9 * smallest, n) == Approx(found[smallest]).margin(1e-5 * term_scale(sh + 9 * smallest)));
    }
}

TEST_CASE("Minimum irradiance in the hard case: a ring of minima around an axis", "[sh_eval]") {
    // E = c + p z + q z^2 with q > 0 and -p/2q inside (-1, 1): the minimum c - p^2/4q is attained on a
    // circle, where the smallest eigenvalue (0, twice) has no component of b: the trust-region hard case.
    float s[9] = {};
    s[0] = 1.0f;
    s[2] = 0.3f;
    s[6] = 0.5f;
    const double c = kPi * kShY00 * s[0] - (kPi / 4.0) * kShY20 * s[6];
    const double p = (2.0 * kPi / 3.0) * kShY1 * s[2], q = (kPi / 4.0) * 3.0 * kShY20 * s[6];
    REQUIRE(std::fabs(p / (2.0 * q)) < 1.0);
    const ShChannelMinimum m = sh_channel_min_irradiance(s);
    REQUIRE(m.value == Approx(c - p * p / (4.0 * q)).epsilon(1e-12));
    REQUIRE(m.lower_bound == Approx(c - p * p / (4.0 * q)).epsilon(1e-9));
    REQUIRE(m.normal[2] == Approx(-p / (2.0 * q)).epsilon(1e-9));
}

TEST_CASE("Minimum irradiance of constant and L1-only SH", "[sh_eval]") {
    float s[9] = {};
    s[0] = 2.0f;
    ShChannelMinimum m = sh_channel_min_irradiance(s);
    REQUIRE(m.value == Approx(kPi * kShY00 * 2.0).epsilon(1e-12));
    // L1 only: c - |b| at n = -b/|b|.
    s[1] = 0.3f;
    s[2] = -0.4f;
    s[3] = 1.2f;
    m = sh_channel_min_irradiance(s);
    const double length = std::sqrt(double(s[1]) * s[1] + double(s[2]) * s[2] + double(s[3]) * s[3]);
    const double b = (2.0 * kPi / 3.0) * kShY1 * length;
    REQUIRE(m.value == Approx(kPi * kShY00 * 2.0 - b).epsilon(1e-12));
    REQUIRE(m.normal[0] == Approx(-double(s[3]) / length).epsilon(1e-9));
}
