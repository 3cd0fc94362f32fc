// Octahedral normals (core/octahedral_normal.h): every code decodes to a finite unit vector; encoding
// picks the code nearest in angle among its neighbours, within the grid's angular resolution; a
// decoded normal encodes back to the same vector; the axes are exact.
#include "core/octahedral_normal.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace tetprobe;

namespace {

double angle(const float a[3], const double b[3]) {
    double dot = 0, aa = 0, bb = 0;
    for (int k = 0; k < 3; ++k) dot += a[k] * b[k], aa += double(a[k]) * a[k], bb += b[k] * b[k];
    return std::acos(std::fmax(-1.0, std::fmin(1.0, dot / std::sqrt(aa * bb))));
}

}  // namespace

TEST_CASE("every octahedral code decodes to a finite unit vector", "[octahedral_normal]") {
    std::mt19937 rng(62);
    std::uniform_int_distribution<int> code(-32768, 32767);
    for (int trial = 0; trial < 200000; ++trial) {
        const int16_t c[2] = {int16_t(code(rng)), int16_t(trial % 5 == 0 ? 32767 : code(rng))};
        float n[3];
        decode_normal(c, n);
        const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
        REQUIRE(std::isfinite(length));
        REQUIRE(std::fabs(length - 1.0) <= 2e-7);
    }
}

TEST_CASE("encoding is the nearest code around the direction, within the grid's resolution, and stable", "[octahedral_normal]") {
    std::mt19937 rng(63);
    std::normal_distribution<double> g(0.0, 1.0);
    double worst = 0;
    for (int trial = 0; trial < 50000; ++trial) {
        double n[3] = {g(rng), g(rng), g(rng)};
        if (trial % 10 == 0) n[trial / 10 % 3] = 0;  // on the octahedron's folds
        if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
        int16_t c[2];
        encode_normal(n, c);
        float d[3];
        decode_normal(c, d);
        const double chosen = angle(d, n);
        worst = std::fmax(worst, chosen);
        // No code within two steps is nearer.
        for (int du = -2; du <= 2; ++du)
            for (int dv = -2; dv <= 2; ++dv) {
                const long u = long(c[0]) + du, v = long(c[1]) + dv;
                if (u < -32767 || u > 32767 || v < -32767 || v > 32767) continue;
                const int16_t other[2] = {int16_t(u), int16_t(v)};
                float o[3];
                decode_normal(other, o);
                REQUIRE(angle(o, n) >= chosen - 1e-12);
            }
        // The stored vector encodes back to itself.
        const double stored[3] = {d[0], d[1], d[2]};
        float again[3];
        quantize_normal(stored, again);
        for (int k = 0; k < 3; ++k) REQUIRE(again[k] == d[k]);
    }
    INFO("largest angle " << worst);
    CHECK(worst < 6e-5);  // about a step (2 / 32767 across the square) at the octahedron's steepest
    CHECK(worst > 1e-5);
    for (const double axis : {1.0, -1.0})
        for (int k = 0; k < 3; ++k) {
            double n[3] = {0, 0, 0};
            n[k] = axis;
            float d[3];
            quantize_normal(n, d);
            for (int j = 0; j < 3; ++j) REQUIRE(d[j] == float(n[j]));
        }
}
