// The real-level benchmark's peers (samples/bench): APV's 8-bit SH encoding keeps what non-negative
// radiance can reach, the SIMD trilinear blends agree with their scalar references, the dilated grid is
// exact at its probes and reproduces fields that trilinear interpolation can, dilation fills invalid
// probes from valid neighbours, and the brick grid stays within its budget, refines where a surface is and
// lighting changes, and answers from its finest brick there.
#include "apv_sh_encoding.h"
#include "brick_grid.h"
#include "dilated_grid.h"
#include "trilinear_blend.h"

#include "core/half.h"
#include "core/sh.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

using namespace bench;

namespace {

// The SH of radiance made of a few narrow lobes (each a projected direction with a positive colour) over
// an ambient term: non-negative radiance, as a bake gives.
std::vector<float> lobes_sh(std::mt19937& rng) {
    std::vector<float> sh(27, 0.0f);
    std::uniform_real_distribution<float> u(-1, 1), c(0.05f, 2.0f);
    for (int lobe = 0; lobe < 3; ++lobe) {
        float d[3] = {u(rng), u(rng), u(rng)};
        const float n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        double basis[9];
        tetprobe::sh_basis(double(d[0] / n), double(d[1] / n), double(d[2] / n), basis);
        for (int ch = 0; ch < 3; ++ch) {
            const float colour = c(rng);
            for (int k = 0; k < 9; ++k) sh[9 * ch + k] += colour * float(basis[k]);
        }
    }
    for (int ch = 0; ch < 3; ++ch) sh[9 * ch] += 0.1f;
    return sh;
}

}  // namespace

TEST_CASE("APV's 8-bit encoding: ratios of non-negative radiance lie in the stated ranges and round-trip",
          "[level_peers]") {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 200; ++trial) {
        const std::vector<float> sh = lobes_sh(rng);
        for (int ch = 0; ch < 3; ++ch)
            for (int k = 1; k < 9; ++k) {
                float lo, hi;
                apv_ratio_range(k, &lo, &hi);
                const float ratio = sh[9 * ch + k] / sh[9 * ch];
                REQUIRE(ratio >= lo * 1.0001f);
                REQUIRE(ratio <= hi * 1.0001f);
            }
        uint8_t record[kApvRecordBytes];
        apv_encode(sh.data(), record);
        float back[27];
        apv_decode(record, back);
        for (int ch = 0; ch < 3; ++ch) {
            CHECK(back[9 * ch] == tetprobe::half_to_float(tetprobe::float_to_half(sh[9 * ch])));
            for (int k = 1; k < 9; ++k) {
                float lo, hi;
                apv_ratio_range(k, &lo, &hi);
                // Half a step of 8 bits over the range, times L0 (and L0's own half rounding).
                CHECK(std::fabs(back[9 * ch + k] - sh[9 * ch + k]) <= back[9 * ch] * (hi - lo) / 510.0f * 1.001f + 1e-3f * std::fabs(sh[9 * ch + k]));
            }
        }
    }
    // The extremes of a basis function are reached by a single direction: a delta light along +z puts L10
    // (Y ∝ z) at its largest ratio sqrt(3) and L20 at sqrt(5).
    double basis[9];
    tetprobe::sh_basis(0.0, 0.0, 1.0, basis);
    CHECK(basis[2] / basis[0] == Approx(std::sqrt(3.0)));
    CHECK(basis[6] / basis[0] == Approx(std::sqrt(5.0)));
}

