// The in-sphere filter (insphere.h) as the Delaunay builders call it, in two implementations with the
// same operations in the same order, so that they agree bit for bit: portable scalar code, and AVX2
// (the four points' differences side by side), chosen at run time on x86-64 like the walk's
// orientation kernels (tetrahedron_orientations.h). Each reads 16 bytes at every point: its three
// floats and four readable bytes after them.
#pragma once

#include "core/insphere.h"
#include "core/tetrahedron_orientations.h"

namespace tetprobe {

struct ScalarInsphere {
    // P: a, b, c, d (a positively oriented tetrahedron) and e; the sign as insphere_filter's.
    __attribute__((always_inline)) static inline bool filter(const float* const P[5], int* sign) {
        return insphere_filter(P[0], P[1], P[2], P[3], P[4], sign);
    }
    // Four cells against one point e: bit k of *inside when e is inside cell k's sphere, of *outside
    // when outside (or the filter's sign is 0); neither when the filter cannot tell.
    __attribute__((always_inline)) static inline void filter4(const float* const cells[4][4], const float* e,
                                                              unsigned* inside, unsigned* outside) {
        unsigned in = 0, out = 0;
        for (unsigned k = 0; k < 4; ++k) {
            int sign;
            if (insphere_filter(cells[k][0], cells[k][1], cells[k][2], cells[k][3], e, &sign)) {
                in |= unsigned(sign > 0) << k;
                out |= unsigned(sign <= 0) << k;
            }
        }
        *inside = in, *outside = out;
    }
};

#ifdef TETPROBE_X86_64
struct Avx2Insphere {
    // Lane i of X, Y, Z holds point i's difference from e; rotations pair the points as the scalar
    // expressions do: rot1 = (b, c, d, a), rot2 = (c, d, a, b).
    __attribute__((target("avx2"), always_inline)) static inline bool filter(const float* const P[5], int* sign) {
        __m128 p0 = _mm_loadu_ps(P[0]), p1 = _mm_loadu_ps(P[1]), p2 = _mm_loadu_ps(P[2]), p3 = _mm_loadu_ps(P[3]);
        _MM_TRANSPOSE4_PS(p0, p1, p2, p3);
        const __m256d X = _mm256_sub_pd(_mm256_cvtps_pd(p0), _mm256_set1_pd(P[4][0]));
        const __m256d Y = _mm256_sub_pd(_mm256_cvtps_pd(p1), _mm256_set1_pd(P[4][1]));
        const __m256d Z = _mm256_sub_pd(_mm256_cvtps_pd(p2), _mm256_set1_pd(P[4][2]));
#define TP_ROT1(v) _mm256_permute4x64_pd(v, _MM_SHUFFLE(0, 3, 2, 1))
#define TP_ROT2(v) _mm256_permute4x64_pd(v, _MM_SHUFFLE(1, 0, 3, 2))
        // (ab, bc, cd, da) and (ac, bd, -ac, -bd): x_i y_j - x_j y_i.
        const __m256d M1 = _mm256_sub_pd(_mm256_mul_pd(X, TP_ROT1(Y)), _mm256_mul_pd(TP_ROT1(X), Y));
        const __m256d M2 = _mm256_sub_pd(_mm256_mul_pd(X, TP_ROT2(Y)), _mm256_mul_pd(TP_ROT2(X), Y));
        // (abc, bcd, cda, dab): z_i m1_{i+1} - z_{i+1} m2_i + z_{i+2} m1_i.
        const __m256d C = _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(Z, TP_ROT1(M1)), _mm256_mul_pd(TP_ROT1(Z), M2)),
                                        _mm256_mul_pd(TP_ROT2(Z), M1));
        const __m256d L = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(X, X), _mm256_mul_pd(Y, Y)), _mm256_mul_pd(Z, Z));
        // (alift bcd, blift cda, clift dab, dlift abc).
        const __m256d Q = _mm256_mul_pd(L, TP_ROT1(C));
