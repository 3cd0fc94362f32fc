// The store's SH encodings (core/sh_encoding.h) and the blend that decodes them (core/sh_blend.h):
// the 8-bit ranges are the ones a non-negative radiance reaches, every encoding decodes within its
// stated bound (random radiance, deltas, constants), L0 <= 0 is handled as documented, each kernel
// gives the bits of the documented expression (written out in the test) and of the portable kernel and,
// with weight 1 on a probe, exactly that probe's decoded SH,
// and a store reproduces linear fields within the encoding's error.
#include "probe_families.h"
#include "sh_test_support.h"

#include "bake/store_builder.h"
#include "core/half.h"
#include "core/sh.h"
#include "core/sh_blend.h"
#include "core/sh_encoding.h"
#include "core/store.h"
#include "core/store_data.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

using namespace tetprobe;

namespace {

const ShEncoding kEncodings[] = {kShHalf, kShUnorm8, kShHalfL1, kShUnorm8L1};

bool is_l1(ShEncoding e) { return e == kShHalfL1 || e == kShUnorm8L1; }

// The stated bound of coefficient k of a channel whose true L0 is l0 (sh_encoding.h): half rounding
// (relative 2^-11, or 2^-25 absolute below the normal halves) for halves, c0 (step / 2 + max / 1024)
// for 8-bit coefficients.
double bound(ShEncoding e, int k, double value, double l0) {
    const int i = k % 9;
    if (is_l1(e) && i >= 4) return 0;  // not stored: decoded as exactly zero, compared with zero below
    if (!sh_encoding_is_unorm8(e) || i == 0) return std::ldexp(std::fabs(value), -11) + std::ldexp(1.0, -25);
    return l0 * (0.5 * kUnorm8Step[i] + kUnorm8RatioMax[i] / 1024);
}

std::vector<uint8_t> encode(ShEncoding e, const float sh[27]) {
    std::vector<uint8_t> record(sh_record_bytes(e, false));
    encode_sh_record(e, sh, record.data());
    return record;
}

// Checks decode(encode(sh)) against sh for a non-negative radiance; returns the largest error of an
// 8-bit coefficient in units of its half step (to show the bound is not vacuous).
double check_round_trip(ShEncoding e, const float sh[27]) {
    const std::vector<uint8_t> record = encode(e, sh);
    float out[27];
    decode_sh_record(e, record.data(), out);
    double worst_steps = 0;
    for (int k = 0; k < 27; ++k) {
        const int i = k % 9;
        const double l0 = sh[k - i];
        INFO("encoding " << e << " coefficient " << k << ": " << sh[k] << " decoded " << out[k] << ", L0 " << l0);
        if (is_l1(e) && i >= 4) {
            REQUIRE(out[k] == 0.0f);
            continue;
        }
        const double error = std::fabs(double(out[k]) - double(sh[k]));
        REQUIRE(error <= bound(e, k, sh[k], l0));
        if (sh_encoding_is_unorm8(e) && i > 0 && l0 > 0) worst_steps = std::max(worst_steps, error / (l0 * 0.5 * kUnorm8Step[i]));
    }
    return worst_steps;
}

// A random non-negative radiance: an ambient term and a few deltas of random colour, at a random scale.
void random_radiance(std::mt19937& rng, float sh[27]) {
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), colour(0.0f, 1.0f);
    std::uniform_int_distribution<int> deltas(0, 5), exponent(-8, 12);
    std::fill(sh, sh + 27, 0.0f);
    const float scale = std::ldexp(1.0f, exponent(rng));
    const float ambient[3] = {scale * colour(rng), scale * colour(rng), scale * colour(rng)};
    sh_add_ambient(sh, ambient);
    for (int d = deltas(rng); d > 0; --d) {
        float direction[3] = {unit(rng), unit(rng), unit(rng)};
        const float length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
        if (!(length > 0.01f)) continue;
        for (float& x : direction) x /= length;
        const float rgb[3] = {scale * colour(rng), scale * colour(rng), scale * colour(rng)};
        sh_add_directional(sh, direction, rgb);
    }
}

