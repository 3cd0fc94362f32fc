// Orientation predicates against exact references on adversarial float inputs: TetGen's copy of
// Shewchuk's exact predicates (orient3dexact, orient2dexact) everywhere, and an independent __int128
// evaluation wherever the inputs are integers times a power of two. Both the exact and the filtered
// versions are compared, also with the points permuted (the sign follows the permutation's parity).
#include "core/orientation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>

// TetGen 1.5's robust predicates (global functions in libtet; REAL is double). orient3dexact(a, b,
// c, d) is det[a - d, b - d, c - d], minus our orient3d; orient2dexact(a, b, c) is det[a - c, b - c],
// equal to ours. Declared as in exact_referee.h, which this file does not include because it pulls
// in the store.
void exactinit(int verbose, int noexact, int nofilter, double maxx, double maxy, double maxz);
double orient3dexact(double* pa, double* pb, double* pc, double* pd);
double orient2dexact(double* pa, double* pb, double* pc);

using namespace tetprobe;

namespace {

using Rng = std::mt19937_64;

int sign_of(double x) { return (x > 0) - (x < 0); }

void init_tetgen() {
    static const bool initialised = (exactinit(0, 0, 0, 1.0, 1.0, 1.0), true);
    (void)initialised;
}

int tetgen_orient3d(const float a[3], const float b[3], const float c[3], const float d[3]) {
    init_tetgen();
    double pa[3], pb[3], pc[3], pd[3];
    for (int k = 0; k < 3; ++k) pa[k] = a[k], pb[k] = b[k], pc[k] = c[k], pd[k] = d[k];
    return -sign_of(orient3dexact(pa, pb, pc, pd));
}

int tetgen_orient2d(const float a[2], const float b[2], const float c[2]) {
    init_tetgen();
    double pa[2] = {a[0], a[1]}, pb[2] = {b[0], b[1]}, pc[2] = {c[0], c[1]};
    return sign_of(orient2dexact(pa, pb, pc));
}

// Integer determinants, exact in __int128 for coordinates below 2^24 in magnitude.
int int_orient3d(const int64_t a[3], const int64_t b[3], const int64_t c[3], const int64_t d[3]) {
    __int128 u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
    const __int128 det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                         u[2] * (v[0] * w[1] - v[1] * w[0]);
    return (det > 0) - (det < 0);
}

int int_orient2d(const int64_t a[2], const int64_t b[2], const int64_t c[2]) {
    const __int128 det = __int128(b[0] - a[0]) * (c[1] - a[1]) - __int128(b[1] - a[1]) * (c[0] - a[0]);
    return (det > 0) - (det < 0);
}

std::string describe(const float* const* p, int count, int dim) {
    std::ostringstream s;
    s << std::hexfloat;
    for (int i = 0; i < count; ++i) {
        s << (i ? " " : "") << "(";
        for (int k = 0; k < dim; ++k) s << (k ? ", " : "") << p[i][k];
        s << ")";
    }
    return s.str();
}

// Compares our predicates with the reference on one case and counts; REQUIREs only on a mismatch
// (Catch's per-assertion cost would dominate millions of cases).
struct Tally {
    long cases = 0, fallbacks = 0, zeros = 0, nonzero_fallbacks = 0, mismatches = 0;
};

struct Checker3 {
    Tally tally;
    Rng perm_rng{7};

