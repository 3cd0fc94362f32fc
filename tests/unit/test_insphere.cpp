// The in-sphere and in-circle predicates (core/insphere.h) and their exact integers
// (core/exact_integer.h): signs against Shewchuk's exact predicates as TetGen ships them, on random
// and nearly cospherical float points; exact zeros on cospherical sets; signs kept under scaling by
// any power of two over the whole float range (denormals to 2^127); the filters never claim a wrong
// sign; and the tie rule: never 0, antisymmetric in the tetrahedron's vertices, the same for every
// even permutation, and in 2D what TetGen's 3D rule gives under an apex of the highest index.
#include "bake/tetgen_guard.h"
#include "core/exact_integer.h"
#include "core/insphere.h"
#include "core/insphere_kernels.h"
#include "core/orientation.h"

#include <tetgen.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <random>
#include <vector>

using namespace tetprobe;

// Shewchuk's 2D predicate as libtet exports it (not declared by tetgen.h).
REAL incircle(REAL* pa, REAL* pb, REAL* pc, REAL* pd);

namespace {

using P3 = std::array<float, 3>;
using P2 = std::array<float, 2>;

int sign_of(double x) { return (x > 0) - (x < 0); }

// Shewchuk's insphere is positive inside for his orientation, minus the store's.
int reference_insphere(const P3& a, const P3& b, const P3& c, const P3& d, const P3& e) {
    static std::once_flag once;
    std::call_once(once, [] {
        std::lock_guard<std::mutex> lock(tetgen_mutex());
        exactinit(0, 0, 0, 1.0, 1.0, 1.0);
    });
    double p[5][3];
    const P3* q[5] = {&a, &b, &c, &d, &e};
    for (int i = 0; i < 5; ++i)
        for (int k = 0; k < 3; ++k) p[i][k] = (*q[i])[size_t(k)];
    return -sign_of(::insphere(p[0], p[1], p[2], p[3], p[4]));
}

int reference_incircle(const P2& a, const P2& b, const P2& c, const P2& d) {
    double p[4][2] = {{a[0], a[1]}, {b[0], b[1]}, {c[0], c[1]}, {d[0], d[1]}};
    return sign_of(::incircle(p[0], p[1], p[2], p[3]));
}

// Points near a sphere: float-rounded points of a sphere of radius r around c, or nudged by an ulp.
P3 near_sphere(std::mt19937& rng, const P3& centre, double radius) {
    std::normal_distribution<double> g;
    double v[3] = {g(rng), g(rng), g(rng)};
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    P3 p;
    for (int k = 0; k < 3; ++k) p[size_t(k)] = float(centre[size_t(k)] + radius * v[k] / n);
    return p;
}

P3 scaled(const P3& p, int exponent) { return {std::ldexp(p[0], exponent), std::ldexp(p[1], exponent), std::ldexp(p[2], exponent)}; }

}  // namespace

TEST_CASE("exact integers add, subtract and multiply as 128-bit integers do", "[insphere]") {
    std::mt19937_64 rng(3);
    for (int trial = 0; trial < 20000; ++trial) {
        // 24-bit magnitudes shifted by up to 36 bits: sums and products fit in 128 bits.
        ExactInteger ea, eb, sum, difference, product;
        exact_scaled(uint32_t(rng() & 0xFFFFFF), int(rng() % 37), (rng() & 1) != 0, ea);
        exact_scaled(uint32_t(rng() & 0xFFFFFF), int(rng() % 37), (rng() & 1) != 0, eb);
        auto value = [](const ExactInteger& e) {
            __int128 v = 0;
            for (int i = e.size - 1; i >= 0; --i) v = (v << 32) | e.limb[i];
            return e.negative ? -v : v;
        };
        const __int128 va = value(ea), vb = value(eb);
        exact_add(ea, eb, sum);
        exact_subtract(ea, eb, difference);
        exact_multiply(ea, eb, product);
        REQUIRE(value(sum) == va + vb);
        REQUIRE(value(difference) == va - vb);
        REQUIRE(value(product) == va * vb);
        REQUIRE(sum.sign() == ((va + vb > 0) - (va + vb < 0)));
        // Aliased operands, as the predicates use them.
        exact_subtract(sum, eb, sum);
        REQUIRE(value(sum) == va);
    }
}

