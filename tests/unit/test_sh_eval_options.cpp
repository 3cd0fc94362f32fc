// SH evaluation options (the order and window dispatch, which options commute with interpolation) and
// the minimum irradiance, against analytic answers, bit-exact identities and brute-force sampling.
#include "core/sh.h"
#include "core/sh_eval_options.h"
#include "core/sh_min_irradiance.h"
#include "core/sh_window.h"
#include "sh_test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace tetprobe;
using namespace tetprobe::sh_test;

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

namespace {

// The store's blend, in float as blend_sh_halves does it, of four probes' float SH.
void blend_probes(const float probes[4][27], const float weights[4], float out[27]) {
    for (int i = 0; i < 27; ++i) {
        float sum = 0.0f;
        for (int k = 0; k < 4; ++k) sum += weights[k] * probes[k][i];
        out[i] = sum;
    }
}

// Random barycentric weights (non-negative floats).
void random_weights(std::mt19937& rng, float weights[4]) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    float total = 0.0f;
    for (int k = 0; k < 4; ++k) total += weights[k] = u(rng);
    for (int k = 0; k < 4; ++k) weights[k] /= total;
}

}  // namespace

TEST_CASE("L1 and the Sloan window commute with interpolation", "[sh_eval]") {
    // Interpolating rewritten probes against rewriting the interpolated SH. L1 only zeroes band 2:
    // bit for bit. The window scales coefficient i by w (< = 1): both sides are w sum_k a_k c_k with
    // at most 5 roundings of relative size u on each term's path (the window product, the weight
    // product, 3 additions; the other side the same in another order), so they differ by at most
    // 2 gamma_5 < 11u times w sum_k a_k |c_k|.
    std::mt19937 rng(21);
    for (int trial = 0; trial < 200; ++trial) {
        float probes[4][27], weights[4];
        for (auto& probe : probes) random_sh(rng, probe, 2.0f);
        random_weights(rng, weights);
        float interpolated[27];
        blend_probes(probes, weights, interpolated);
        for (const ShEvalOptions& o : {options(ShOrder::l1), options(ShOrder::l2, ShWindow::sloan, 0.04f),
                                       options(ShOrder::l1, ShWindow::sloan, 0.7f)}) {
            float rewritten_probes[4][27], per_probe[27], per_query[27];
            std::memcpy(rewritten_probes, probes, sizeof probes);
            for (auto& probe : rewritten_probes) sh_apply_eval_options(probe, o);
            blend_probes(rewritten_probes, weights, per_probe);
            std::memcpy(per_query, interpolated, sizeof per_query);
            sh_apply_eval_options(per_query, o);
            if (o.window == ShWindow::none) {
                REQUIRE(std::memcmp(per_probe, per_query, sizeof per_query) == 0);
                continue;
            }
            for (int i = 0; i < 27; ++i) {
                const double w = sh_sloan_window(kShBandOfCoefficient[i % 9], o.window_strength);
                double scale = 0;
                for (int k = 0; k < 4; ++k) scale += double(weights[k]) * std::fabs(probes[k][i]);
                REQUIRE(std::fabs(double(per_probe[i]) - per_query[i]) <= 11.0 * std::ldexp(w * scale, -24));
            }
        }
    }
}