TEST_CASE("the trilinear blends agree with their scalar references", "[level_peers]") {
    std::mt19937 rng(8);
    std::vector<uint8_t> halves(8 * kGridHalves * 2, 0), apv(8 * kApvRecordBytes);
    for (int c = 0; c < 8; ++c) {
        const std::vector<float> sh = lobes_sh(rng);
        for (int k = 0; k < 27; ++k) {
            const uint16_t h = tetprobe::float_to_half(sh[size_t(k)]);
            std::memcpy(&halves[size_t(c) * kGridHalves * 2 + 2 * size_t(k)], &h, 2);
        }
        apv_encode(sh.data(), &apv[size_t(c) * kApvRecordBytes]);
    }
    size_t half_offsets[8], apv_offsets[8];
    for (int c = 0; c < 8; ++c) half_offsets[c] = size_t(c) * kGridHalves * 2, apv_offsets[c] = size_t(c) * kApvRecordBytes;
    std::uniform_real_distribution<float> u(0, 1);
    for (int trial = 0; trial < 100; ++trial) {
        const float frac[3] = {u(rng), u(rng), trial == 0 ? 0.0f : u(rng)};
        float fast[27], slow[27];
        trilinear_halves(halves.data(), half_offsets, frac, fast);
        trilinear_halves_scalar(halves.data(), half_offsets, frac, slow);
        for (int k = 0; k < 27; ++k) REQUIRE(fast[k] == Approx(slow[k]).margin(1e-5));
        trilinear_apv(apv.data(), apv_offsets, frac, fast);
        trilinear_apv_scalar(apv.data(), apv_offsets, frac, slow);
        for (int k = 0; k < 27; ++k) REQUIRE(fast[k] == Approx(slow[k]).margin(1e-5));
    }
    // At a corner the blend is that corner's record.
    const float corner[3] = {1, 0, 1};  // corner 5: +x, +z
    float out[27], decoded[27];
    trilinear_apv(apv.data(), apv_offsets, corner, out);
    apv_decode(&apv[5 * kApvRecordBytes], decoded);
    for (int k = 0; k < 27; ++k) CHECK(out[k] == Approx(decoded[k]).margin(1e-6));
}

TEST_CASE("the dilated grid is exact at its probes, trilinear between, and fills invalid probes from valid ones",
          "[level_peers]") {
    const float lo[3] = {-1, 0, 2}, hi[3] = {3, 1, 5};
    const int dims[3] = {5, 3, 4};
    DilatedGrid grid(lo, hi, dims, GridEncoding::half);
    const std::vector<float> p = grid.positions();
    // SH coefficient k = a linear function of position, in small steps exact in half.
    auto field = [](const float* x, int k) { return 0.25f * float(k) + 0.5f * x[0] - 0.25f * x[1] + 0.125f * x[2]; };
    std::vector<float> sh(27 * grid.probe_count());
    for (size_t i = 0; i < grid.probe_count(); ++i)
        for (int k = 0; k < 27; ++k) sh[27 * i + size_t(k)] = field(&p[3 * i], k);
    grid.set_sh(sh, std::vector<uint8_t>(grid.probe_count(), 1));
    CHECK(grid.dilation_passes() == 0);
    CHECK(grid.bytes() == grid.probe_count() * 54 + DilatedGrid::kHeaderBytes);
    std::mt19937 rng(3);
    for (int trial = 0; trial < 200; ++trial) {
        float q[3], out[27];
        for (int k = 0; k < 3; ++k) q[k] = std::uniform_real_distribution<float>(lo[k], hi[k])(rng);
        grid.interpolate(q, out);
        for (int k = 0; k < 27; ++k) REQUIRE(out[k] == Approx(field(q, k)).margin(2e-3));  // half rounding of the probes
    }
    for (size_t i = 0; i < grid.probe_count(); ++i) {
        float out[27];
        grid.interpolate(&p[3 * i], out);
        for (int k = 0; k < 27; ++k) REQUIRE(out[k] == tetprobe::half_to_float(tetprobe::float_to_half(sh[27 * i + size_t(k)])));
    }
    // Outside the box: clamped onto it.
    const float far[3] = {100, -100, 100}, clamped[3] = {3, 0, 5};
    float a[27], b[27];
    grid.interpolate(far, a);
    grid.interpolate(clamped, b);
    for (int k = 0; k < 27; ++k) CHECK(a[k] == b[k]);

    // Dilation: a corner probe invalid takes the mean of its 7 valid neighbours; a far probe surrounded by
    // invalid ones is filled in a second pass.
    std::vector<uint8_t> valid(60, 1);
    std::vector<float> values(27 * 60);
    for (size_t i = 0; i < 60; ++i)
        for (int k = 0; k < 27; ++k) values[27 * i + size_t(k)] = float(i);
    valid[0] = 0;  // corner (0, 0, 0): neighbours 1, 5, 6, 15, 16, 20, 21
    for (size_t i : {38u, 39u, 43u, 44u, 53u, 54u, 58u, 59u}) valid[i] = 0;  // the far corner block (2 x 2 x 2)
    std::vector<float> dilated = values;
    CHECK(dilate_probes(dims, valid, dilated) == 2);
    CHECK(dilated[0] == Approx((1 + 5 + 6 + 15 + 16 + 20 + 21) / 7.0));
    for (size_t i = 0; i < 60; ++i)
        if (valid[i]) REQUIRE(dilated[27 * i] == values[27 * i]);
    CHECK_THROWS(dilate_probes(dims, std::vector<uint8_t>(60, 0), dilated));
}

