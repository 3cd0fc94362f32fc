// The exact in-sphere and in-circle signs: every float coordinate is m * 2^x with an integer m of at
// most 24 bits; scaled by 2^-k for the smallest x among the points, all of them are integers (below
// 2^277), and the determinant of their differences is evaluated in exact integer arithmetic, in the
// same expression as the filter's: in fixed width when they span few bits (integer_predicates.h),
// else with the fixed-capacity integers of exact_integer.h.
#include "core/insphere.h"

#include "core/exact_integer.h"
#include "core/float_bits.h"
#include "core/integer_predicates.h"

#include <algorithm>
#include <climits>

namespace tetprobe {

namespace {

// A float as sign, integer significand without trailing zero bits, and exponent: value = +-m * 2^x.
struct FloatParts {
    uint32_t significand = 0;  // 0 for zero
    int exponent = 0;
    bool negative = false;
};

FloatParts float_parts(float value) {
    const uint32_t bits = float_bits(value);
    FloatParts parts;
    parts.negative = (bits >> 31) != 0;
    const uint32_t biased = (bits >> 23) & 0xFFu, fraction = bits & 0x7FFFFFu;
    if (biased == 0) {
        parts.significand = fraction;  // zero or a denormal
        parts.exponent = -149;
    } else {
        parts.significand = fraction | 0x800000u;
        parts.exponent = int(biased) - 150;
    }
    if (parts.significand == 0) {
        parts.negative = false;
        return parts;
    }
    const int zeros = __builtin_ctz(parts.significand);
    parts.significand >>= zeros;
    parts.exponent += zeros;
    return parts;
}

// Coordinates of n points (dims each) as exact integers over their common power of two, and their
// differences from the last point: out[i][c] = point_i[c] - point_last[c], scaled, for i < n - 1.
template <int n, int dims>
void scaled_differences(const float* const points[n], ExactInteger (&out)[n - 1][dims]) {
    FloatParts parts[n][dims];
    int lowest = INT_MAX;
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < dims; ++c) {
            parts[i][c] = float_parts(points[i][c]);
            if (parts[i][c].significand != 0) lowest = std::min(lowest, parts[i][c].exponent);
        }
    ExactInteger last[dims];
    for (int c = 0; c < dims; ++c) {
        const FloatParts& p = parts[n - 1][c];
        exact_scaled(p.significand, p.significand ? p.exponent - lowest : 0, p.negative, last[c]);
    }
    for (int i = 0; i + 1 < n; ++i)
        for (int c = 0; c < dims; ++c) {
            const FloatParts& p = parts[i][c];
            ExactInteger value;
            exact_scaled(p.significand, p.significand ? p.exponent - lowest : 0, p.negative, value);
            exact_subtract(value, last[c], out[i][c]);
        }
}

// x * y - z * w
void cross_difference(const ExactInteger& x, const ExactInteger& y, const ExactInteger& z, const ExactInteger& w,
                      ExactInteger& out) {
    ExactInteger left, right;
    exact_multiply(x, y, left);
    exact_multiply(z, w, right);
    exact_subtract(left, right, out);
}

// s0 * m0 + s1 * m1 + s2 * m2, each term's sign given by negate_k.
void three_terms(const ExactInteger& s0, const ExactInteger& m0, bool negate0, const ExactInteger& s1,
                 const ExactInteger& m1, bool negate1, const ExactInteger& s2, const ExactInteger& m2, bool negate2,
                 ExactInteger& out) {
    ExactInteger term, sum;
    exact_multiply(s0, m0, sum);
    if (negate0) sum.negative = !sum.negative && sum.size != 0;
    exact_multiply(s1, m1, term);
    if (negate1) exact_subtract(sum, term, sum);
    else exact_add(sum, term, sum);
    exact_multiply(s2, m2, term);
    if (negate2) exact_subtract(sum, term, out);
    else exact_add(sum, term, out);
}

void lift(const ExactInteger* d, int dims, ExactInteger& out) {
    ExactInteger square;
    exact_multiply(d[0], d[0], out);
    for (int c = 1; c < dims; ++c) {
        exact_multiply(d[c], d[c], square);
        exact_add(out, square, out);
    }
}

// The sign of -(Shewchuk's insphere determinant) over exact differences from e.
int insphere_sign(const ExactInteger (&d)[4][3]) {
    enum { x = 0, y = 1, z = 2 };
    const auto& a = d[0];
    const auto& b = d[1];
    const auto& c = d[2];
    const auto& e = d[3];  // the fourth point, d in the filter's names
    ExactInteger ab, bc, cd, da, ac, bd;
    cross_difference(a[x], b[y], b[x], a[y], ab);
    cross_difference(b[x], c[y], c[x], b[y], bc);
    cross_difference(c[x], e[y], e[x], c[y], cd);
    cross_difference(e[x], a[y], a[x], e[y], da);
    cross_difference(a[x], c[y], c[x], a[y], ac);
    cross_difference(b[x], e[y], e[x], b[y], bd);
    ExactInteger abc, bcd, cda, dab;
    three_terms(a[z], bc, false, b[z], ac, true, c[z], ab, false, abc);
    three_terms(b[z], cd, false, c[z], bd, true, e[z], bc, false, bcd);
    three_terms(c[z], da, false, e[z], ac, false, a[z], cd, false, cda);
    three_terms(e[z], ab, false, a[z], bd, false, b[z], da, false, dab);
    ExactInteger alift, blift, clift, dlift;
    lift(a, 3, alift);
    lift(b, 3, blift);
    lift(c, 3, clift);
    lift(e, 3, dlift);
    ExactInteger first, second, term;
    cross_difference(dlift, abc, clift, dab, first);
    cross_difference(blift, cda, alift, bcd, second);
    exact_add(first, second, term);
    return -term.sign();
}

int incircle_sign(const ExactInteger (&d)[3][2]) {
    enum { x = 0, y = 1 };
    ExactInteger bc, ca, ab;
    cross_difference(d[1][x], d[2][y], d[2][x], d[1][y], bc);
    cross_difference(d[2][x], d[0][y], d[0][x], d[2][y], ca);
    cross_difference(d[0][x], d[1][y], d[1][x], d[0][y], ab);
    ExactInteger alift, blift, clift;
    lift(d[0], 2, alift);
    lift(d[1], 2, blift);
    lift(d[2], 2, clift);
    ExactInteger sum;
    three_terms(alift, bc, false, blift, ca, false, clift, ab, false, sum);
    return sum.sign();
}

// Sorts order[0..n) by indices[order[i]] (distinct) and returns +1 for an even permutation, -1 odd.
template <int n>
int sort_by_index(int (&order)[n], const uint32_t* indices) {
    for (int i = 0; i < n; ++i) order[i] = i;
    int parity = 1;
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0 && indices[order[j - 1]] > indices[order[j]]; --j) {
            std::swap(order[j - 1], order[j]);
            parity = -parity;
        }
    return parity;
}

}  // namespace

