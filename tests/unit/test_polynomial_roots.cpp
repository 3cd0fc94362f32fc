// Real roots of cubics, including the degenerate leading coefficients of outer cells.
#include "core/polynomial_roots.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace tetprobe;

namespace {

std::vector<double> roots_of(double a, double b, double c, double d) {
    double r[3];
    const int n = cubic_real_roots(a, b, c, d, r);
    return std::vector<double>(r, r + n);
}

void require_roots(const std::vector<double>& found, std::vector<double> expected, double tolerance) {
    std::sort(expected.begin(), expected.end());
    REQUIRE(found.size() == expected.size());
    for (size_t i = 0; i < found.size(); ++i)
        REQUIRE(std::fabs(found[i] - expected[i]) <= tolerance * std::fmax(1.0, std::fabs(expected[i])));
}

}  // namespace

TEST_CASE("cubic, quadratic, linear and constant cases", "[roots]") {
    require_roots(roots_of(1, -6, 11, -6), {1, 2, 3}, 1e-14);         // (t-1)(t-2)(t-3)
    require_roots(roots_of(2, 0, 0, -16), {2}, 1e-14);                // one real root
    require_roots(roots_of(0, 1, -3, 2), {1, 2}, 1e-14);              // quadratic
    require_roots(roots_of(0, 1, 0, 1), {}, 0);                       // no real root
    require_roots(roots_of(0, 0, 4, -2), {0.5}, 1e-15);               // linear
    require_roots(roots_of(0, 0, 0, 3), {}, 0);                       // constant
    require_roots(roots_of(0, 0, 0, 0), {}, 0);                       // all zero
    require_roots(roots_of(1, -3, 3, -1), {1}, 1e-5);                 // triple root, reported once
    require_roots(roots_of(1, -5, 8, -4), {1, 2}, 1e-7);              // (t-1)(t-2)^2: the double root once
    require_roots(roots_of(1e-300, 1, -3, 2), {1, 2}, 1e-14);         // cubic term vanishes numerically
}

TEST_CASE("a tiny leading coefficient keeps every root, including the huge one", "[roots]") {
    // eps t^3 + t^2 - 3 t + 2: roots near 1 and 2, and one near -1/eps.
    for (double eps : {1e-3, 1e-8, 1e-14}) {
        const std::vector<double> r = roots_of(eps, 1, -3, 2);
        REQUIRE(r.size() == 3);
        REQUIRE(r[0] == Approx(-1.0 / eps).epsilon(1e-2));
        REQUIRE(r[1] == Approx(1.0).epsilon(1e-2));
        REQUIRE(r[2] == Approx(2.0).epsilon(1e-2));
        for (double t : r) {
            const double value = ((eps * t + 1) * t - 3) * t + 2;
            const double scale = ((std::fabs(eps * t) + 1) * std::fabs(t) + 3) * std::fabs(t) + 2;
            REQUIRE(std::fabs(value) <= 1e-12 * scale);
        }
    }
}

TEST_CASE("random cubics: every reported root is a root, and none is missed", "[roots]") {
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-10, 10);
    std::uniform_int_distribution<int> scale(-6, 6);
    for (int trial = 0; trial < 20000; ++trial) {
        // Build from chosen roots so the expected set is known.
        const int real_count = 1 + 2 * (trial % 2);  // 1 or 3 real roots
        const double s = std::pow(10.0, scale(rng));
        std::vector<double> expected;
        double a = s, b, c, d;
        if (real_count == 3) {
            double r[3] = {u(rng), u(rng), u(rng)};
            std::sort(r, r + 3);
            if (r[1] - r[0] < 1e-3 || r[2] - r[1] < 1e-3) continue;
            expected.assign(r, r + 3);
            b = -s * (r[0] + r[1] + r[2]);
            c = s * (r[0] * r[1] + r[1] * r[2] + r[0] * r[2]);
            d = -s * r[0] * r[1] * r[2];
        } else {
            const double r = u(rng), re = u(rng), im = 0.1 + std::fabs(u(rng));
            expected = {r};
            // (t - r)(t^2 - 2 re t + re^2 + im^2)
            const double q = re * re + im * im;
            b = s * (-2 * re - r);
            c = s * (q + 2 * re * r);
            d = -s * r * q;
        }
        require_roots(roots_of(a, b, c, d), expected, 1e-9);
    }
}