    // reference: the sign from TetGen; integer_reference: an independent one, or 2 when there is none.
    void check(const float a[3], const float b[3], const float c[3], const float d[3], int integer_reference = 2) {
        const int reference = tetgen_orient3d(a, b, c, d);
        const int exact = orient3d_exact(a, b, c, d);
        int filtered_sign = 0;
        const bool decided = orient3d_filter(a, b, c, d, &filtered_sign);
        const int filtered = orient3d(a, b, c, d);
        // A random permutation of the points: the sign times the permutation's parity.
        const float* p[4] = {a, b, c, d};
        int order[4] = {0, 1, 2, 3};
        std::shuffle(order, order + 4, perm_rng);
        int parity = 1;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j)
                if (order[i] > order[j]) parity = -parity;
        const int permuted = orient3d(p[order[0]], p[order[1]], p[order[2]], p[order[3]]);
        const int permuted_exact = orient3d_exact(p[order[0]], p[order[1]], p[order[2]], p[order[3]]);
        const bool ok = exact == reference && filtered == reference && (!decided || filtered_sign == reference) &&
                        permuted == parity * reference && permuted_exact == parity * reference &&
                        (integer_reference == 2 || integer_reference == reference);
        ++tally.cases;
        tally.fallbacks += !decided;
        tally.zeros += reference == 0;
        tally.nonzero_fallbacks += !decided && reference != 0;
        if (!ok && ++tally.mismatches <= 5) {
            INFO(describe(p, 4, 3));
            INFO("tetgen " << reference << " integer " << integer_reference << " exact " << exact << " filtered "
                           << filtered << " (decided " << decided << ") permuted " << permuted << " / "
                           << permuted_exact << " parity " << parity);
            CHECK(ok);
        }
    }

    void report(const char* family) {
        WARN(family << ": " << tally.cases << " cases, " << tally.zeros << " exact zeros, exact fallback in "
                    << tally.fallbacks << " (" << 100.0 * double(tally.fallbacks) / double(tally.cases) << "%), "
                    << tally.nonzero_fallbacks << " of them with a non-zero sign");
        REQUIRE(tally.mismatches == 0);
    }
};

struct Checker2 {
    Tally tally;
    Rng perm_rng{8};

    void check(const float a[2], const float b[2], const float c[2], int integer_reference = 2) {
        const int reference = tetgen_orient2d(a, b, c);
        const int exact = orient2d_exact(a, b, c);
        int filtered_sign = 0;
        const bool decided = orient2d_filter(a, b, c, &filtered_sign);
        const int filtered = orient2d(a, b, c);
        const float* p[3] = {a, b, c};
        int order[3] = {0, 1, 2};
        std::shuffle(order, order + 3, perm_rng);
        int parity = 1;
        for (int i = 0; i < 3; ++i)
            for (int j = i + 1; j < 3; ++j)
                if (order[i] > order[j]) parity = -parity;
        const int permuted = orient2d(p[order[0]], p[order[1]], p[order[2]]);
        const int permuted_exact = orient2d_exact(p[order[0]], p[order[1]], p[order[2]]);
        const bool ok = exact == reference && filtered == reference && (!decided || filtered_sign == reference) &&
                        permuted == parity * reference && permuted_exact == parity * reference &&
                        (integer_reference == 2 || integer_reference == reference);
        ++tally.cases;
        tally.fallbacks += !decided;
        tally.zeros += reference == 0;
        tally.nonzero_fallbacks += !decided && reference != 0;
        if (!ok && ++tally.mismatches <= 5) {
            INFO(describe(p, 3, 2));
            INFO("tetgen " << reference << " integer " << integer_reference << " exact " << exact << " filtered "
                           << filtered << " (decided " << decided << ") permuted " << permuted << " / "
                           << permuted_exact << " parity " << parity);
            CHECK(ok);
        }
    }

    void report(const char* family) {
        WARN(family << ": " << tally.cases << " cases, " << tally.zeros << " exact zeros, exact fallback in "
                    << tally.fallbacks << " (" << 100.0 * double(tally.fallbacks) / double(tally.cases) << "%), "
                    << tally.nonzero_fallbacks << " of them with a non-zero sign");
        REQUIRE(tally.mismatches == 0);
    }
};

float uniform(Rng& rng, double lo, double hi) { return float(std::uniform_real_distribution<double>(lo, hi)(rng)); }

// Moves x by -1, 0 or +1 ulp.
float nudge(Rng& rng, float x) {
    switch (rng() % 3) {
        case 0: return std::nextafter(x, -std::numeric_limits<float>::infinity());
        case 1: return std::nextafter(x, std::numeric_limits<float>::infinity());
        default: return x;
    }
}