// sh_blend.h's expression of the blend, written out here from the format (store_format.h) rather than
// taken from core: products, then sums from probe 0 to 3, no fused multiply-add (the tests build with
// -ffp-contract=off, like the library).
void reference_blend(ShEncoding e, const uint8_t* const r[4], const float w[4], float out[27]) {
    const int coefficients = is_l1(e) ? 4 : 9;
    auto half_at = [](const uint8_t* record, int index) {
        uint16_t h;
        std::memcpy(&h, record + 2 * index, 2);
        return half_to_float(h);
    };
    std::fill(out, out + 27, 0.0f);
    for (int c = 0; c < 3; ++c) {
        if (!sh_encoding_is_unorm8(e)) {
            for (int i = 0; i < coefficients; ++i) {
                const int at = coefficients * c + i;
                out[9 * c + i] = ((w[0] * half_at(r[0], at) + w[1] * half_at(r[1], at)) + w[2] * half_at(r[2], at)) +
                                 w[3] * half_at(r[3], at);
            }
            continue;
        }
        float a[4];
        for (int k = 0; k < 4; ++k) a[k] = w[k] * half_at(r[k], c);
        out[9 * c] = ((a[0] + a[1]) + a[2]) + a[3];
        for (int i = 1; i < coefficients; ++i) {
            const int at = 6 + c * (coefficients - 1) + (i - 1);
            float d[4];
            for (int k = 0; k < 4; ++k) d[k] = float(int32_t(r[k][at]) - kUnorm8Zero[i]);
            out[9 * c + i] = kUnorm8Step[i] * (((a[0] * d[0] + a[1] * d[1]) + a[2] * d[2]) + a[3] * d[3]);
        }
    }
}

}  // namespace

TEST_CASE("every blend kernel, dispatched and portable, gives the bits of the documented expression", "[sh_encoding][blend]") {
    // Records from a few probes' worth of random bytes (finite halves where the format stores halves),
    // with repeated pointers, zero and negative weights, and weight 1 on one probe.
    std::mt19937 rng(75);
    std::uniform_real_distribution<float> value(-300.0f, 300.0f), unit(-0.25f, 1.0f);
    std::uniform_int_distribution<int> byte(0, 255), pick(0, 5);
    INFO("F16C/AVX2 kernels available: " << half_simd_available());
    for (const ShEncoding e : kEncodings) {
        const size_t bytes = sh_record_bytes(e, false);
        const int halves = sh_encoding_is_unorm8(e) ? 3 : int(bytes / 2);
        const ShBlendFunction kernels[2] = {sh_blend_function(e), sh_blend_function_portable(e)};
        for (int trial = 0; trial < 2000; ++trial) {
            std::vector<uint8_t> pool(6 * bytes);
            for (auto& b : pool) b = uint8_t(byte(rng));
            for (int p = 0; p < 6; ++p)
                for (int h = 0; h < halves; ++h) {
                    const uint16_t bits = float_to_half(trial % 7 == 0 ? 0.0f : value(rng));
                    std::memcpy(pool.data() + p * bytes + 2 * h, &bits, 2);
                }
            const uint8_t* r[4];
            for (auto& x : r) x = pool.data() + pick(rng) * bytes;
            float w[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
            if (trial % 3 == 0) w[trial % 4] = 0.0f;
            if (trial % 11 == 0) w[0] = w[1] = w[2] = w[3] = 0.0f, w[trial % 4] = 1.0f;
            float expected[27];
            reference_blend(e, r, w, expected);
            for (const ShBlendFunction f : kernels) {
                float out[27];
                std::memset(out, 0xA5, sizeof out);  // every coefficient must be written
                f(r, w, out);
                INFO("encoding " << e << " trial " << trial);
                REQUIRE(std::memcmp(out, expected, sizeof out) == 0);
            }
        }
    }
}

TEST_CASE("the 8-bit ranges are where Y_i / Y_00 goes over the sphere, with ratio 0 exact", "[sh_encoding]") {
    double lowest[9], highest[9];
    for (int i = 0; i < 9; ++i) lowest[i] = INFINITY, highest[i] = -INFINITY;
    for (const auto& d : sh_test::fibonacci_sphere(400000)) {
        double y[9];
        sh_basis(d.x, d.y, d.z, y);
        for (int i = 1; i < 9; ++i) lowest[i] = std::min(lowest[i], y[i] / y[0]), highest[i] = std::max(highest[i], y[i] / y[0]);
    }
    for (const auto& axis : {sh_test::unit(0, 0, 1), sh_test::unit(1, 1, 0), sh_test::unit(1, 0, 1), sh_test::unit(0, 1, 1),
                             sh_test::unit(1, 0, 0), sh_test::unit(1, -1, 0), sh_test::unit(0, 1, -1), sh_test::unit(1, 0, -1),
                             sh_test::unit(0, 1, 0)}) {
        for (double sign : {1.0, -1.0}) {  // the extremes lie on these directions
            double y[9];
            sh_basis(sign * axis.x, sign * axis.y, sign * axis.z, y);
            for (int i = 1; i < 9; ++i) lowest[i] = std::min(lowest[i], y[i] / y[0]), highest[i] = std::max(highest[i], y[i] / y[0]);
        }
    }
    for (int i = 1; i < 9; ++i) {
        INFO("coefficient " << i << ": sampled [" << lowest[i] << ", " << highest[i] << "]");
        const int first = kUnorm8Zero[i] == 128 ? 1 : 0;  // the symmetric ranges leave code 0 one step beyond
        const double low = double(kUnorm8Step[i]) * (first - kUnorm8Zero[i]);
        const double high = double(kUnorm8Step[i]) * (255 - kUnorm8Zero[i]);
        CHECK(std::fabs(low - lowest[i]) <= 1e-6 * kUnorm8RatioMax[i]);
        CHECK(std::fabs(high - highest[i]) <= 1e-6 * kUnorm8RatioMax[i]);
        CHECK(kUnorm8RatioMax[i] == Approx(std::max(-lowest[i], highest[i])).epsilon(1e-9));
    }
}

TEST_CASE("every encoding decodes a non-negative radiance within its stated bound", "[sh_encoding]") {
    std::mt19937 rng(71);
    double worst_steps = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        float sh[27];
        random_radiance(rng, sh);
        for (const ShEncoding e : kEncodings) worst_steps = std::max(worst_steps, check_round_trip(e, sh));
    }
    // The 8-bit coefficients are rounded to their codes: errors of nearly half a step do occur.
    CHECK(worst_steps > 0.9);
    CHECK(worst_steps <= 1.0 + 1e-3);
}

