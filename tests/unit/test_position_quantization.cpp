// Quantised positions (core/position_quantization.h): decoding is monotone, exact at the box's ends
// and inside it; encoding picks the nearest code (checked against every code) and a decoded value
// encodes back to itself; a position moves by at most half the largest gap.
#include "core/position_quantization.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

using namespace tetprobe;

namespace {

// Boxes of probe sets' local coordinates (centred on the bounds' centre, so |lo| ~ |hi|), a flat axis,
// a lopsided one, one far from zero and a tiny one.
const std::pair<float, float> kBoxes[] = {{-1.0f, 1.0f}, {-37.25f, 41.5f}, {0.0f, 0.0f},  {-3e-4f, 2e-4f},
                                          {-1e5f, 1e5f}, {1000.0f, 1000.5f}, {-7.0f, 7.0f}};

}  // namespace

TEST_CASE("decoding is monotone, inside the box, and exact at its ends", "[position_quantization]") {
    for (const auto& box : kBoxes) {
        const float lo = box.first, hi = box.second;
        INFO("box [" << lo << ", " << hi << "]");
        REQUIRE(decode_position(0, lo, hi) == lo);
        REQUIRE(decode_position(uint16_t(kPositionCodeMax), lo, hi) == hi);
        float previous = lo;
        for (uint32_t q = 0; q <= kPositionCodeMax; ++q) {
            const float p = decode_position(uint16_t(q), lo, hi);
            REQUIRE(p >= previous);
            REQUIRE(p <= hi);
            previous = p;
        }
        const double gap = position_max_gap(lo, hi);
        const double step = (double(hi) - double(lo)) / kPositionCodeMax;
        REQUIRE(gap >= step);
        REQUIRE(gap <= step + std::ldexp(std::fmax(std::fabs(lo), std::fabs(hi)), -23));  // within a float rounding
    }
}

TEST_CASE("encoding picks the nearest code, and a decoded value encodes back to itself", "[position_quantization]") {
    std::mt19937 rng(61);
    for (const auto& box : kBoxes) {
        const float lo = box.first, hi = box.second;
        INFO("box [" << lo << ", " << hi << "]");
        std::vector<float> decoded(kPositionCodeMax + 1);
        for (uint32_t q = 0; q <= kPositionCodeMax; ++q) decoded[q] = decode_position(uint16_t(q), lo, hi);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (int trial = 0; trial < 300; ++trial) {
            const float p = float(double(lo) + u(rng) * (double(hi) - double(lo)));
            const uint16_t q = encode_position(p, lo, hi);
            double best = INFINITY;
            for (float d : decoded) best = std::fmin(best, std::fabs(double(d) - double(p)));
            REQUIRE(std::fabs(double(decoded[q]) - double(p)) == best);
            REQUIRE(std::fabs(double(decoded[q]) - double(p)) <= 0.5 * position_max_gap(lo, hi));
        }
        for (uint32_t q = 0; q <= kPositionCodeMax; q += 7)
            REQUIRE(decode_position(encode_position(decoded[q], lo, hi), lo, hi) == decoded[q]);
        // Positions beyond the box (never given by the builder) clamp to its ends.
        REQUIRE(encode_position(lo - 1.0f, lo, hi) == 0);
        REQUIRE(decode_position(encode_position(hi + 1.0f, lo, hi), lo, hi) == hi);
    }
}