// Any finite float, every exponent equally likely.
float random_bits_float(Rng& rng) {
    for (;;) {
        const uint32_t u = uint32_t(rng());
        float f;
        std::memcpy(&f, &u, sizeof f);
        if (std::isfinite(f)) return f;
    }
}

// A uniformly random rotation (from a random unit quaternion).
void random_rotation(Rng& rng, double r[3][3]) {
    std::normal_distribution<double> g;
    double q[4], n = 0;
    do {
        n = 0;
        for (double& x : q) x = g(rng), n += x * x;
    } while (n < 1e-6);
    n = std::sqrt(n);
    for (double& x : q) x /= n;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double m[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    std::memcpy(r, m, sizeof m);
}

// |q|^2 times a rotation, with integer entries, from a random integer quaternion q.
void integer_rotation(Rng& rng, int64_t r[3][3]) {
    int64_t w, x, y, z;
    do {
        w = int64_t(rng() % 7) - 3, x = int64_t(rng() % 7) - 3, y = int64_t(rng() % 7) - 3, z = int64_t(rng() % 7) - 3;
    } while (w == 0 && x == 0 && y == 0 && z == 0);
    const int64_t m[3][3] = {{w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)},
                             {2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)},
                             {2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z}};
    std::memcpy(r, m, sizeof m);
}

// The value pool of the denormal-gap family: denormals, the smallest normal, 1 and its neighbours,
// huge values and the largest float.
float gap_value(Rng& rng) {
    static const float pool[] = {0.0f,
                                 std::numeric_limits<float>::denorm_min(),
                                 2 * std::numeric_limits<float>::denorm_min(),
                                 1e-40f,
                                 std::nextafter(1e-40f, 1.0f),
                                 std::numeric_limits<float>::min(),
                                 1e-20f,
                                 1.0f,
                                 std::nextafter(1.0f, 2.0f),
                                 std::nextafter(1.0f, 0.0f),
                                 3.0f,
                                 1e30f,
                                 std::nextafter(1e30f, 0.0f),
                                 std::numeric_limits<float>::max()};
    const float v = pool[rng() % (sizeof pool / sizeof pool[0])];
    return rng() % 2 ? -v : v;
}

constexpr int kScaleExponents[] = {-20, -10, 0, 10, 20};
constexpr double kOffsetScales[] = {1e6, 1e3, 1e-3};

}  // namespace

TEST_CASE("orientation signs: the stated convention and TetGen's relation", "[orientation]") {
    const float o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, z[3] = {0, 0, 1};
    CHECK(orient3d_exact(o, x, y, z) == 1);
    CHECK(orient3d(o, x, y, z) == 1);
    CHECK(orient3d(o, y, x, z) == -1);
    CHECK(orient3d(o, x, y, o) == 0);
    // TetGen's orient3d(a, b, c, d) is det[a - d, b - d, c - d]: minus ours.
    init_tetgen();
    double po[3] = {0, 0, 0}, px[3] = {1, 0, 0}, py[3] = {0, 1, 0}, pz[3] = {0, 0, 1};
    CHECK(orient3dexact(po, px, py, pz) < 0);
    const float o2[2] = {0, 0}, x2[2] = {1, 0}, y2[2] = {0, 1};
    CHECK(orient2d_exact(o2, x2, y2) == 1);
    CHECK(orient2d(o2, x2, y2) == 1);
    CHECK(orient2d(o2, y2, x2) == -1);
    double qo[2] = {0, 0}, qx[2] = {1, 0}, qy[2] = {0, 1};
    CHECK(orient2dexact(qo, qx, qy) > 0);
    // The error factors are Shewchuk's values.
    CHECK(kOrient3dErrorFactor == (7.0 + 56.0 * std::ldexp(1.0, -53)) * std::ldexp(1.0, -53));
    CHECK(kOrient2dErrorFactor == (3.0 + 16.0 * std::ldexp(1.0, -53)) * std::ldexp(1.0, -53));
    // Extremes: the largest floats (cubes near 2^384) and the smallest denormals (cubes near 2^-447).
    const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min();
    const float bx[3] = {big, 0, 0}, by[3] = {0, big, 0}, bz[3] = {0, 0, big}, bm[3] = {-big, -big, -big};
    CHECK(orient3d_exact(bm, bx, by, bz) == 1);
    CHECK(orient3d(bm, bx, by, bz) == 1);
    const float tx[3] = {tiny, 0, 0}, ty[3] = {0, tiny, 0}, tz[3] = {0, 0, tiny};
    CHECK(orient3d_exact(o, tx, ty, tz) == 1);
    CHECK(orient3d(o, tx, ty, tz) == 1);
    CHECK(orient3d(o, tx, tz, ty) == -1);
}

