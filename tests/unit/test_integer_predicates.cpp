// The fixed-width integer predicates (core/integer_predicates.h): wherever they answer, their signs
// are the exact ones (orientation.h's expansions, Shewchuk's predicates as libtet ships them), over
// both integer tiers (differences below 2^20 and below 2^40), lattices and their exact zeros
// included; inputs spanning more bits are declined, never answered wrongly.
#include "bake/tetgen_guard.h"
#include "core/integer_predicates.h"
#include "core/orientation.h"

#include <tetgen.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <mutex>
#include <random>

using namespace tetprobe;

REAL incircle(REAL* pa, REAL* pb, REAL* pc, REAL* pd);

namespace {

int sign_of(double x) { return (x > 0) - (x < 0); }

void exact_init() {
    static std::once_flag once;
    std::call_once(once, [] {
        std::lock_guard<std::mutex> lock(tetgen_mutex());
        exactinit(0, 0, 0, 1.0, 1.0, 1.0);
    });
}

// Points whose coordinates are random multiples of 2^low below 2^high in magnitude (a span of
// high - low bits), some on a small lattice so that exact zeros are common.
struct Generator {
    std::mt19937 rng;
    explicit Generator(uint32_t seed) : rng(seed) {}
    float coordinate(int low, int span, bool lattice) {
        const int64_t range = lattice ? 3 : (int64_t(1) << std::min(span, 23)) - 1;
        std::uniform_int_distribution<int64_t> u(-range, range);
        return float(std::ldexp(double(u(rng)), low + (lattice ? 0 : std::max(0, span - 23))));
    }
};

}  // namespace

TEST_CASE("integer orientations are the exact ones wherever they answer", "[integer_predicates]") {
    Generator g(3);
    int answered = 0, declined = 0, zeros = 0;
    for (int trial = 0; trial < 30000; ++trial) {
        const int span = 4 + trial % 50, low = int(g.rng() % 200) - 140;
        const bool lattice = trial % 3 == 0;
        float p[4][3];
        for (auto& q : p)
            for (float& x : q) x = g.coordinate(low, span, lattice);
        // Mixed magnitudes: one coordinate far below the others.
        if (trial % 7 == 0) p[3][0] = std::ldexp(p[3][0], -(trial % 60));
        int sign;
        if (orient3d_integer(p[0], p[1], p[2], p[3], &sign)) {
            REQUIRE(sign == orient3d_exact(p[0], p[1], p[2], p[3]));
            zeros += sign == 0;
            ++answered;
        } else {
            ++declined;
        }
        REQUIRE(orient3d_exact_fast(p[0], p[1], p[2], p[3]) == orient3d_exact(p[0], p[1], p[2], p[3]));
        if (orient2d_integer(p[0], p[1], p[2], &sign)) REQUIRE(sign == orient2d_exact(p[0], p[1], p[2]));
        REQUIRE(orient2d_exact_fast(p[0], p[1], p[2]) == orient2d_exact(p[0], p[1], p[2]));
    }
    REQUIRE(answered > 5000);
    REQUIRE(declined > 1000);
    REQUIRE(zeros > 300);
}

TEST_CASE("integer in-sphere and in-circle are the exact ones wherever they answer", "[integer_predicates]") {
    exact_init();
    Generator g(5);
    int answered = 0, zeros = 0;
    for (int trial = 0; trial < 30000; ++trial) {
        // Moderate magnitudes, so that Shewchuk's double predicates neither underflow nor overflow.
        const int span = 4 + trial % 45, low = int(g.rng() % 40) - 30;
        const bool lattice = trial % 2 == 0;
        float p[5][3];
        for (auto& q : p)
            for (float& x : q) x = g.coordinate(low, span, lattice);
        if (trial % 5 == 0) p[4][1] = std::ldexp(p[4][1], -(trial % 30));  // wider spans, up to declined
        double d[5][3];
        for (int i = 0; i < 5; ++i)
            for (int k = 0; k < 3; ++k) d[i][k] = p[i][k];
        int sign;
        if (insphere_integer(p[0], p[1], p[2], p[3], p[4], &sign)) {
            REQUIRE(sign == -sign_of(::insphere(d[0], d[1], d[2], d[3], d[4])));
            zeros += sign == 0;
            ++answered;
        }
        if (incircle_integer(p[0], p[1], p[2], p[3], &sign)) REQUIRE(sign == sign_of(::incircle(d[0], d[1], d[2], d[3])));
    }
    REQUIRE(answered > 10000);
    REQUIRE(zeros > 300);
}
