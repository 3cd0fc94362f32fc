// The orientations of eight queries' cells at once, structure of arrays (one query per lane): for
// the lane walk (walk_lanes.inl). Each lane's D[k], bound, filter verdict and weights are those of
// ScalarOrientations (tetrahedron_orientations.h) for its cell and query, bit for bit: the same
// operations in the same order on the same values, lane by lane (no FMA; +, -, *, / and max are
// correctly rounded, so a vector lane rounds as the scalar does).
#pragma once

#include "core/tetrahedron_orientations.h"

#include <cstdint>

namespace tetprobe {

constexpr int kLanes = 8;

// What the kernels write for the eight lanes.
struct alignas(32) LaneBlock {
    double D[4][kLanes];       // D[k][lane]
    double bound[kLanes];
    alignas(16) float weights[kLanes][4];  // float(D[k] * (1 / (D0 + D1 + D2 + D3))) where held, else unspecified
    unsigned held = 0;         // bit lane: every D above the bound (the filter decides the cell holds the query)
};

// P[lane][k]: vertex k of the lane's cell (3 floats, readable as 4: see Avx2Orientations); q[lane]: its query.
struct ScalarLaneOrientations {
    static inline void of(const float* const P[kLanes][4], const float* const q[kLanes], LaneBlock& out) {
        unsigned held = 0;
        for (int lane = 0; lane < kLanes; ++lane) {
            const Orientations o = ScalarOrientations::of(P[lane], q[lane]);
            for (int k = 0; k < 4; ++k) out.D[k][lane] = o.D[k];
            out.bound[lane] = o.bound;
            if (!ScalarOrientations::all_above_bound(o)) continue;  // weights only where read
            const double scale = 1.0 / (o.D[0] + o.D[1] + o.D[2] + o.D[3]);
            for (int k = 0; k < 4; ++k) out.weights[lane][k] = float(o.D[k] * scale);
            held |= 1u << lane;
        }
        out.held = held;
    }
};

#ifdef TETPROBE_X86_64
struct Avx2LaneOrientations {
    // The x, y, z of four vertices read 16 bytes each (as Avx2Orientations reads them), in double.
    __attribute__((target("avx2"), always_inline)) static inline void transposed(const float* a, const float* b,
                                                                                 const float* c, const float* d,
                                                                                 __m256d& x, __m256d& y, __m256d& z) {
        __m128 p0 = _mm_loadu_ps(a), p1 = _mm_loadu_ps(b), p2 = _mm_loadu_ps(c), p3 = _mm_loadu_ps(d);
        _MM_TRANSPOSE4_PS(p0, p1, p2, p3);
        x = _mm256_cvtps_pd(p0);
        y = _mm256_cvtps_pd(p1);
        z = _mm256_cvtps_pd(p2);
    }
    __attribute__((target("avx2"), always_inline)) static inline __m256d magnitude(__m256d v) {
        return _mm256_and_pd(v, _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffll)));
    }
    // ScalarOrientations::det, lane by lane.
    __attribute__((target("avx2"), always_inline)) static inline __m256d det(__m256d xi, __m256d xj, __m256d xl,
                                                                             __m256d yi, __m256d yj, __m256d yl,
                                                                             __m256d zi, __m256d zj, __m256d zl) {
        const __m256d t1 = _mm256_sub_pd(_mm256_mul_pd(yj, zl), _mm256_mul_pd(yl, zj));
        const __m256d t2 = _mm256_sub_pd(_mm256_mul_pd(yi, zl), _mm256_mul_pd(yl, zi));
        const __m256d t3 = _mm256_sub_pd(_mm256_mul_pd(yi, zj), _mm256_mul_pd(yj, zi));
        return _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(xi, t1), _mm256_mul_pd(xj, t2)), _mm256_mul_pd(xl, t3));
    }
    // Lanes 4h .. 4h + 3.
    __attribute__((target("avx2"), always_inline)) static inline unsigned half(const float* const P[kLanes][4],
                                                                               const float* const q[kLanes], int h,
                                                                               LaneBlock& out) {
        const int a = 4 * h;
        // The queries element by element (a query's 3 floats may end its buffer).
        const __m256d qx = _mm256_set_pd(q[a + 3][0], q[a + 2][0], q[a + 1][0], q[a][0]);
        const __m256d qy = _mm256_set_pd(q[a + 3][1], q[a + 2][1], q[a + 1][1], q[a][1]);
        const __m256d qz = _mm256_set_pd(q[a + 3][2], q[a + 2][2], q[a + 1][2], q[a][2]);
        __m256d x[4], y[4], z[4];
        for (int k = 0; k < 4; ++k) {
            transposed(P[a][k], P[a + 1][k], P[a + 2][k], P[a + 3][k], x[k], y[k], z[k]);
            x[k] = _mm256_sub_pd(x[k], qx);
            y[k] = _mm256_sub_pd(y[k], qy);
            z[k] = _mm256_sub_pd(z[k], qz);
        }
        const __m256d negate = _mm256_set1_pd(-0.0);
        __m256d D[4];
        D[0] = det(x[1], x[2], x[3], y[1], y[2], y[3], z[1], z[2], z[3]);
        D[1] = _mm256_xor_pd(det(x[0], x[2], x[3], y[0], y[2], y[3], z[0], z[2], z[3]), negate);  // exact, as unary minus
        D[2] = det(x[0], x[1], x[3], y[0], y[1], y[3], z[0], z[1], z[3]);
        D[3] = _mm256_xor_pd(det(x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2]), negate);
        const __m256d mx = _mm256_max_pd(_mm256_max_pd(magnitude(x[0]), magnitude(x[2])),
                                         _mm256_max_pd(magnitude(x[1]), magnitude(x[3])));
        const __m256d my = _mm256_max_pd(_mm256_max_pd(magnitude(y[0]), magnitude(y[2])),
                                         _mm256_max_pd(magnitude(y[1]), magnitude(y[3])));
        const __m256d mz = _mm256_max_pd(_mm256_max_pd(magnitude(z[0]), magnitude(z[2])),
                                         _mm256_max_pd(magnitude(z[1]), magnitude(z[3])));
        const __m256d bound = _mm256_mul_pd(_mm256_set1_pd(kOrient3dBoundScale), _mm256_mul_pd(_mm256_mul_pd(mx, my), mz));
        for (int k = 0; k < 4; ++k) _mm256_store_pd(&out.D[k][a], D[k]);
        _mm256_store_pd(&out.bound[a], bound);
        const __m256d held = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(D[0], bound, _CMP_GT_OQ), _mm256_cmp_pd(D[1], bound, _CMP_GT_OQ)),
                                           _mm256_and_pd(_mm256_cmp_pd(D[2], bound, _CMP_GT_OQ), _mm256_cmp_pd(D[3], bound, _CMP_GT_OQ)));
        // The weights, each lane's (D0 + D1) + D2) + D3 as the scalar sum, transposed to one float4 per lane. A
        // lane that is not held divides by 1 instead (its weights are never read): no division by a flat cell's
        // zero, which a caller's floating-point traps would catch.
        const __m256d one = _mm256_set1_pd(1.0);
        const __m256d sum = _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(D[0], D[1]), D[2]), D[3]);
        const __m256d scale = _mm256_div_pd(one, _mm256_blendv_pd(one, sum, held));
        __m128 w0 = _mm256_cvtpd_ps(_mm256_mul_pd(D[0], scale)), w1 = _mm256_cvtpd_ps(_mm256_mul_pd(D[1], scale));
        __m128 w2 = _mm256_cvtpd_ps(_mm256_mul_pd(D[2], scale)), w3 = _mm256_cvtpd_ps(_mm256_mul_pd(D[3], scale));
        _MM_TRANSPOSE4_PS(w0, w1, w2, w3);
        _mm_store_ps(out.weights[a], w0);
        _mm_store_ps(out.weights[a + 1], w1);
        _mm_store_ps(out.weights[a + 2], w2);
        _mm_store_ps(out.weights[a + 3], w3);
        return unsigned(_mm256_movemask_pd(held)) << a;
    }
    __attribute__((target("avx2"), always_inline)) static inline void of(const float* const P[kLanes][4],
                                                                         const float* const q[kLanes], LaneBlock& out) {
        out.held = half(P, q, 0, out) | half(P, q, 1, out);
    }
};
#endif

}  // namespace tetprobe