TEST_CASE("orient3d on nearly coplanar points", "[orientation]") {
    Rng rng(1001);
    Checker3 check;
    for (int n = 0; n < 400000; ++n) {
        const double s = std::ldexp(1.0, kScaleExponents[rng() % 5]);
        float p[4][3];
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) p[i][k] = uniform(rng, -s, s);
        // Kinds 1 and 2 round c (and then d) from the line through a and b: the determinant
        // relative to its permanent drops from about 2^-24 (a rounded plane point) to about 2^-48,
        // where the double filter has to give up now and then.
        const int kind = int(n % 3);
        if (kind > 0) {
            const double t = uniform(rng, -1, 2);
            for (int k = 0; k < 3; ++k) p[2][k] = float(p[0][k] + t * (double(p[1][k]) - p[0][k]));
        }
        const double alpha = uniform(rng, -1, 2), beta = kind == 2 ? 0.0 : uniform(rng, -1, 2);
        for (int k = 0; k < 3; ++k) {
            const double on_plane = p[0][k] + alpha * (double(p[1][k]) - p[0][k]) + beta * (double(p[2][k]) - p[0][k]);
            p[3][k] = nudge(rng, float(on_plane));
        }
        check.check(p[0], p[1], p[2], p[3]);
    }
    check.report("3D nearly coplanar");
}

TEST_CASE("orient3d on rotated lattices", "[orientation]") {
    Rng rng(1002);
    SECTION("a random rotation, rounded to float") {
        Checker3 check;
        for (int set = 0; set < 2000; ++set) {
            double r[3][3];
            random_rotation(rng, r);
            const int size = 1 + int(rng() % 5);
            const double scale = std::ldexp(uniform(rng, 1, 2), int(rng() % 21) - 10);
            double t[3];
            for (double& x : t) x = uniform(rng, -100, 100);
            for (int n = 0; n < 150; ++n) {
                float p[4][3];
                for (auto& q : p) {
                    int l[3];
                    for (int& x : l) x = int(rng() % (2 * size + 1)) - size;
                    for (int k = 0; k < 3; ++k)
                        q[k] = float((r[k][0] * l[0] + r[k][1] * l[1] + r[k][2] * l[2]) * scale + t[k]);
                }
                check.check(p[0], p[1], p[2], p[3]);
            }
        }
        check.report("3D rotated lattices, rounded");
    }
    SECTION("an integer rotation: exact, so lattice planes stay exactly flat") {
        Checker3 check;
        for (int set = 0; set < 2000; ++set) {
            int64_t r[3][3];
            integer_rotation(rng, r);
            const int size = 1 + int(rng() % 4);
            int64_t t[3];
            for (int64_t& x : t) x = int64_t(rng() % (1u << 21)) - (1 << 20);
            const int exponent = int(rng() % 61) - 30;
            for (int n = 0; n < 150; ++n) {
                int64_t q[4][3];
                float p[4][3];
                for (int i = 0; i < 4; ++i) {
                    int64_t l[3];
                    for (int64_t& x : l) x = int64_t(rng() % (2 * size + 1)) - size;
                    for (int k = 0; k < 3; ++k) {
                        q[i][k] = r[k][0] * l[0] + r[k][1] * l[1] + r[k][2] * l[2] + t[k];
                        p[i][k] = std::ldexp(float(q[i][k]), exponent);  // exact: |q| < 2^24
                    }
                }
                check.check(p[0], p[1], p[2], p[3], int_orient3d(q[0], q[1], q[2], q[3]));
            }
        }
        check.report("3D integer-rotated lattices");
        CHECK(check.tally.zeros > check.tally.cases / 10);
    }
}