#undef TP_ROT1
#undef TP_ROT2
        alignas(32) double q[4], lift[4];
        _mm256_store_pd(q, Q);
        _mm256_store_pd(lift, L);
        const double det = (q[3] - q[2]) + (q[1] - q[0]);
        const double x = Avx2Orientations::largest_magnitude(X), y = Avx2Orientations::largest_magnitude(Y),
                     z = Avx2Orientations::largest_magnitude(Z);
        const double permanent_bound = 6 * (x * y * z) * ((lift[0] + lift[1]) + (lift[2] + lift[3]));
        const double bound = (kInsphereErrorFactor * (1 + 0x1p-40)) * permanent_bound;
        if (det > bound) return *sign = -1, true;
        if (-det > bound) return *sign = 1, true;
        if (permanent_bound == 0) return *sign = 0, true;
        return false;
    }

    // filter4 of ScalarInsphere with one cell per lane: insphere_filter's operations in its order,
    // so each lane decides exactly as insphere_filter does, under its proven bound. Four independent
    // cells at once and no branch: the cavity search tests a cell's neighbours together instead of
    // waiting on each test's latency and on a mispredicted sign.
    __attribute__((target("avx2"), always_inline)) static inline void filter4(const float* const cells[4][4],
                                                                             const float* e, unsigned* inside,
                                                                             unsigned* outside) {
        const __m256d ex = _mm256_set1_pd(e[0]), ey = _mm256_set1_pd(e[1]), ez = _mm256_set1_pd(e[2]);
        __m256d X[4], Y[4], Z[4];  // slot s of the four cells, relative to e
        for (int s = 0; s < 4; ++s) {
            __m128 q0 = _mm_loadu_ps(cells[0][s]), q1 = _mm_loadu_ps(cells[1][s]), q2 = _mm_loadu_ps(cells[2][s]),
                   q3 = _mm_loadu_ps(cells[3][s]);
            _MM_TRANSPOSE4_PS(q0, q1, q2, q3);
            X[s] = _mm256_sub_pd(_mm256_cvtps_pd(q0), ex);
            Y[s] = _mm256_sub_pd(_mm256_cvtps_pd(q1), ey);
            Z[s] = _mm256_sub_pd(_mm256_cvtps_pd(q2), ez);
        }
#define mul _mm256_mul_pd
#define sub _mm256_sub_pd
#define add _mm256_add_pd
        const __m256d ab = sub(mul(X[0], Y[1]), mul(X[1], Y[0])), bc = sub(mul(X[1], Y[2]), mul(X[2], Y[1]));
        const __m256d cd = sub(mul(X[2], Y[3]), mul(X[3], Y[2])), da = sub(mul(X[3], Y[0]), mul(X[0], Y[3]));
        const __m256d ac = sub(mul(X[0], Y[2]), mul(X[2], Y[0])), bd = sub(mul(X[1], Y[3]), mul(X[3], Y[1]));
        const __m256d abc = add(sub(mul(Z[0], bc), mul(Z[1], ac)), mul(Z[2], ab));
        const __m256d bcd = add(sub(mul(Z[1], cd), mul(Z[2], bd)), mul(Z[3], bc));
        const __m256d cda = add(add(mul(Z[2], da), mul(Z[3], ac)), mul(Z[0], cd));
        const __m256d dab = add(add(mul(Z[3], ab), mul(Z[0], bd)), mul(Z[1], da));
        __m256d lift[4];
        for (int s = 0; s < 4; ++s) lift[s] = add(add(mul(X[s], X[s]), mul(Y[s], Y[s])), mul(Z[s], Z[s]));
        const __m256d det = add(sub(mul(lift[3], abc), mul(lift[2], dab)), sub(mul(lift[1], cda), mul(lift[0], bcd)));
        const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffll));
        __m256d largest[3];  // per axis, the largest |difference| of the four slots
        const __m256d* axes[3] = {X, Y, Z};
        for (int a = 0; a < 3; ++a) {
            const __m256d* v = axes[a];
            const __m256d p = _mm256_and_pd(v[0], magnitude), q = _mm256_and_pd(v[1], magnitude);
            const __m256d r = _mm256_and_pd(v[2], magnitude), s = _mm256_and_pd(v[3], magnitude);
            largest[a] = _mm256_max_pd(_mm256_max_pd(q, p), _mm256_max_pd(s, r));
        }
        const __m256d x = largest[0], y = largest[1], z = largest[2];
        const __m256d permanent_bound =
            mul(mul(_mm256_set1_pd(6), mul(mul(x, y), z)), add(add(lift[0], lift[1]), add(lift[2], lift[3])));
        const __m256d bound = mul(_mm256_set1_pd(kInsphereErrorFactor * (1 + 0x1p-40)), permanent_bound);
#undef mul
#undef sub
#undef add
        const __m256d negated = _mm256_xor_pd(det, _mm256_set1_pd(-0.0));
        *inside = unsigned(_mm256_movemask_pd(_mm256_cmp_pd(negated, bound, _CMP_GT_OQ)));
        *outside = unsigned(_mm256_movemask_pd(_mm256_or_pd(_mm256_cmp_pd(det, bound, _CMP_GT_OQ),
                                                            _mm256_cmp_pd(permanent_bound, _mm256_setzero_pd(), _CMP_EQ_OQ))));
    }
};
#endif

}  // namespace tetprobe
