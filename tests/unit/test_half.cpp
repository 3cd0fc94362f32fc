// Half floats: exact round trips, correct rounding, and the dispatched paths against the scalar ones.
#include "core/half.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

using namespace tetprobe;

namespace {

bool is_nan_half(uint16_t h) { return (h & 0x7C00u) == 0x7C00u && (h & 0x3FFu) != 0; }

uint32_t bits_of(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

}  // namespace

TEST_CASE("every half survives half -> float -> half", "[half]") {
    for (uint32_t h = 0; h < 65536; ++h) {
        const float f = half_to_float(uint16_t(h));
        const uint16_t back = float_to_half(f);
        if (is_nan_half(uint16_t(h))) {
            REQUIRE(std::isnan(f));
            REQUIRE(is_nan_half(back));
            REQUIRE((back & 0x8000u) == (h & 0x8000u));
        } else {
            REQUIRE(back == h);
        }
    }
}

TEST_CASE("half_to_float gives the exact values of the format", "[half]") {
    CHECK(half_to_float(0x3C00) == 1.0f);
    CHECK(half_to_float(0xC000) == -2.0f);
    CHECK(half_to_float(0x7BFF) == 65504.0f);
    CHECK(half_to_float(0x0400) == std::ldexp(1.0f, -14));  // smallest normal
    CHECK(half_to_float(0x0001) == std::ldexp(1.0f, -24));  // smallest subnormal
    CHECK(half_to_float(0x03FF) == std::ldexp(1023.0f, -24));
    CHECK(std::isinf(half_to_float(0x7C00)));
    CHECK(half_to_float(0xFC00) < 0);
    CHECK(bits_of(half_to_float(0x8000)) == 0x80000000u);  // negative zero
    // Every finite half, read in order, increases strictly (positives) — no gaps or repeats.
    for (uint32_t h = 1; h < 0x7C00; ++h) REQUIRE(half_to_float(uint16_t(h)) > half_to_float(uint16_t(h - 1)));
}

TEST_CASE("float_to_half rounds to nearest, ties to even, with subnormals and overflow", "[half]") {
    CHECK(float_to_half(std::ldexp(1.0f, -24)) == 0x0001);
    CHECK(float_to_half(std::ldexp(1.0f, -25)) == 0x0000);          // tie between 0 and 1 ulp: even (0)
    CHECK(float_to_half(std::ldexp(3.0f, -25)) == 0x0002);          // tie between 1 and 2 ulp: even (2)
    CHECK(float_to_half(std::ldexp(3.0f, -26)) == 0x0001);          // 0.75 ulp
    CHECK(float_to_half(std::ldexp(1.0f, -26)) == 0x0000);          // 0.25 ulp
    CHECK(float_to_half(std::ldexp(1023.5f, -24)) == 0x0400);       // rounds up into the normals
    CHECK(float_to_half(1.0f + std::ldexp(1.0f, -11)) == 0x3C00);   // tie: even mantissa kept
    CHECK(float_to_half(1.0f + std::ldexp(3.0f, -11)) == 0x3C02);   // tie: rounds to even above
    CHECK(float_to_half(65504.0f) == 0x7BFF);
    CHECK(float_to_half(65519.0f) == 0x7BFF);
    CHECK(float_to_half(65520.0f) == 0x7C00);                       // tie at the top rounds to infinity
    CHECK(float_to_half(1e30f) == 0x7C00);
    CHECK(float_to_half(-1e30f) == 0xFC00);
    CHECK(float_to_half(std::numeric_limits<float>::denorm_min()) == 0x0000);
    CHECK(float_to_half(-0.0f) == 0x8000);
    CHECK(is_nan_half(float_to_half(std::numeric_limits<float>::quiet_NaN())));
}

TEST_CASE("float_to_half picks the nearest half for random floats", "[half]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> exponent(-26.0f, 16.0f);
    std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
    for (int i = 0; i < 200000; ++i) {
        float f = std::ldexp(mantissa(rng), int(std::floor(exponent(rng))));
        if (i & 1) f = -f;
        if (std::fabs(f) >= 65520.0f) continue;
        const uint16_t h = float_to_half(f);
        const double error = std::fabs(double(half_to_float(h)) - double(f));
        // Neither neighbour of h (same sign) is closer.
        if ((h & 0x7FFFu) < 0x7BFFu) REQUIRE(error <= std::fabs(double(half_to_float(uint16_t(h + 1))) - double(f)));
        if ((h & 0x7FFFu) > 0u) REQUIRE(error <= std::fabs(double(half_to_float(uint16_t(h - 1))) - double(f)));
        // The error bound of the format: half an ulp, relative 2^-11 for normals, 2^-25 absolute below.
        REQUIRE(error <= std::fmax(std::fabs(double(f)) * std::ldexp(1.0, -11), std::ldexp(1.0, -25)));
    }
}

TEST_CASE("halves_to_floats (dispatched) equals the scalar conversion", "[half]") {
    std::vector<uint16_t> all(65536 + 5);
    for (size_t i = 0; i < all.size(); ++i) all[i] = uint16_t(i * 40503u);
    std::vector<float> fast(all.size()), slow(all.size());
    halves_to_floats(all.data(), fast.data(), all.size());
    halves_to_floats_scalar(all.data(), slow.data(), all.size());
    for (size_t i = 0; i < all.size(); ++i) {
        if (std::isnan(slow[i]))
            REQUIRE(std::isnan(fast[i]));
        else
            REQUIRE(bits_of(fast[i]) == bits_of(slow[i]));
    }
    INFO("F16C path available: " << half_simd_available());
}

TEST_CASE("blend_sh_halves (dispatched) gives the scalar blend's bits and reads only 27 halves per probe", "[half]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> value(-40.0f, 40.0f);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int trial = 0; trial < 500; ++trial) {
        // Each probe's halves sit at the very end of their own allocation, so ASan sees any over-read.
        std::vector<std::vector<uint16_t>> probes(4, std::vector<uint16_t>(27));
        for (auto& probe : probes)
            for (auto& h : probe) h = float_to_half(value(rng));
        float w[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
        const float sum = w[0] + w[1] + w[2] + w[3];
        for (float& x : w) x /= sum;
        const uint16_t* sh[4] = {probes[0].data(), probes[1].data(), probes[2].data(), probes[trial % 4].data()};
        float fast[27], slow[27];
        blend_sh_halves(sh, w, fast);
        blend_sh_halves_scalar(sh, w, slow);
        for (int i = 0; i < 27; ++i) {
            double exact = 0;
            for (int k = 0; k < 4; ++k) exact += double(w[k]) * double(half_to_float(sh[k][i]));
            REQUIRE(bits_of(fast[i]) == bits_of(slow[i]));
            REQUIRE(std::fabs(slow[i] - exact) <= 1e-5 * 40);
        }
    }
}