TEST_CASE("orient3d on points offset far from the origin with tiny relative differences", "[orientation]") {
    Rng rng(1003);
    for (const double scale : kOffsetScales) {
        Checker3 check;
        for (int n = 0; n < 150000; ++n) {
            double o[3];
            for (double& x : o) x = scale * uniform(rng, 1, 2) * (rng() % 2 ? 1 : -1);
            // Spreads of a few float ulps (many exact coincidences) up to a thousand.
            const double spread = rng() % 2 ? 1e-6 : 1e-4;
            float p[4][3];
            for (auto& q : p)
                for (int k = 0; k < 3; ++k) q[k] = float(o[k] * (1 + uniform(rng, -spread, spread)));
            check.check(p[0], p[1], p[2], p[3]);
        }
        check.report(scale == 1e6 ? "3D offset 1e6" : scale == 1e3 ? "3D offset 1e3" : "3D offset 1e-3");
    }
}

TEST_CASE("orient3d with denormal gaps: coordinates near 1e-40 next to 1 and 1e30", "[orientation]") {
    Rng rng(1004);
    Checker3 check;
    for (int n = 0; n < 300000; ++n) {
        float p[4][3];
        for (auto& q : p)
            for (float& x : q) x = gap_value(rng);
        check.check(p[0], p[1], p[2], p[3]);
    }
    check.report("3D denormal gaps");
}

TEST_CASE("orient3d is zero on exactly degenerate points", "[orientation]") {
    Rng rng(1005);
    Checker3 check;
    for (int n = 0; n < 100000; ++n) {
        float p[4][3];
        int64_t q[4][3];
        const int kind = int(n % 4);
        const int exponent = int(rng() % 61) - 30;
        if (kind == 0) {  // a repeated point among arbitrary floats
            for (auto& x : p)
                for (float& v : x) v = n % 8 == 0 ? random_bits_float(rng) : uniform(rng, -1e3, 1e3);
            const int i = int(rng() % 4), j = (i + 1 + int(rng() % 3)) % 4;
            std::memcpy(p[j], p[i], sizeof p[i]);
            check.check(p[0], p[1], p[2], p[3]);
        } else if (kind == 1) {  // four arbitrary floats sharing one coordinate: a plane
            const int axis = int(rng() % 3);
            const float shared = random_bits_float(rng);
            for (auto& x : p)
                for (int k = 0; k < 3; ++k) x[k] = k == axis ? shared : random_bits_float(rng);
            check.check(p[0], p[1], p[2], p[3]);
        } else {  // integer points: three collinear (kind 2) or all four on an integer plane (kind 3)
            int64_t base[3], dir[3];
            for (int64_t& x : base) x = int64_t(rng() % 2001) - 1000;
            for (int64_t& x : dir) x = int64_t(rng() % 41) - 20;
            const int64_t alpha = int64_t(rng() % 9) - 4, beta = int64_t(rng() % 9) - 4;
            for (int i = 0; i < 4; ++i) {
                if (kind == 2 && i < 3) {
                    const int64_t t = int64_t(rng() % 21) - 10;
                    for (int k = 0; k < 3; ++k) q[i][k] = base[k] + t * dir[k];
                } else if (kind == 2) {
                    for (int k = 0; k < 3; ++k) q[i][k] = int64_t(rng() % 2001) - 1000;
                } else {
                    q[i][0] = int64_t(rng() % 2001) - 1000;
                    q[i][1] = int64_t(rng() % 2001) - 1000;
                    q[i][2] = alpha * q[i][0] + beta * q[i][1] + base[2];
                }
            }
            std::shuffle(q, q + 4, rng);
            for (int i = 0; i < 4; ++i)
                for (int k = 0; k < 3; ++k) p[i][k] = std::ldexp(float(q[i][k]), exponent);
            const int integer = int_orient3d(q[0], q[1], q[2], q[3]);
            REQUIRE(integer == 0);
            check.check(p[0], p[1], p[2], p[3], integer);
        }
        REQUIRE(orient3d(p[0], p[1], p[2], p[3]) == 0);
    }
    check.report("3D exactly degenerate");
    CHECK(check.tally.zeros == check.tally.cases);
}

