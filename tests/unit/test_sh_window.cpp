// Sloan's window and the non-negative window: the scaling, analytic strengths, and non-negativity of
// the shipped float evaluation.
#include "core/sh.h"
#include "core/sh_eval_options.h"
#include "core/sh_min_irradiance.h"
#include "core/sh_window.h"
#include "sh_test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace tetprobe;
using namespace tetprobe::sh_test;

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

namespace {

// Whether some channel with positive band 0 fails the window's test: its proven lower bound of the
// minimum does not clear the float evaluation's rounding bound.
bool some_channel_fails(const float sh[27]) {
    for (int c = 0; c < 3; ++c)
        if (sh[9 * c] > 0 && !(sh_channel_min_irradiance(sh + 9 * c).lower_bound >= sh_irradiance_rounding_bound(sh + 9 * c)))
            return true;
    return false;
}

}  // namespace

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
        REQUIRE_FALSE(some_channel_fails(result));

        REQUIRE((strength > 0) == some_channel_fails(ordered));
        float min_before[3], normal[3];
        sh_min_irradiance(ordered, min_before, normal);
        const bool was_negative = std::min({min_before[0], min_before[1], min_before[2]}) < 0;
        if (was_negative) REQUIRE(strength > 0);
        if (strength == 0) continue;
        // The float strength just below fails the test: the search ends on adjacent floats.
        float below[27];
        std::memcpy(below, ordered, sizeof ordered);
        sh_apply_sloan_window(below, std::nextafter(float(strength), 0.0f));
        REQUIRE(some_channel_fails(below));
        if (!was_negative) continue;
        ++windowed_cases;
        // A slightly weaker window leaves a negative value, at the normal the minimum search reports:
        // the rounding margin costs far less than 0.1% of the strength.
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

namespace {

// Float normals around unit m: m rounded, its neighbours one float step away in each component, and
// rings at angles 1e-4, 1e-3 and 1e-2 about m, each rounded to float.
std::vector<std::array<float, 3>> normals_around(const Direction& m) {
    std::vector<std::array<float, 3>> out;
    const float base[3] = {float(m.x), float(m.y), float(m.z)};
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                const int step[3] = {dx, dy, dz};
                std::array<float, 3> n;
                for (int k = 0; k < 3; ++k)
                    n[k] = step[k] == 0 ? base[k] : std::nextafter(base[k], step[k] > 0 ? INFINITY : -INFINITY);
                out.push_back(n);
            }
    // Two unit vectors perpendicular to m.
    const Direction helper = std::fabs(m.x) < 0.9 ? Direction{1, 0, 0} : Direction{0, 1, 0};
    const Direction e1 = unit(m.y * helper.z - m.z * helper.y, m.z * helper.x - m.x * helper.z, m.x * helper.y - m.y * helper.x);
    const Direction e2{m.y * e1.z - m.z * e1.y, m.z * e1.x - m.x * e1.z, m.x * e1.y - m.y * e1.x};
    for (double angle : {1e-4, 1e-3, 1e-2})
        for (int k = 0; k < 12; ++k) {
            const double phi = 2.0 * kPi * k / 12, c = std::cos(angle), s = std::sin(angle);
            const Direction d{c * m.x + s * (std::cos(phi) * e1.x + std::sin(phi) * e2.x),
                              c * m.y + s * (std::cos(phi) * e1.y + std::sin(phi) * e2.y),
                              c * m.z + s * (std::cos(phi) * e1.z + std::sin(phi) * e2.z)};
            out.push_back({float(d.x), float(d.y), float(d.z)});
        }
    return out;
}

}  // namespace

TEST_CASE("The non-negative window keeps the shipped float evaluation >= 0 on 9000 random SH", "[sh_eval]") {
    // 3000 SH for each order. Each is evaluated in float, as tp_sh_eval_irradiance(_ex) does, at the
    // normal tp_sh_min_irradiance reports (through the options path), at float neighbours and rings
    // around every channel's minimiser, and at 300 lattice normals. A bound of the minimum >= 0 in
    // double alone (no rounding margin) fails this: the float evaluation rounds below zero there.
    std::mt19937 rng(11);
    std::vector<std::array<float, 3>> lattice;
    for (const Direction& d : fibonacci_sphere(300)) lattice.push_back({float(d.x), float(d.y), float(d.z)});
    const ShOrder orders[] = {ShOrder::l2, ShOrder::l1, ShOrder::zh3};
    int windowed = 0;
    for (ShOrder order : orders)
        for (int trial = 0; trial < 3000; ++trial) {
            float sh[27];
            random_sh(rng, sh, trial % 2 == 0 ? 0.6f : 2.0f);
            const ShEvalOptions nonnegative = options(order, ShWindow::nonnegative);
            float applied[27];
            std::memcpy(applied, sh, sizeof sh);
            sh_apply_eval_options(applied, nonnegative);
            float original[27];
            std::memcpy(original, sh, sizeof sh);
            sh_apply_order(original, order);
            if (std::memcmp(applied, original, sizeof applied) != 0) ++windowed;

            float reported_min[3], reported_normal[3], rgb[3];
            sh_min_irradiance_with_options(sh, nonnegative, reported_min, reported_normal);
            sh_eval_irradiance_with_options(sh, reported_normal, nonnegative, rgb);
            for (int c = 0; c < 3; ++c) {
                REQUIRE(reported_min[c] >= 0.0f);
                REQUIRE(rgb[c] >= 0.0f);
            }
            std::vector<std::array<float, 3>> normals = lattice;
            for (int c = 0; c < 3; ++c) {
                const ShChannelMinimum m = sh_channel_min_irradiance(applied + 9 * c);
                const auto around = normals_around({m.normal[0], m.normal[1], m.normal[2]});
                normals.insert(normals.end(), around.begin(), around.end());
            }
            for (const auto& n : normals) {
                sh_eval_irradiance(applied, n.data(), rgb);
                for (int c = 0; c < 3; ++c) REQUIRE(rgb[c] >= 0.0f);
            }
        }
    REQUIRE(windowed >= 3000);
}
