// SH helpers against a slow numerical quadrature over the sphere (the reference) and the contract
// written in capi/tetprobe.h.
#include "core/sh.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>

using namespace tetprobe;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Midpoint rule in z = cos(theta) and in phi: exact in phi for the low-degree trigonometric terms,
// O(h^2) in z; plenty for integrands of degree <= 4.
double integrate_sphere(const std::function<double(double, double, double)>& f, int nz = 600, int nphi = 24) {
    double sum = 0;
    for (int i = 0; i < nz; ++i) {
        const double z = -1.0 + (i + 0.5) * 2.0 / nz;
        const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
        for (int j = 0; j < nphi; ++j) {
            const double phi = (j + 0.5) * 2.0 * kPi / nphi;
            sum += f(r * std::cos(phi), r * std::sin(phi), z);
        }
    }
    return sum * (2.0 / nz) * (2.0 * kPi / nphi);
}

// Radiance inside the span of bands 0..2, per channel.
double test_radiance(int channel, double x, double y, double z) {
    const double s = 1.0 + 0.5 * channel;
    return s * (0.7 + 0.2 * x - 0.5 * y + 0.1 * z + 0.3 * x * y - 0.2 * z * z + 0.15 * (x * x - y * y) + 0.05 * y * z);
}

void project(const std::function<double(int, double, double, double)>& radiance, float sh[27]) {
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 9; ++i)
            sh[9 * c + i] = float(integrate_sphere([&](double x, double y, double z) {
                double basis[9];
                sh_basis(x, y, z, basis);
                return radiance(c, x, y, z) * basis[i];
            }));
}

void random_direction(std::mt19937& rng, float d[3]) {
    std::normal_distribution<float> g;
    float len;
    do {
        d[0] = g(rng), d[1] = g(rng), d[2] = g(rng);
        len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (len < 1e-3f);
    for (int k = 0; k < 3; ++k) d[k] /= len;
}

}  // namespace

TEST_CASE("sh_basis follows the contract's order and constants", "[sh]") {
    const double x = 0.48, y = -0.6, z = std::sqrt(1.0 - 0.48 * 0.48 - 0.36);
    double b[9];
    sh_basis(x, y, z, b);
    CHECK(b[0] == Approx(0.282095).margin(5e-7));
    CHECK(b[1] == Approx(0.488603 * y).margin(5e-7));
    CHECK(b[2] == Approx(0.488603 * z).margin(5e-7));
    CHECK(b[3] == Approx(0.488603 * x).margin(5e-7));
    CHECK(b[4] == Approx(1.092548 * x * y).margin(5e-7));
    CHECK(b[5] == Approx(1.092548 * y * z).margin(5e-7));
    CHECK(b[6] == Approx(0.315392 * (3 * z * z - 1)).margin(5e-7));
    CHECK(b[7] == Approx(1.092548 * x * z).margin(5e-7));
    CHECK(b[8] == Approx(0.546274 * (x * x - y * y)).margin(5e-7));
    float bf[9];
    sh_basis(float(x), float(y), float(z), bf);
    for (int i = 0; i < 9; ++i) CHECK(bf[i] == Approx(b[i]).margin(1e-6));
    CHECK(sh_cosine_lobe_band(0) == Approx(kPi));
    CHECK(sh_cosine_lobe_band(1) == Approx(2 * kPi / 3));
    CHECK(sh_cosine_lobe_band(2) == Approx(kPi / 4));
}

TEST_CASE("the basis is orthonormal under quadrature", "[sh]") {
    for (int i = 0; i < 9; ++i) {
        for (int j = 0; j < 9; ++j) {
            const double integral = integrate_sphere([&](double x, double y, double z) {
                double b[9];
                sh_basis(x, y, z, b);
                return b[i] * b[j];
            });
            INFO("i=" << i << " j=" << j);
            REQUIRE(integral == Approx(i == j ? 1.0 : 0.0).margin(2e-5));
        }
    }
}