int insphere_exact(const float a[3], const float b[3], const float c[3], const float d[3], const float e[3]) {
    const float* const points[5] = {a, b, c, d, e};
    int sign;
    if (insphere_integer(a, b, c, d, e, &sign)) return sign;
    ExactInteger differences[4][3];
    scaled_differences<5, 3>(points, differences);
    return insphere_sign(differences);
}

int incircle_exact(const float a[2], const float b[2], const float c[2], const float d[2]) {
    int sign;
    if (incircle_integer(a, b, c, d, &sign)) return sign;
    const float* const points[4] = {a, b, c, d};
    ExactInteger differences[3][2];
    scaled_differences<4, 2>(points, differences);
    return incircle_sign(differences);
}

int insphere_tie(const float* const points[5], const uint32_t indices[5]) {
    // The lifted determinant gains eps_i times the cofactor of point i's lift, which is the
    // orientation of the other four in their order (with the permutation's sign); the lowest index
    // whose cofactor is not zero decides. Two suffice: if the four after the first and the first with
    // the last three were both coplanar, all five would be (or a point would lie on an edge's line
    // and the sphere at once, which only a vertex does).
    int order[5];
    const int parity = sort_by_index(order, indices);
    const float* q[5];
    for (int i = 0; i < 5; ++i) q[i] = points[order[i]];
    int sign = orient3d_fast(q[1], q[2], q[3], q[4]);
    if (sign == 0) sign = -orient3d_fast(q[0], q[2], q[3], q[4]);
    return parity * sign;
}

int incircle_tie(const float* const points[4], const uint32_t indices[4]) {
    // TetGen decides a flat set's ties in 3D, with the apex (the highest index) over the plane: its
    // insphere_s over (a, b, c, apex, d) sorts the apex last, one transposition more than sorting
    // (a, b, c, d), and every orientation with the apex is orient2d of the other three.
    int order[4];
    const int parity = sort_by_index(order, indices);
    const float* q[4];
    for (int i = 0; i < 4; ++i) q[i] = points[order[i]];
    int sign = orient2d_fast(q[1], q[2], q[3]);
    if (sign == 0) sign = -orient2d_fast(q[0], q[2], q[3]);
    return -parity * sign;
}

}  // namespace tetprobe
