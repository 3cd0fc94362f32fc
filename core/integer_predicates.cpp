#include "core/integer_predicates.h"

#include "core/float_bits.h"
#include "core/orientation.h"

#include <algorithm>
#include <climits>
#include <cstring>

namespace tetprobe {

namespace {

#if defined(__SIZEOF_INT128__)
using Int128 = __int128;
using Uint128 = unsigned __int128;

// Differences of n points (dims coordinates each) from point `from`, as integers: every coordinate
// scaled by 2^-lowest (the largest power of two dividing all the nonzero ones; a float is m 2^x with
// m below 2^24, so the product with a power of two is exact). False when a scaled coordinate would
// reach 2^39 in magnitude; else the differences stay below 2^40, and *span bounds them by a power of
// two.
template <int n, int dims>
bool integer_differences(const float* const (&points)[n], int from, int64_t (&out)[n - 1][dims], int* span) {
    int lowest = INT_MAX, highest = INT_MIN;
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < dims; ++c) {
            const uint32_t bits = float_bits(points[i][c]) & 0x7FFFFFFFu;
            if (bits == 0) continue;
            const uint32_t biased = bits >> 23;
            const uint32_t significand = biased ? ((bits & 0x7FFFFFu) | 0x800000u) : bits;
            const int exponent = (biased ? int(biased) : 1) - 150;  // of the significand's last bit
            lowest = std::min(lowest, exponent + __builtin_ctz(significand));
            highest = std::max(highest, exponent + 24);  // |value| < 2^(exponent + 24)
        }
    if (lowest == INT_MAX) lowest = highest = 0;
    if (highest - lowest > 39) return false;
    *span = highest - lowest + 1;
    const uint64_t scale_bits = uint64_t(1023 - lowest) << 52;  // 2^-lowest, lowest in [-149, 127]
    double scale;
    std::memcpy(&scale, &scale_bits, sizeof scale);
    int64_t base[dims];
    for (int c = 0; c < dims; ++c) base[c] = int64_t(double(points[from][c]) * scale);
    for (int i = 0, row = 0; i < n; ++i) {
        if (i == from) continue;
        for (int c = 0; c < dims; ++c) out[row][c] = int64_t(double(points[i][c]) * scale) - base[c];
        ++row;
    }
    return true;
}

int sign_of(Int128 x) { return (x > 0) - (x < 0); }

// 256-bit unsigned accumulator of products of two magnitudes below 2^128.
struct Wide {
    uint64_t limb[4] = {0, 0, 0, 0};
    void add_product(Uint128 x, Uint128 y) {
        const uint64_t x0 = uint64_t(x), x1 = uint64_t(x >> 64), y0 = uint64_t(y), y1 = uint64_t(y >> 64);
        const Uint128 p00 = Uint128(x0) * y0, p01 = Uint128(x0) * y1, p10 = Uint128(x1) * y0, p11 = Uint128(x1) * y1;
        Uint128 sum = Uint128(limb[0]) + uint64_t(p00);
        limb[0] = uint64_t(sum);
        sum = (sum >> 64) + limb[1] + uint64_t(p00 >> 64) + uint64_t(p01) + uint64_t(p10);
        limb[1] = uint64_t(sum);
        sum = (sum >> 64) + limb[2] + uint64_t(p01 >> 64) + uint64_t(p10 >> 64) + uint64_t(p11);
        limb[2] = uint64_t(sum);
        limb[3] += uint64_t(sum >> 64) + uint64_t(p11 >> 64);
    }
};

int compare(const Wide& a, const Wide& b) {
    for (int i = 3; i >= 0; --i)
        if (a.limb[i] != b.limb[i]) return a.limb[i] < b.limb[i] ? -1 : 1;
    return 0;
}

// Adds lift * minor (lift >= 0) to positive or negative by the sign of minor, flipped if subtract.
void add_term(Uint128 lift, Int128 minor, bool subtract, Wide& positive, Wide& negative) {
    const bool below = (minor < 0) != subtract;
    const Uint128 magnitude = minor < 0 ? Uint128(-minor) : Uint128(minor);
    (below ? negative : positive).add_product(lift, magnitude);
}
#endif

}  // namespace

bool orient3d_integer(const float a[3], const float b[3], const float c[3], const float d[3], int* sign) {
#if defined(__SIZEOF_INT128__)
    const float* const points[4] = {a, b, c, d};
    int64_t e[3][3];  // b - a, c - a, d - a
    int span;
    if (!integer_differences<4, 3>(points, 0, e, &span)) return false;
    if (span <= 20) {  // differences below 2^21: every product and sum fits 64 bits
        const int64_t yz = e[1][1] * e[2][2] - e[1][2] * e[2][1], xz = e[1][0] * e[2][2] - e[1][2] * e[2][0];
        const int64_t xy = e[1][0] * e[2][1] - e[1][1] * e[2][0];
        const int64_t det = e[0][0] * yz - e[0][1] * xz + e[0][2] * xy;
        *sign = (det > 0) - (det < 0);
        return true;
    }
    const Int128 yz = Int128(e[1][1]) * e[2][2] - Int128(e[1][2]) * e[2][1];
    const Int128 xz = Int128(e[1][0]) * e[2][2] - Int128(e[1][2]) * e[2][0];
    const Int128 xy = Int128(e[1][0]) * e[2][1] - Int128(e[1][1]) * e[2][0];
    *sign = sign_of(Int128(e[0][0]) * yz - Int128(e[0][1]) * xz + Int128(e[0][2]) * xy);
    return true;
#else
    return false;
#endif
}