TEST_CASE("insphere and incircle agree with Shewchuk's exact predicates on random and nearly cospherical points", "[insphere]") {
    // Float points of similar magnitude are either exactly cospherical or far enough from it for the
    // filter; the exact evaluation decides the rest: a point a tiny step from a sphere point at the
    // origin (mixed magnitudes), every third case here.
    std::vector<P3> through_origin;
    for (int x = -15; x <= 15; ++x)
        for (int y = -15; y <= 15; ++y)
            for (int z = -15; z <= 15; ++z)
                if (x * x + y * y + z * z == 225) through_origin.push_back({float(x + 15), float(y), float(z)});
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-3, 3);
    std::uniform_int_distribution<int> tiny(-140, -60);
    size_t filtered = 0, exact = 0;
    for (int trial = 0; trial < 40000; ++trial) {
        P3 q[5];
        if (trial % 3 == 2) {
            for (int i = 0; i < 4; ++i) q[i] = through_origin[rng() % through_origin.size()];
            q[4] = {float(std::ldexp(u(rng), tiny(rng))), float(std::ldexp(u(rng), tiny(rng))), float(std::ldexp(u(rng), tiny(rng)))};
        } else if (trial % 3 == 0) {
            for (auto& p : q) p = {float(u(rng)), float(u(rng)), float(u(rng))};
        } else {
            const P3 centre = {float(u(rng)), float(u(rng)), float(u(rng))};
            const double radius = std::exp(u(rng));
            for (auto& p : q) p = near_sphere(rng, centre, radius);
            if (trial % 2 == 1) q[4][size_t(trial / 4 % 3)] = std::nextafter(q[4][size_t(trial / 4 % 3)], 1e9f);
        }
        if (orient3d(q[0].data(), q[1].data(), q[2].data(), q[3].data()) == 0) continue;
        const int expected = reference_insphere(q[0], q[1], q[2], q[3], q[4]);
        REQUIRE(insphere_exact(q[0].data(), q[1].data(), q[2].data(), q[3].data(), q[4].data()) == expected);
        REQUIRE(insphere(q[0].data(), q[1].data(), q[2].data(), q[3].data(), q[4].data()) == expected);
        int sign;
        if (insphere_filter(q[0].data(), q[1].data(), q[2].data(), q[3].data(), q[4].data(), &sign)) {
            REQUIRE(sign == expected);
            ++filtered;
        } else {
            ++exact;
        }
        // The filter on doubles holding the same floats decides alike.
        double d[5][3];
        for (int i = 0; i < 5; ++i)
            for (int k = 0; k < 3; ++k) d[i][k] = q[i][size_t(k)];
        if (insphere_filter(d[0], d[1], d[2], d[3], d[4], &sign)) REQUIRE(sign == expected);

        const P2 r[4] = {{q[0][0], q[0][1]}, {q[1][0], q[1][1]}, {q[2][0], q[2][1]}, {q[3][0], q[3][1]}};
        if (orient2d(r[0].data(), r[1].data(), r[2].data()) == 0) continue;
        const int expected2 = reference_incircle(r[0], r[1], r[2], r[3]);
        REQUIRE(incircle_exact(r[0].data(), r[1].data(), r[2].data(), r[3].data()) == expected2);
        REQUIRE(incircle(r[0].data(), r[1].data(), r[2].data(), r[3].data()) == expected2);
    }
    // Both paths were exercised.
    REQUIRE(filtered > 1000);
    REQUIRE(exact > 500);
}

TEST_CASE("insphere is exactly zero on cospherical float points and keeps its sign under scaling by 2^k", "[insphere]") {
    // Integer points on the sphere of radius 15 around the origin (15^2 = 225 = 2^2 + 5^2 + 14^2 ...).
    std::vector<P3> sphere;
    for (int x = -15; x <= 15; ++x)
        for (int y = -15; y <= 15; ++y)
            for (int z = -15; z <= 15; ++z)
                if (x * x + y * y + z * z == 225) sphere.push_back({float(x), float(y), float(z)});
    REQUIRE(sphere.size() > 50);
    std::mt19937 rng(5);
    std::uniform_int_distribution<size_t> pick(0, sphere.size() - 1);
    std::uniform_real_distribution<float> u(-20, 20);
    int zeros = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        P3 q[5];
        for (auto& p : q) p = sphere[pick(rng)];
        if (trial % 3 == 0) q[4] = {u(rng), u(rng), u(rng)};
        if (orient3d(q[0].data(), q[1].data(), q[2].data(), q[3].data()) == 0) continue;
        const int expected = reference_insphere(q[0], q[1], q[2], q[3], q[4]);
        const bool on_sphere = trial % 3 != 0;
        if (on_sphere) {
            REQUIRE(expected == 0);
            ++zeros;
        }
        // Every power of two from the denormals to the top of the float range gives the same sign.
        for (int exponent : {-140, -126, -100, -60, -20, 0, 20, 60, 100, 122}) {
            P3 s[5];
            for (int i = 0; i < 5; ++i) s[i] = scaled(q[i], exponent);
            REQUIRE(insphere(s[0].data(), s[1].data(), s[2].data(), s[3].data(), s[4].data()) == expected);
        }
    }
    REQUIRE(zeros > 1000);
}