TEST_CASE("orient3d on random general points", "[orientation]") {
    Rng rng(1006);
    Checker3 uniform_check, any_exponent_check;
    for (int n = 0; n < 300000; ++n) {
        float p[4][3];
        for (auto& q : p)
            for (float& x : q) x = uniform(rng, -1, 1);
        uniform_check.check(p[0], p[1], p[2], p[3]);
        for (auto& q : p)
            for (float& x : q) x = random_bits_float(rng);
        any_exponent_check.check(p[0], p[1], p[2], p[3]);
    }
    uniform_check.report("3D random in [-1, 1]");
    any_exponent_check.report("3D random, any exponent");
}

TEST_CASE("orient2d against TetGen's exact predicate and integer arithmetic", "[orientation]") {
    Rng rng(2001);
    SECTION("nearly collinear") {
        Checker2 check;
        for (int n = 0; n < 200000; ++n) {
            const double s = std::ldexp(1.0, kScaleExponents[rng() % 5]);
            float p[3][2];
            for (int i = 0; i < 2; ++i)
                for (int k = 0; k < 2; ++k) p[i][k] = uniform(rng, -s, s);
            const double t = uniform(rng, -1, 2);
            for (int k = 0; k < 2; ++k) p[2][k] = nudge(rng, float(p[0][k] + t * (double(p[1][k]) - p[0][k])));
            check.check(p[0], p[1], p[2]);
        }
        check.report("2D nearly collinear");
    }
    SECTION("rotated lattices, rounded and exact") {
        Checker2 check;
        for (int set = 0; set < 2000; ++set) {
            const double angle = uniform(rng, 0, 6.283185307179586);
            const double scale = std::ldexp(uniform(rng, 1, 2), int(rng() % 21) - 10);
            const int64_t u = int64_t(rng() % 7) - 3, v = int64_t(rng() % 7) - 3 + (u == 0);
            const int size = 1 + int(rng() % 5);
            const int exponent = int(rng() % 61) - 30;
            for (int n = 0; n < 100; ++n) {
                float p[3][2], e[3][2];
                int64_t q[3][2];
                for (int i = 0; i < 3; ++i) {
                    const int64_t l0 = int64_t(rng() % (2 * size + 1)) - size, l1 = int64_t(rng() % (2 * size + 1)) - size;
                    p[i][0] = float((std::cos(angle) * l0 - std::sin(angle) * l1) * scale + 1000.0);
                    p[i][1] = float((std::sin(angle) * l0 + std::cos(angle) * l1) * scale - 300.0);
                    q[i][0] = u * l0 - v * l1 + 4096, q[i][1] = v * l0 + u * l1 - 777;  // |q|^2 x a rotation
                    e[i][0] = std::ldexp(float(q[i][0]), exponent), e[i][1] = std::ldexp(float(q[i][1]), exponent);
                }
                check.check(p[0], p[1], p[2]);
                check.check(e[0], e[1], e[2], int_orient2d(q[0], q[1], q[2]));
            }
        }
        check.report("2D rotated lattices");
    }
    SECTION("offsets 1e6, 1e3, 1e-3 with tiny relative differences") {
        Checker2 check;
        for (int n = 0; n < 300000; ++n) {
            const double scale = kOffsetScales[n % 3];
            const double spread = rng() % 2 ? 1e-6 : 1e-4;
            double o[2];
            for (double& x : o) x = scale * uniform(rng, 1, 2) * (rng() % 2 ? 1 : -1);
            float p[3][2];
            for (auto& q : p)
                for (int k = 0; k < 2; ++k) q[k] = float(o[k] * (1 + uniform(rng, -spread, spread)));
            check.check(p[0], p[1], p[2]);
        }
        check.report("2D offsets");
    }
    SECTION("denormal gaps") {
        Checker2 check;
        for (int n = 0; n < 200000; ++n) {
            float p[3][2];
            for (auto& q : p)
                for (float& x : q) x = gap_value(rng);
            check.check(p[0], p[1], p[2]);
        }
        check.report("2D denormal gaps");
    }
    SECTION("exactly degenerate") {
        Checker2 check;
        for (int n = 0; n < 100000; ++n) {
            float p[3][2];
            const int kind = n % 3;
            if (kind == 0) {  // a repeated point
                for (auto& q : p)
                    for (float& x : q) x = random_bits_float(rng);
                const int i = int(rng() % 3), j = (i + 1 + int(rng() % 2)) % 3;
                std::memcpy(p[j], p[i], sizeof p[i]);
                check.check(p[0], p[1], p[2]);
            } else if (kind == 1) {  // three arbitrary floats on an axis-parallel line
                const int axis = int(rng() % 2);
                const float shared = random_bits_float(rng);
                for (auto& q : p)
                    for (int k = 0; k < 2; ++k) q[k] = k == axis ? shared : random_bits_float(rng);
                check.check(p[0], p[1], p[2]);
            } else {  // collinear integer points
                int64_t q[3][2], base[2], dir[2];
                for (int64_t& x : base) x = int64_t(rng() % 200001) - 100000;
                for (int64_t& x : dir) x = int64_t(rng() % 201) - 100;
                const int exponent = int(rng() % 61) - 30;
                for (int i = 0; i < 3; ++i) {
                    const int64_t t = int64_t(rng() % 201) - 100;
                    for (int k = 0; k < 2; ++k) {
                        q[i][k] = base[k] + t * dir[k];
                        p[i][k] = std::ldexp(float(q[i][k]), exponent);
                    }
                }
                check.check(p[0], p[1], p[2], int_orient2d(q[0], q[1], q[2]));
            }
            REQUIRE(orient2d(p[0], p[1], p[2]) == 0);
        }
        check.report("2D exactly degenerate");
        CHECK(check.tally.zeros == check.tally.cases);
    }
    SECTION("random general points") {
        Checker2 uniform_check, any_exponent_check;
        for (int n = 0; n < 150000; ++n) {
            float p[3][2];
            for (auto& q : p)
                for (float& x : q) x = uniform(rng, -1, 1);
            uniform_check.check(p[0], p[1], p[2]);
            for (auto& q : p)
                for (float& x : q) x = random_bits_float(rng);
            any_exponent_check.check(p[0], p[1], p[2]);
        }
        uniform_check.report("2D random in [-1, 1]");
        any_exponent_check.report("2D random, any exponent");
    }
}

TEST_CASE("orientation predicates terminate on NaN and infinite inputs", "[orientation]") {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const float values[] = {nan, inf, -inf, 0.0f, 1.0f, std::numeric_limits<float>::max()};
    int count = 0;
    for (float v : values)
        for (int slot = 0; slot < 12; ++slot) {
            float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
            p[slot / 3][slot % 3] = v;
            const int s3 = orient3d(p[0], p[1], p[2], p[3]), e3 = orient3d_exact(p[0], p[1], p[2], p[3]);
            const int s2 = orient2d(p[0], p[1], p[2]), e2 = orient2d_exact(p[0], p[1], p[2]);
            count += (s3 >= -1 && s3 <= 1) + (e3 >= -1 && e3 <= 1) + (s2 >= -1 && s2 <= 1) + (e2 >= -1 && e2 <= 1);
        }
    CHECK(count == 6 * 12 * 4);
}