TEST_CASE("extreme radiance: deltas reach the ends of the ranges, constants decode to exact zeros", "[sh_encoding]") {
    const auto directions = sh_test::fibonacci_sphere(500);
    for (const auto& d : directions) {
        float sh[27] = {0};
        const float direction[3] = {float(d.x), float(d.y), float(d.z)}, white[3] = {1.0f, 0.5f, 2.0f};
        sh_add_directional(sh, direction, white);
        for (const ShEncoding e : kEncodings) check_round_trip(e, sh);
    }
    for (const auto& axis : {sh_test::unit(1, 0, 0), sh_test::unit(0, -1, 0), sh_test::unit(0, 0, 1), sh_test::unit(1, 1, 0)}) {
        float sh[27] = {0};
        const float direction[3] = {float(axis.x), float(axis.y), float(axis.z)}, rgb[3] = {3.0f, 3.0f, 3.0f};
        sh_add_directional(sh, direction, rgb);
        for (const ShEncoding e : kEncodings) check_round_trip(e, sh);
    }
    // Ambient light: every coefficient but L0 is exactly zero after the round trip (ratio 0 is a code).
    for (const float level : {1e-3f, 1.0f, 700.0f}) {
        float sh[27] = {0};
        const float rgb[3] = {level, 2 * level, 0.5f * level};
        sh_add_ambient(sh, rgb);
        for (const ShEncoding e : kEncodings) {
            float out[27];
            decode_sh_record(e, encode(e, sh).data(), out);
            for (int k = 0; k < 27; ++k) {
                INFO("encoding " << e << " coefficient " << k);
                if (k % 9 == 0)
                    CHECK(out[k] == half_to_float(float_to_half(sh[k])));
                else
                    CHECK(out[k] == 0.0f);
            }
        }
    }
    // No light at all decodes to exact zeros.
    float zero[27] = {0}, out[27];
    for (const ShEncoding e : kEncodings) {
        decode_sh_record(e, encode(e, zero).data(), out);
        for (float x : out) CHECK(x == 0.0f);
    }
}

