// The four orientations of a tetrahedron with a query point, D[k] = orient3d of the cell with vertex
// k replaced by the query (their sum is the cell's own orientation), and the filter's bound: a D
// beyond +-bound has the sign of its exact value. Evaluated in double from the differences
// a_i = P_i - q, each as det(a_i, a_j, a_l) of the three other vertices (i < j < l) expanded along
// x, which is Shewchuk's orient3d expression up to the order of its three terms, so his bound
// (7 + 56 eps) eps * permanent holds; the permanent is bounded by 6 * max|x| * max|y| * max|z|.
// Two implementations with the same operations in the same order, so that they agree bit for bit:
// portable scalar code, and AVX2 (all four at once), chosen at run time on x86-64.
#pragma once

#include "core/orientation.h"

#include <cmath>

#if defined(__x86_64__) || defined(_M_X64)
#define TETPROBE_X86_64 1
#include <immintrin.h>
#endif

namespace tetprobe {

struct Orientations {
    double D[4];
    double bound;
};

// 6 products of the largest |differences|, with room for the rounding of that bound itself.
constexpr double kOrient3dBoundScale = 6.000001 * kOrient3dErrorFactor;

struct ScalarOrientations {
    static inline double larger(double a, double b) { return a > b ? a : b; }
    static inline double det(double xi, double xj, double xl, double yi, double yj, double yl, double zi, double zj,
                             double zl) {
        return (xi * (yj * zl - yl * zj) - xj * (yi * zl - yl * zi)) + xl * (yi * zj - yj * zi);
    }
    // P: the four vertices (3 floats each, readable as 4: see the AVX2 version); q: the query.
    static inline Orientations of(const float* const P[4], const float q[3]) {
        double x[4], y[4], z[4];
        for (int i = 0; i < 4; ++i) {
            x[i] = double(P[i][0]) - double(q[0]);
            y[i] = double(P[i][1]) - double(q[1]);
            z[i] = double(P[i][2]) - double(q[2]);
        }
        Orientations o;
        o.D[0] = det(x[1], x[2], x[3], y[1], y[2], y[3], z[1], z[2], z[3]);
        o.D[1] = -det(x[0], x[2], x[3], y[0], y[2], y[3], z[0], z[2], z[3]);
        o.D[2] = det(x[0], x[1], x[3], y[0], y[1], y[3], z[0], z[1], z[3]);
        o.D[3] = -det(x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2]);
        const double mx = larger(larger(std::fabs(x[0]), std::fabs(x[2])), larger(std::fabs(x[1]), std::fabs(x[3])));
        const double my = larger(larger(std::fabs(y[0]), std::fabs(y[2])), larger(std::fabs(y[1]), std::fabs(y[3])));
        const double mz = larger(larger(std::fabs(z[0]), std::fabs(z[2])), larger(std::fabs(z[1]), std::fabs(z[3])));
        o.bound = kOrient3dBoundScale * ((mx * my) * mz);
        return o;
    }
    // Every D certainly positive: the filter decides that the cell holds the query.
    static inline bool all_above_bound(const Orientations& o) {
        return (o.D[0] > o.bound) & (o.D[1] > o.bound) & (o.D[2] > o.bound) & (o.D[3] > o.bound);
    }
};

#ifdef TETPROBE_X86_64
struct Avx2Orientations {
    // max over lanes of |v| as max(max(l0, l2), max(l1, l3)): the scalar order (max is exact anyway).
    __attribute__((target("avx2"))) static inline double largest_magnitude(__m256d v) {
        const __m256d a = _mm256_and_pd(v, _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffll)));
        const __m256d pair = _mm256_max_pd(a, _mm256_permute4x64_pd(a, _MM_SHUFFLE(1, 0, 3, 2)));
        return _mm256_cvtsd_f64(_mm256_max_pd(pair, _mm256_permute_pd(pair, 5)));
    }

    // Reads 16 bytes at each vertex (its 3 floats and 4 bytes after them, which the store guarantees
    // readable: the positions section is followed by the SH section, decoded positions by a spare float).
    __attribute__((target("avx2"))) static inline Orientations of(const float* const P[4], const float q[3]) {
        __m128 p0 = _mm_loadu_ps(P[0]), p1 = _mm_loadu_ps(P[1]), p2 = _mm_loadu_ps(P[2]), p3 = _mm_loadu_ps(P[3]);
        _MM_TRANSPOSE4_PS(p0, p1, p2, p3);
        const __m256d x = _mm256_sub_pd(_mm256_cvtps_pd(p0), _mm256_set1_pd(q[0]));
        const __m256d y = _mm256_sub_pd(_mm256_cvtps_pd(p1), _mm256_set1_pd(q[1]));
        const __m256d z = _mm256_sub_pd(_mm256_cvtps_pd(p2), _mm256_set1_pd(q[2]));
        // Lane k holds (i, j, l) = the vertices other than k: (1,2,3), (0,2,3), (0,1,3), (0,1,2).
#define TP_I(v) _mm256_permute4x64_pd(v, _MM_SHUFFLE(0, 0, 0, 1))
#define TP_J(v) _mm256_permute4x64_pd(v, _MM_SHUFFLE(1, 1, 2, 2))
#define TP_L(v) _mm256_permute4x64_pd(v, _MM_SHUFFLE(2, 3, 3, 3))
        const __m256d xi = TP_I(x), xj = TP_J(x), xl = TP_L(x);
        const __m256d yi = TP_I(y), yj = TP_J(y), yl = TP_L(y);
        const __m256d zi = TP_I(z), zj = TP_J(z), zl = TP_L(z);
#undef TP_I
#undef TP_J
#undef TP_L
        const __m256d t1 = _mm256_sub_pd(_mm256_mul_pd(yj, zl), _mm256_mul_pd(yl, zj));
        const __m256d t2 = _mm256_sub_pd(_mm256_mul_pd(yi, zl), _mm256_mul_pd(yl, zi));
        const __m256d t3 = _mm256_sub_pd(_mm256_mul_pd(yi, zj), _mm256_mul_pd(yj, zi));
        const __m256d det =
            _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(xi, t1), _mm256_mul_pd(xj, t2)), _mm256_mul_pd(xl, t3));
        // Negating lanes 1 and 3 flips their sign bits: exact, as the scalar unary minus.
        const __m256d D = _mm256_xor_pd(det, _mm256_set_pd(-0.0, 0.0, -0.0, 0.0));
        Orientations o;
        _mm256_storeu_pd(o.D, D);
        const double mx = largest_magnitude(x), my = largest_magnitude(y), mz = largest_magnitude(z);
        o.bound = kOrient3dBoundScale * ((mx * my) * mz);
        return o;
    }
    // ScalarOrientations::all_above_bound in one compare of the four (the same > on the same values).
    __attribute__((target("avx2"))) static inline bool all_above_bound(const Orientations& o) {
        return _mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(o.D), _mm256_set1_pd(o.bound), _CMP_GT_OQ)) == 15;
    }
};

inline bool cpu_has_avx2() { return __builtin_cpu_supports("avx2"); }
#else
inline bool cpu_has_avx2() { return false; }
#endif

}  // namespace tetprobe
