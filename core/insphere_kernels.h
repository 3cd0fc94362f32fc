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
};
#endif

}  // namespace tetprobe