bool orient2d_integer(const float a[2], const float b[2], const float c[2], int* sign) {
#if defined(__SIZEOF_INT128__)
    const float* const points[3] = {a, b, c};
    int64_t e[2][2];  // b - a, c - a
    int span;
    if (!integer_differences<3, 2>(points, 0, e, &span)) return false;
    *sign = sign_of(Int128(e[0][0]) * e[1][1] - Int128(e[0][1]) * e[1][0]);
    return true;
#else
    return false;
#endif
}

bool insphere_integer(const float a[3], const float b[3], const float c[3], const float d[3], const float e[3], int* sign) {
#if defined(__SIZEOF_INT128__)
    const float* const points[5] = {a, b, c, d, e};
    int64_t q[4][3];  // a - e, b - e, c - e, d - e: below 2^40, so 2x2 minors below 2^81, 3x3 below 2^123
    int span;
    if (!integer_differences<5, 3>(points, 4, q, &span)) return false;
    enum { x = 0, y = 1, z = 2 };
    if (span <= 19) {
        // Differences below 2^20 (lattices): minors below 2^41, 3x3 below 2^63, lifts below 2^42, and
        // the four products below 2^105.
        auto minor64 = [&](int i, int j) { return q[i][x] * q[j][y] - q[j][x] * q[i][y]; };
        const int64_t ab = minor64(0, 1), bc = minor64(1, 2), cd = minor64(2, 3), da = minor64(3, 0), ac = minor64(0, 2),
                      bd = minor64(1, 3);
        const int64_t abc = q[0][z] * bc - q[1][z] * ac + q[2][z] * ab;
        const int64_t bcd = q[1][z] * cd - q[2][z] * bd + q[3][z] * bc;
        const int64_t cda = q[2][z] * da + q[3][z] * ac + q[0][z] * cd;
        const int64_t dab = q[3][z] * ab + q[0][z] * bd + q[1][z] * da;
        auto lift64 = [&](int i) { return q[i][x] * q[i][x] + q[i][y] * q[i][y] + q[i][z] * q[i][z]; };
        const Int128 det = (Int128(lift64(3)) * abc - Int128(lift64(2)) * dab) + (Int128(lift64(1)) * cda - Int128(lift64(0)) * bcd);
        *sign = -sign_of(det);
        return true;
    }
    auto minor = [&](int i, int j) { return Int128(q[i][x]) * q[j][y] - Int128(q[j][x]) * q[i][y]; };
    const Int128 ab = minor(0, 1), bc = minor(1, 2), cd = minor(2, 3), da = minor(3, 0), ac = minor(0, 2), bd = minor(1, 3);
    const Int128 abc = q[0][z] * bc - q[1][z] * ac + q[2][z] * ab;
    const Int128 bcd = q[1][z] * cd - q[2][z] * bd + q[3][z] * bc;
    const Int128 cda = q[2][z] * da + q[3][z] * ac + q[0][z] * cd;
    const Int128 dab = q[3][z] * ab + q[0][z] * bd + q[1][z] * da;
    auto lift = [&](int i) { return Uint128(Int128(q[i][x]) * q[i][x]) + Uint128(Int128(q[i][y]) * q[i][y]) + Uint128(Int128(q[i][z]) * q[i][z]); };
    // Shewchuk's determinant dlift abc - clift dab + blift cda - alift bcd; the store's sign is minus it.
    Wide positive, negative;
    add_term(lift(3), abc, false, positive, negative);
    add_term(lift(2), dab, true, positive, negative);
    add_term(lift(1), cda, false, positive, negative);
    add_term(lift(0), bcd, true, positive, negative);
    *sign = -compare(positive, negative);
    return true;
#else
    return false;
#endif
}

bool incircle_integer(const float a[2], const float b[2], const float c[2], const float d[2], int* sign) {
#if defined(__SIZEOF_INT128__)
    const float* const points[4] = {a, b, c, d};
    int64_t q[3][2];  // a - d, b - d, c - d
    int span;
    if (!integer_differences<4, 2>(points, 3, q, &span)) return false;
    auto minor = [&](int i, int j) { return Int128(q[i][0]) * q[j][1] - Int128(q[j][0]) * q[i][1]; };
    auto lift = [&](int i) { return Uint128(Int128(q[i][0]) * q[i][0]) + Uint128(Int128(q[i][1]) * q[i][1]); };
    // Shewchuk's incircle: alift bc + blift ca + clift ab, positive inside.
    Wide positive, negative;
    add_term(lift(0), minor(1, 2), false, positive, negative);
    add_term(lift(1), minor(2, 0), false, positive, negative);
    add_term(lift(2), minor(0, 1), false, positive, negative);
    *sign = compare(positive, negative);
    return true;
#else
    return false;
#endif
}

int orient3d_exact_fast(const float a[3], const float b[3], const float c[3], const float d[3]) {
    int sign;
    return orient3d_integer(a, b, c, d, &sign) ? sign : orient3d_exact(a, b, c, d);
}

int orient2d_exact_fast(const float a[2], const float b[2], const float c[2]) {
    int sign;
    return orient2d_integer(a, b, c, &sign) ? sign : orient2d_exact(a, b, c);
}

}  // namespace tetprobe