TEST_CASE("projecting band-limited radiance and evaluating it reproduces the radiance", "[sh]") {
    float sh[27];
    project(test_radiance, sh);
    std::mt19937 rng(3);
    for (int n = 0; n < 200; ++n) {
        float d[3], rgb[3];
        random_direction(rng, d);
        sh_eval_radiance(sh, d, rgb);
        for (int c = 0; c < 3; ++c) REQUIRE(rgb[c] == Approx(test_radiance(c, d[0], d[1], d[2])).margin(1e-4));
    }
}

TEST_CASE("irradiance equals the quadrature of radiance times the clamped cosine", "[sh]") {
    float sh[27];
    project(test_radiance, sh);
    std::mt19937 rng(5);
    for (int n = 0; n < 6; ++n) {
        float normal[3], rgb[3];
        random_direction(rng, normal);
        sh_eval_irradiance(sh, normal, rgb);
        for (int c = 0; c < 3; ++c) {
            const double reference = integrate_sphere([&](double x, double y, double z) {
                const double cosine = x * normal[0] + y * normal[1] + z * normal[2];
                return test_radiance(c, x, y, z) * std::fmax(0.0, cosine);
            }, 300, 300);
            // The clamped cosine's kink limits the midpoint rule to ~1e-4 here.
            REQUIRE(rgb[c] == Approx(reference).margin(2e-3));
        }
    }
}

TEST_CASE("add_ambient gives constant radiance and irradiance pi times it", "[sh]") {
    float sh[27] = {};
    const float rgb[3] = {0.25f, 1.5f, 3.0f};
    sh_add_ambient(sh, rgb);
    for (int c = 0; c < 3; ++c)
        for (int i = 1; i < 9; ++i) REQUIRE(sh[9 * c + i] == 0.0f);
    std::mt19937 rng(9);
    for (int n = 0; n < 100; ++n) {
        float d[3], radiance[3], irradiance[3];
        random_direction(rng, d);
        sh_eval_radiance(sh, d, radiance);
        sh_eval_irradiance(sh, d, irradiance);
        for (int c = 0; c < 3; ++c) {
            REQUIRE(radiance[c] == Approx(rgb[c]).epsilon(1e-6));
            REQUIRE(irradiance[c] == Approx(kPi * rgb[c]).epsilon(1e-6));
        }
    }
}

TEST_CASE("add_directional: irradiance facing the light is rgb within the L2 bound", "[sh]") {
    std::mt19937 rng(13);
    for (int n = 0; n < 50; ++n) {
        float travel[3];
        random_direction(rng, travel);
        const float rgb[3] = {1.0f, 0.5f, 2.0f};
        float sh[27] = {};
        sh_add_directional(sh, travel, rgb);
        const float facing[3] = {-travel[0], -travel[1], -travel[2]};
        float e[3], away[3];
        sh_eval_irradiance(sh, facing, e);
        sh_eval_irradiance(sh, travel, away);
        for (int c = 0; c < 3; ++c) {
            // Band factors times (2l+1)/4pi: 1/4 + 1/2 + 5/16 = 17/16 facing, 1/4 - 1/2 + 5/16 = 1/16 away.
            REQUIRE(e[c] == Approx(rgb[c] * 17.0 / 16.0).epsilon(1e-5));
            REQUIRE(away[c] == Approx(rgb[c] / 16.0).epsilon(1e-4));
            REQUIRE(std::fabs(e[c] - rgb[c]) <= rgb[c] / 16.0 + 1e-5);
        }
        // The projection of a delta is E * Y(w): evaluate radiance-weighted basis integral directly.
        double basis[9];
        sh_basis(double(facing[0]), double(facing[1]), double(facing[2]), basis);
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 9; ++i) REQUIRE(sh[9 * c + i] == Approx(rgb[c] * basis[i]).margin(1e-6));
    }
}