TEST_CASE("a channel whose L0 is zero decodes to zero; a negative L0 keeps its ratios inside the range", "[sh_encoding]") {
    std::mt19937 rng(72);
    std::uniform_real_distribution<float> any(-3.0f, 3.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        float sh[27];
        for (float& x : sh) x = any(rng);
        sh[0] = 0.0f;                 // red: L0 zero
        sh[9] = -std::fabs(sh[9]);    // green: L0 negative
        if (trial % 3 == 0) sh[18] = 1e-9f;  // blue: an L0 that rounds to a zero half
        for (const ShEncoding e : {kShUnorm8, kShUnorm8L1}) {
            float out[27];
            decode_sh_record(e, encode(e, sh).data(), out);
            for (float x : out) REQUIRE(std::isfinite(x));
            for (int i = 1; i < 9; ++i) REQUIRE(out[i] == 0.0f);
            const float l0 = out[9];
            REQUIRE(l0 == half_to_float(float_to_half(sh[9])));
            for (int i = 1; i < int(sh_encoding_coefficients(e)); ++i) {
                // The ratio the code stands for lies within the codes' range, whatever was given.
                const double ratio = double(out[9 + i]) / double(l0);
                REQUIRE(ratio >= double(kUnorm8Step[i]) * (0 - kUnorm8Zero[i]) * (1 + 1e-6));
                REQUIRE(ratio <= double(kUnorm8Step[i]) * (255 - kUnorm8Zero[i]) * (1 + 1e-6));
            }
            if (trial % 3 == 0)
                for (int i = 0; i < 9; ++i) REQUIRE(out[18 + i] == 0.0f);
        }
    }
}