TEST_CASE("ZH3 and the non-negative window do not commute with interpolation", "[sh_eval]") {
    // Halfway between a probe lit from +x and one lit from +y. Per probe, ZH3's axes are x and y,
    // where the xy coefficient's basis Y2 x y vanishes; per query the axis is (1, 1, 0) / sqrt 2, where
    // it is Y2 / 2, with z = L0 r (0.08 + 0.6 r), L0 = Y00, r = |L1| / L0 = Y1 / (sqrt 2 Y00) = sqrt(3/2).
    float probes[4][27] = {};
    const float from_x[3] = {-1, 0, 0}, from_y[3] = {0, -1, 0}, white[3] = {1, 1, 1};
    sh_add_directional(probes[0], from_x, white);
    sh_add_directional(probes[1], from_y, white);
    std::memcpy(probes[2], probes[0], sizeof probes[0]);
    std::memcpy(probes[3], probes[1], sizeof probes[1]);
    const float weights[4] = {0.5f, 0.5f, 0.0f, 0.0f};
    float interpolated[27];
    blend_probes(probes, weights, interpolated);

    float zh3_probes[4][27], per_probe[27], per_query[27];
    std::memcpy(zh3_probes, probes, sizeof probes);
    for (auto& probe : zh3_probes) sh_apply_order(probe, ShOrder::zh3);
    blend_probes(zh3_probes, weights, per_probe);
    std::memcpy(per_query, interpolated, sizeof per_query);
    sh_apply_order(per_query, ShOrder::zh3);
    const double r = std::sqrt(1.5), z = kShY00 * r * (0.08 + 0.6 * r);
    for (int c = 0; c < 3; ++c) {
        REQUIRE(per_probe[9 * c + 4] == 0.0f);
        REQUIRE(per_query[9 * c + 4] == Approx(z * std::sqrt(4.0 * kPi / 5.0) * kShY2 / 2.0).epsilon(1e-6));
    }
    // So the irradiance differs at n = (1, 1, 0) / sqrt 2 (bands 0 and 1 agree): per query the zonal
    // term is z (pi/4) Y20(1) = z (pi/4) 2 c20 (c20 = sqrt(5/16pi)); per probe each light's own,
    // z1 = Y1 (0.08 + 0.6 sqrt 3) (r = sqrt 3), at angle 45 degrees: 2 * 0.5 z1 (pi/4) c20 (3/2 - 1).
    const float n[3] = {float(std::sqrt(0.5)), float(std::sqrt(0.5)), 0.0f};
    float e_probe[3], e_query[3];
    sh_eval_irradiance(per_probe, n, e_probe);
    sh_eval_irradiance(per_query, n, e_query);
    const double z1 = kShY1 * (0.08 + 0.6 * std::sqrt(3.0));
    const double difference = (kPi / 4.0) * kShY20 * (2.0 * z - 0.5 * z1);
    REQUIRE(difference > 0.07);
    for (int c = 0; c < 3; ++c) REQUIRE(e_query[c] - e_probe[c] == Approx(difference).margin(1e-6));

    // The non-negative window: an ambient probe needs none, a directional L2 probe needs strength s;
    // their blend needs less than s, so windowing per probe over-smooths the blend's band 1.
    float mixed[4][27] = {};
    const float ambient[3] = {1, 1, 1};
    sh_add_ambient(mixed[0], ambient);
    sh_add_directional(mixed[1], from_x, white);
    std::memcpy(mixed[2], mixed[0], sizeof mixed[0]);
    std::memcpy(mixed[3], mixed[1], sizeof mixed[1]);
    float mixed_blend[27];
    blend_probes(mixed, weights, mixed_blend);
    const double s_directional = sh_nonnegative_window_strength(mixed[1]);
    const double s_blend = sh_nonnegative_window_strength(mixed_blend);
    REQUIRE(sh_nonnegative_window_strength(mixed[0]) == 0.0);
    REQUIRE(s_directional > 0.0);
    REQUIRE(s_blend < 0.5 * s_directional);
    float windowed[4][27], nn_probe[27], nn_query[27];
    std::memcpy(windowed, mixed, sizeof mixed);
    for (auto& probe : windowed) sh_apply_eval_options(probe, options(ShOrder::l2, ShWindow::nonnegative));
    blend_probes(windowed, weights, nn_probe);
    std::memcpy(nn_query, mixed_blend, sizeof nn_query);
    sh_apply_eval_options(nn_query, options(ShOrder::l2, ShWindow::nonnegative));
    REQUIRE(nn_query[3] > 1.2f * nn_probe[3]);  // band 1 along x
}