TEST_CASE("the brick grid stays within its budget and refines where a surface is and lighting changes",
          "[level_peers]") {
    const float lo[3] = {0, 0, 0}, hi[3] = {32, 8, 32};
    // Lighting: L0 = 1 + a bump around (8, 2, 8); a surface (the plane x = 8) near the bump.
    auto l0 = [](const float* p) {
        const float d2 = (p[0] - 8) * (p[0] - 8) + (p[1] - 2) * (p[1] - 2) + (p[2] - 8) * (p[2] - 8);
        return 1.0f + 4.0f * std::exp(-d2 / 8.0f);
    };
    BrickBuildHooks hooks;
    hooks.mean_irradiance = 3.14159f;
    size_t baked = 0;
    hooks.bake = [&](const std::vector<float>& p) {
        std::vector<float> sh(p.size() / 3 * 27, 0.0f);
        for (size_t i = 0; i < p.size() / 3; ++i)
            for (int ch = 0; ch < 3; ++ch) sh[27 * i + 9 * size_t(ch)] = l0(&p[3 * i]);
        baked += p.size() / 3;
        return sh;
    };
    hooks.valid = [](const std::vector<float>& p) { return std::vector<uint8_t>(p.size() / 3, 1); };
    hooks.near_surface = [](const float point[3], float radius) { return std::fabs(point[0] - 8) <= radius; };
    for (size_t budget : {size_t(40000), size_t(150000), size_t(400000)}) {
        const BrickGrid grid(lo, hi, budget, hooks);
        CHECK(grid.bytes() <= budget);
        CHECK(grid.bytes() == (grid.bricks(0) + grid.bricks(1) + grid.bricks(2)) * 4000 + 2 * grid.indirection_entries() +
                                  BrickGrid::kHeaderBytes);
        CHECK(grid.indirection_entries() == grid.bricks(0) * 16 * 16 * 16);  // at the finest bricks' size
        // Every refined brick's 125 samples are baked; the top level's shared lattice at most 125 a brick.
        CHECK(grid.samples_baked() > (grid.bricks(1) + grid.bricks(2)) * 125);
        CHECK(grid.samples_baked() <= (grid.bricks(0) + grid.bricks(1) + grid.bricks(2)) * 125);
        // Far from the surface and the bump nothing is refined: a constant field there is exact.
        const float quiet[3] = {28, 4, 28};
        float out[27];
        grid.interpolate(quiet, out);
        CHECK(out[0] == Approx(l0(quiet)).epsilon(2e-3));
        if (budget >= 150000) CHECK(grid.bricks(1) > 0);
    }
    // More budget, finer bricks at the bump: the error there falls.
    const BrickGrid small(lo, hi, 40000, hooks), large(lo, hi, 400000, hooks);
    double small_error = 0, large_error = 0;
    std::mt19937 rng(4);
    for (int trial = 0; trial < 300; ++trial) {
        const float q[3] = {std::uniform_real_distribution<float>(6, 10)(rng), std::uniform_real_distribution<float>(0, 4)(rng),
                            std::uniform_real_distribution<float>(6, 10)(rng)};
        float a[27], b[27];
        small.interpolate(q, a);
        large.interpolate(q, b);
        small_error += std::fabs(a[0] - l0(q)), large_error += std::fabs(b[0] - l0(q));
    }
    CHECK(large.bricks(2) > 0);
    CHECK(large_error < 0.5 * small_error);
    CHECK_THROWS(BrickGrid(lo, hi, 5000, hooks));  // not even one top brick and its indirection
}