TEST_CASE("each blend kernel gives the portable kernel's bits and reads one record per probe", "[sh_encoding]") {
    std::mt19937 rng(73);
    std::uniform_real_distribution<float> value(-40.0f, 40.0f), unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> byte(0, 255);
    INFO("F16C/AVX2 kernels available: " << half_simd_available());
    for (const ShEncoding e : kEncodings) {
        const ShBlendFunction dispatched = sh_blend_function(e), portable = sh_blend_function_portable(e);
        const size_t bytes = sh_record_bytes(e, false);
        for (int trial = 0; trial < 3000; ++trial) {
            // Each record at the very end of its own allocation, so that ASan sees any over-read.
            std::vector<std::vector<uint8_t>> records(4, std::vector<uint8_t>(bytes));
            for (auto& r : records) {
                if (sh_encoding_is_unorm8(e)) {
                    for (auto& b : r) b = uint8_t(byte(rng));
                    for (int c = 0; c < 3; ++c) {
                        const uint16_t h = float_to_half(value(rng));
                        std::memcpy(r.data() + 2 * c, &h, 2);
                    }
                } else {
                    for (size_t i = 0; i < bytes / 2; ++i) {
                        const uint16_t h = float_to_half(value(rng));
                        std::memcpy(r.data() + 2 * i, &h, 2);
                    }
                }
            }
            float w[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
            if (trial % 5 == 0) w[trial % 4] = 0.0f;
            const float sum = w[0] + w[1] + w[2] + w[3];
            for (float& x : w) x /= sum;
            const uint8_t* r[4] = {records[0].data(), records[1].data(), records[2].data(), records[trial % 4].data()};
            float fast[27], slow[27];
            dispatched(r, w, fast);
            portable(r, w, slow);
            REQUIRE(std::memcmp(fast, slow, sizeof fast) == 0);
            // The blend is the weighted sum of the decoded records, to float rounding.
            for (int i = 0; i < 27; ++i) {
                double exact = 0, magnitude = 0;
                for (int k = 0; k < 4; ++k) {
                    float decoded[27];
                    decode_sh_record(e, r[k], decoded);
                    exact += double(w[k]) * decoded[i];
                    magnitude += std::fabs(double(w[k]) * decoded[i]);
                }
                REQUIRE(std::fabs(slow[i] - exact) <= 1e-6 * magnitude);
            }
            // Weight 1 on one record (0 on the others, in any slot): exactly its decoded SH.
            const int slot = trial % 4;
            float one[4] = {0, 0, 0, 0}, decoded[27];
            one[slot] = 1.0f;
            decode_sh_record(e, r[slot], decoded);
            for (const ShBlendFunction f : {dispatched, portable}) {
                f(r, one, fast);
                for (int i = 0; i < 27; ++i) REQUIRE(fast[i] == decoded[i]);
            }
        }
    }
}

TEST_CASE("a store reproduces a linear field within its encoding's error, and its probes' decoded SH exactly", "[sh_encoding]") {
    // Every coefficient linear in position: L0 = 2 + a . x (positive over the set), coefficient i = L0 * rho_i
    // with rho_i inside its range: at each probe a non-negative radiance's ratios.
    const families::ProbeSet set = families::random_cloud(400, 74, 1.0);
    const size_t n = set.count();
    auto field = [](const double p[3], int k) {
        const int c = k / 9, i = k % 9;
        const double l0 = 2.0 + 0.4 * p[0] - 0.3 * p[1] + 0.2 * (c + 1) * p[2];
        return i == 0 ? l0 : l0 * 0.5 * kUnorm8RatioMax[i] * std::sin(1.0 + i + 2.0 * c);
    };
    std::vector<float> sh(27 * n);
    for (size_t j = 0; j < n; ++j) {
        const double p[3] = {set.positions[3 * j], set.positions[3 * j + 1], set.positions[3 * j + 2]};
        for (int k = 0; k < 27; ++k) sh[27 * j + k] = float(field(p, k));
    }
    std::mt19937 rng(75);
    std::uniform_real_distribution<double> u(0.1, 0.9);
    for (const bool quantize : {false, true}) {
        for (const ShEncoding e : kEncodings) {
            BuildSettings settings;
            settings.sh_encoding = e;
            settings.quantize_positions = quantize;
            const StoreData data = build_store_data(set.positions.data(), 12, sh.data(), 108, n, settings);
            const std::vector<uint8_t> blob = write_store_blob(data);
            const std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
            INFO("encoding " << e << (quantize ? ", quantised positions" : ""));
            size_t inside = 0;
            for (int q = 0; q < 2000; ++q) {
                const float world[3] = {float(u(rng)), float(u(rng)), float(u(rng))};
                const Location loc = store->locate(world, -1);
                if (loc.status != Status::ok || loc.kind != CellKind::inner) continue;
                ++inside;
                float out[27];
                REQUIRE(store->interpolate(world, nullptr, out) == Status::ok);
                // Each probe holds the field at its input position, within its encoding's bound; the
                // weights reproduce the field linearly from the stored positions (to float rounding of
                // the weights), which quantisation moved from the inputs.
                const double p[3] = {world[0], world[1], world[2]};
                for (int k = 0; k < 27; ++k) {
                    const bool dropped = is_l1(e) && k % 9 >= 4;
                    const double expected = dropped ? 0.0 : field(p, k);
                    double encoding_error = 0, moved = 0, magnitude = std::fabs(expected);
                    for (int slot = 0; slot < 4; ++slot) {
                        const uint32_t stored = loc.probes[slot], input = store->probe_source(stored);
                        const double given[3] = {set.positions[3 * input], set.positions[3 * input + 1],
                                                 set.positions[3 * input + 2]};
                        double kept[3];
                        for (int a = 0; a < 3; ++a) kept[a] = store->header().origin[a] + store->probe_position(stored)[a];
                        encoding_error = std::max(encoding_error, bound(e, k, field(given, k), field(given, k - k % 9)));
                        if (!dropped) moved += loc.weights[slot] * std::fabs(field(given, k) - field(kept, k));
                        magnitude = std::max(magnitude, std::fabs(field(given, k)));
                    }
                    INFO("coefficient " << k);
                    REQUIRE(std::fabs(out[k] - expected) <= encoding_error + moved + 1e-6 * magnitude);
                }
            }
            CHECK(inside > 500);
            // At every stored probe: its decoded SH exactly, through the query.
            for (uint32_t j = 0; j < store->header().probe_count; ++j) {
                const float* at = store->probe_position(j);
                float world[3];
                bool exact = true;
                for (int a = 0; a < 3; ++a) {
                    world[a] = float(store->header().origin[a] + at[a]);
                    exact &= float(double(world[a]) - store->header().origin[a]) == at[a];
                }
                if (!exact) continue;
                float out[27], decoded[27];
                REQUIRE(store->interpolate(world, nullptr, out) == Status::ok);
                store->probe_sh(j, decoded);
                for (int k = 0; k < 27; ++k) REQUIRE(out[k] == decoded[k]);
            }
        }
    }
}