TEST_CASE("the filters never claim a sign the exact evaluation does not give, even at extreme magnitudes", "[insphere]") {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_int_distribution<int> e(-149, 126);
    for (int trial = 0; trial < 20000; ++trial) {
        P3 q[5];
        const int exponent = e(rng), spread = trial % 5 == 0 ? 40 : 2;
        for (auto& p : q)
            for (float& x : p) x = float(std::ldexp(u(rng), std::min(127, exponent + int(rng() % uint32_t(spread)))));
        int sign;
        if (insphere_filter(q[0].data(), q[1].data(), q[2].data(), q[3].data(), q[4].data(), &sign))
            REQUIRE(sign == insphere_exact(q[0].data(), q[1].data(), q[2].data(), q[3].data(), q[4].data()));
        if (incircle_filter(q[0].data(), q[1].data(), q[2].data(), q[3].data(), &sign))
            REQUIRE(sign == incircle_exact(q[0].data(), q[1].data(), q[2].data(), q[3].data()));
    }
}

TEST_CASE("the tie rule never answers 0, is antisymmetric and follows even permutations", "[insphere]") {
    // The corners of a cube and of a square: every five (four) are cospherical (cocircular).
    std::vector<P3> cube;
    for (int i = 0; i < 8; ++i) cube.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
    std::mt19937 rng(23);
    for (int trial = 0; trial < 5000; ++trial) {
        std::vector<uint32_t> pick = {0, 1, 2, 3, 4, 5, 6, 7};
        std::shuffle(pick.begin(), pick.end(), rng);
        uint32_t index[5];
        const float* p[5];
        for (int i = 0; i < 5; ++i) {
            p[i] = cube[pick[size_t(i)]].data();
            index[i] = uint32_t(rng() % 1000) * 8 + pick[size_t(i)];  // distinct
        }
        const int o = orient3d(p[0], p[1], p[2], p[3]);
        if (o == 0) continue;
        REQUIRE(insphere(p[0], p[1], p[2], p[3], p[4]) == 0);
        const int s = insphere_perturbed(p, index);
        REQUIRE(s != 0);
        // Swapping two vertices of the tetrahedron flips orientation and answer.
        const float* q[5] = {p[1], p[0], p[2], p[3], p[4]};
        const uint32_t qi[5] = {index[1], index[0], index[2], index[3], index[4]};
        REQUIRE(insphere_perturbed(q, qi) == -s);
        // A cyclic shift of three (even) keeps it.
        const float* r[5] = {p[1], p[2], p[0], p[3], p[4]};
        const uint32_t ri[5] = {index[1], index[2], index[0], index[3], index[4]};
        REQUIRE(insphere_perturbed(r, ri) == s);
        // Raising every index by the same amount changes nothing (only their order matters).
        uint32_t raised[5];
        for (int i = 0; i < 5; ++i) raised[i] = index[i] + 100000;
        REQUIRE(insphere_perturbed(p, raised) == s);
    }
}

TEST_CASE("the 2D tie rule is TetGen's 3D rule under an apex of the highest index", "[insphere]") {
    // Cocircular points: integer points on the circle of radius 5 (3-4-5 and 0-5 points).
    std::vector<P2> circle;
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            if (x * x + y * y == 25) circle.push_back({float(x), float(y)});
    REQUIRE(circle.size() == 12);
    std::mt19937 rng(29);
    const P3 apex = {0.25f, -0.5f, 7.0f};
    int checked = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        std::vector<uint32_t> pick(circle.size());
        for (uint32_t i = 0; i < pick.size(); ++i) pick[i] = i;
        std::shuffle(pick.begin(), pick.end(), rng);
        const float* p[4];
        uint32_t index[4];
        P3 lifted[4];
        for (int i = 0; i < 4; ++i) {
            p[i] = circle[pick[size_t(i)]].data();
            index[i] = pick[size_t(i)];
            lifted[i] = {p[i][0], p[i][1], 0.0f};
        }
        if (orient2d(p[0], p[1], p[2]) <= 0) continue;
        REQUIRE(incircle(p[0], p[1], p[2], p[3]) == 0);
        // The tetrahedron (a, b, c, apex) is positive for counter-clockwise (a, b, c) with the apex above.
        const float* q[5] = {lifted[0].data(), lifted[1].data(), lifted[2].data(), apex.data(), lifted[3].data()};
        const uint32_t qi[5] = {index[0], index[1], index[2], 1000, index[3]};
        REQUIRE(incircle_perturbed(p, index) == insphere_perturbed(q, qi));
        REQUIRE(incircle_perturbed(p, index) != 0);
        ++checked;
    }
    REQUIRE(checked > 500);
}

