// The exact orientation signs: the determinant expanded into products of input coordinates, each
// product written exactly as doubles, and the doubles summed exactly (Shewchuk 1997: two-sum and
// grow-expansion with zero elimination). The sign of the sum is that of its largest component.
//
// Range: float magnitudes lie in [2^-149, 2^128). Every product of two or three coordinates and
// every two-sum error below is an integer multiple of 2^-447 (the smallest denormal cubed), far
// above double's underflow threshold 2^-1022, and a sum of 24 cubes stays below 2^389, far below
// double's overflow; so each step below is exact, never flushed to zero, never infinite.
//
// Every multiplication here is exact (at most 48-bit significands), so a compiler that contracts
// a*b+c into a fused multiply-add (GCC does by default when the target has FMA, e.g. aarch64)
// cannot change any result; no std::fma and no Veltkamp splitting (which contraction would break).
#include "core/orientation.h"

#include "core/exact_sum.h"

#include <cstdint>
#include <cstring>

namespace tetprobe {

namespace {

// x*y*z exactly as hi + lo, for floats x, y, z: p = x*y is exact (at most 48 significant bits); its
// high part keeps the top 24 bits of the significand (the low 29 stored bits cleared, truncation),
// the rest p - hi is exact (Sterbenz) and has at most 24 significant bits; so both parts times z
// have at most 48 bits and are exact.
inline void triple_product(float x, float y, float z, double& hi, double& lo) {
    const double p = double(x) * double(y);
    uint64_t bits;
    std::memcpy(&bits, &p, sizeof bits);
    bits &= ~((uint64_t(1) << 29) - 1);
    double p_hi;
    std::memcpy(&p_hi, &bits, sizeof p_hi);
    const double p_lo = p - p_hi;
    hi = p_hi * double(z);
    lo = p_lo * double(z);
}

// det[b - a, c - a, d - a] = det of the 4x4 matrix with rows (1, x_i, y_i, z_i) for the points
// (a, b, c, d): a sum over the 24 permutations (l, i, j, k) of the points, with the sign of the
// permutation, of x_i * y_j * z_k (l takes the column of ones).
struct Term {
    int i, j, k;
    double sign;
};

struct TermTable {
    Term terms[24];
};

constexpr TermTable make_terms() {
    TermTable t{};
    int n = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
                if (i == j || j == k || i == k) continue;
                const int l = 6 - i - j - k;
                const int p[4] = {l, i, j, k};
                int inversions = 0;
                for (int r = 0; r < 4; ++r)
                    for (int s = r + 1; s < 4; ++s) inversions += p[r] > p[s];
                t.terms[n++] = Term{i, j, k, inversions % 2 ? -1.0 : 1.0};
            }
    return t;
}

constexpr TermTable kTerms = make_terms();

// The exact determinant as a nonoverlapping expansion e[0..n) in increasing magnitude.
int orient3d_expansion(const float a[3], const float b[3], const float c[3], const float d[3], double e[49]) {
    const float* points[4] = {a, b, c, d};
    int n = 0;
    for (const Term& t : kTerms.terms) {
        double hi, lo;
        triple_product(points[t.i][0], points[t.j][1], points[t.k][2], hi, lo);
        n = grow_expansion(e, n, t.sign * hi);
        n = grow_expansion(e, n, t.sign * lo);
    }
    return n;
}

int orient2d_expansion(const float a[2], const float b[2], const float c[2], double e[7]) {
    // det[b - a, c - a] = det of the rows (1, x, y) of a, b, c; each product of two floats is exact.
    const double terms[6] = {
        double(b[0]) * c[1], -(double(b[1]) * c[0]), -(double(a[0]) * c[1]),
        double(a[1]) * c[0], double(a[0]) * b[1],    -(double(a[1]) * b[0]),
    };
    int n = 0;
    for (double t : terms) n = grow_expansion(e, n, t);
    return n;
}

// An expansion's value rounded to double: its components summed from the smallest up (they do not
// overlap, so the result is within an ulp or so of the exact value, and has its sign).
double expansion_value(const double* e, int n) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += e[i];
    return sum;
}

}  // namespace

int orient3d_exact(const float a[3], const float b[3], const float c[3], const float d[3]) {
    double e[49];
    return expansion_sign(e, orient3d_expansion(a, b, c, d, e));
}

double orient3d_exact_value(const float a[3], const float b[3], const float c[3], const float d[3]) {
    double e[49];
    return expansion_value(e, orient3d_expansion(a, b, c, d, e));
}

int orient2d_exact(const float a[2], const float b[2], const float c[2]) {
    double e[7];
    return expansion_sign(e, orient2d_expansion(a, b, c, e));
}

double orient2d_exact_value(const float a[2], const float b[2], const float c[2]) {
    double e[7];
    return expansion_value(e, orient2d_expansion(a, b, c, e));
}

}  // namespace tetprobe