#ifdef TETPROBE_X86_64
namespace {
// The kernel inlines only into AVX2 code.
__attribute__((target("avx2"))) bool avx2_filter(const float* const P[5], int* sign) { return Avx2Insphere::filter(P, sign); }
__attribute__((target("avx2"))) void avx2_filter4(const float* const cells[4][4], const float* e, unsigned* inside,
                                                  unsigned* outside) {
    Avx2Insphere::filter4(cells, e, inside, outside);
}
}  // namespace
#endif

TEST_CASE("the AVX2 in-sphere filter decides exactly as the scalar one, bit for bit", "[insphere]") {
#ifdef TETPROBE_X86_64
    if (!cpu_has_avx2()) return;
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> u(-4, 4);
    std::vector<P3> sphere;
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            for (int z = -5; z <= 5; ++z)
                if (x * x + y * y + z * z == 25) sphere.push_back({float(x), float(y), float(z)});
    for (int trial = 0; trial < 20000; ++trial) {
        float padded[5][4] = {};
        for (int i = 0; i < 5; ++i) {
            const P3 p = trial % 2 ? sphere[rng() % sphere.size()] : P3{float(u(rng)), float(u(rng)), float(u(rng))};
            for (int k = 0; k < 3; ++k) padded[i][k] = std::ldexp(p[size_t(k)], trial % 7 - 3);
        }
        const float* const P[5] = {padded[0], padded[1], padded[2], padded[3], padded[4]};
        int scalar = 7, avx2 = 7;
        const bool scalar_decided = ScalarInsphere::filter(P, &scalar), avx2_decided = avx2_filter(P, &avx2);
        REQUIRE(scalar_decided == avx2_decided);
        REQUIRE(scalar == avx2);
    }
#endif
}

TEST_CASE("the four-cell in-sphere filters decide each cell as insphere_filter does, and never wrongly", "[insphere]") {
    // Random and cospherical cells (exact ties the filter must leave undecided or call 0), at scales
    // across the float range; each lane against the one-cell filter and the exact sign.
    std::mt19937 rng(43);
    std::uniform_real_distribution<double> u(-4, 4);
    std::vector<P3> sphere;
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            for (int z = -5; z <= 5; ++z)
                if (x * x + y * y + z * z == 25) sphere.push_back({float(x), float(y), float(z)});
    size_t decided = 0, undecided = 0;
    for (int trial = 0; trial < 5000; ++trial) {
        const int scale = trial % 9 * 6 - 24;
        auto draw = [&](float* out) {
            const P3 p = trial % 3 == 0 ? sphere[rng() % sphere.size()] : P3{float(u(rng)), float(u(rng)), float(u(rng))};
            for (int k = 0; k < 3; ++k) out[k] = std::ldexp(p[size_t(k)], scale);
        };
        float padded[4][4][4] = {}, e[4] = {};
        draw(e);
        const float* cells[4][4];
        for (int c = 0; c < 4; ++c) {
            do {
                for (int i = 0; i < 4; ++i) draw(padded[c][i]);
            } while (orient3d(padded[c][0], padded[c][1], padded[c][2], padded[c][3]) == 0);
            if (orient3d(padded[c][0], padded[c][1], padded[c][2], padded[c][3]) < 0)
                for (int k = 0; k < 3; ++k) std::swap(padded[c][0][k], padded[c][1][k]);
            for (int i = 0; i < 4; ++i) cells[c][i] = padded[c][i];
        }
        std::vector<std::pair<unsigned, unsigned>> results;
        unsigned inside = 0, outside = 0;
        ScalarInsphere::filter4(cells, e, &inside, &outside);
        results.push_back({inside, outside});
#ifdef TETPROBE_X86_64
        if (cpu_has_avx2()) {
            avx2_filter4(cells, e, &inside, &outside);
            results.push_back({inside, outside});
        }
#endif
        for (const auto& [in, out] : results) {
            REQUIRE((in & out) == 0);
            for (int c = 0; c < 4; ++c) {
                int sign = 7;
                const bool one = insphere_filter(cells[c][0], cells[c][1], cells[c][2], cells[c][3], e, &sign);
                REQUIRE(bool((in | out) >> c & 1u) == one);
                if (!one) {
                    ++undecided;
                    continue;
                }
                ++decided;
                REQUIRE(bool(in >> c & 1u) == (sign > 0));
                REQUIRE(bool(in >> c & 1u) == (insphere_exact(cells[c][0], cells[c][1], cells[c][2], cells[c][3], e) > 0));
            }
        }
    }
    REQUIRE(decided > 1000);
    REQUIRE(undecided > 100);  // the cospherical cells reach the exact fallback
}
