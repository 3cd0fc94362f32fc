#include "trilinear_blend.h"

#include "apv_sh_encoding.h"

#include "core/half.h"

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace bench {

namespace {

// Per ratio coefficient k = 1..8: value = lo + q * step.
struct ApvScale {
    float lo[8], step[8];
    ApvScale() {
        for (int k = 1; k < 9; ++k) {
            float a, b;
            apv_ratio_range(k, &a, &b);
            lo[k - 1] = a, step[k - 1] = (b - a) / 255.0f;
        }
    }
};
const ApvScale kApvScale;

void corner_weights(const float frac[3], float w[8]) {
    const float x[2] = {1.0f - frac[0], frac[0]}, y[2] = {1.0f - frac[1], frac[1]}, z[2] = {1.0f - frac[2], frac[2]};
    for (int c = 0; c < 8; ++c) w[c] = x[c & 1] * y[(c >> 1) & 1] * z[c >> 2];
}

}  // namespace

void trilinear_halves_scalar(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    float w[8];
    corner_weights(frac, w);
    for (int i = 0; i < 27; ++i) out[i] = 0;
    for (int c = 0; c < 8; ++c)
        for (int i = 0; i < 27; ++i) {
            uint16_t h;
            std::memcpy(&h, base + offsets[c] + 2 * size_t(i), 2);
            out[i] += w[c] * tetprobe::half_to_float(h);
        }
}

void trilinear_apv_scalar(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    float w[8];
    corner_weights(frac, w);
    for (int i = 0; i < 27; ++i) out[i] = 0;
    for (int c = 0; c < 8; ++c) {
        const uint8_t* r = base + offsets[c];
        for (int ch = 0; ch < 3; ++ch) {
            uint16_t h;
            std::memcpy(&h, r + 2 * ch, 2);
            const float l0 = tetprobe::half_to_float(h), s = w[c] * l0;
            out[9 * ch] += w[c] * l0;
            for (int j = 0; j < 8; ++j) out[9 * ch + 1 + j] += s * (kApvScale.lo[j] + float(r[8 + 8 * ch + j]) * kApvScale.step[j]);
        }
    }
}

#if defined(__x86_64__)

namespace {

#define TP_AVX __attribute__((target("avx2,f16c,fma")))

// The 8 weights as broadcast registers, built from the fractions without a trip through memory.
TP_AVX inline void broadcast_weights(const float frac[3], __m256 w[8]) {
    const __m256 fx = _mm256_set1_ps(frac[0]), fy = _mm256_set1_ps(frac[1]), fz = _mm256_set1_ps(frac[2]);
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256 gx = _mm256_sub_ps(one, fx), gy = _mm256_sub_ps(one, fy), gz = _mm256_sub_ps(one, fz);
    const __m256 y0z0 = _mm256_mul_ps(gy, gz), y1z0 = _mm256_mul_ps(fy, gz), y0z1 = _mm256_mul_ps(gy, fz),
                 y1z1 = _mm256_mul_ps(fy, fz);
    w[0] = _mm256_mul_ps(gx, y0z0), w[1] = _mm256_mul_ps(fx, y0z0);
    w[2] = _mm256_mul_ps(gx, y1z0), w[3] = _mm256_mul_ps(fx, y1z0);
    w[4] = _mm256_mul_ps(gx, y0z1), w[5] = _mm256_mul_ps(fx, y0z1);
    w[6] = _mm256_mul_ps(gx, y1z1), w[7] = _mm256_mul_ps(fx, y1z1);
}

TP_AVX void trilinear_halves_f16c(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    __m256 w[8];
    broadcast_weights(frac, w);
    __m256 a0 = _mm256_setzero_ps(), a1 = a0, a2 = a0;
    __m128 a3 = _mm_setzero_ps();
#pragma GCC unroll 8
    for (int c = 0; c < 8; ++c) {
        const __m128i* r = reinterpret_cast<const __m128i*>(base + offsets[c]);
        a0 = _mm256_fmadd_ps(w[c], _mm256_cvtph_ps(_mm_loadu_si128(r)), a0);
        a1 = _mm256_fmadd_ps(w[c], _mm256_cvtph_ps(_mm_loadu_si128(r + 1)), a1);
        a2 = _mm256_fmadd_ps(w[c], _mm256_cvtph_ps(_mm_loadu_si128(r + 2)), a2);
        a3 = _mm_fmadd_ps(_mm256_castps256_ps128(w[c]), _mm_cvtph_ps(_mm_loadl_epi64(r + 3)), a3);
    }
    _mm256_storeu_ps(out, a0);
    _mm256_storeu_ps(out + 8, a1);
    _mm256_storeu_ps(out + 16, a2);
    _mm_storel_pi(reinterpret_cast<__m64*>(out + 24), a3);
    _mm_store_ss(out + 26, _mm_movehl_ps(a3, a3));
}

TP_AVX void trilinear_apv_f16c(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    __m256 w[8];
    broadcast_weights(frac, w);
    const __m256 lo = _mm256_loadu_ps(kApvScale.lo), step = _mm256_loadu_ps(kApvScale.step);
    __m256 r0 = _mm256_setzero_ps(), r1 = r0, r2 = r0;
    __m128 l0_sum = _mm_setzero_ps();
#pragma GCC unroll 8
    for (int c = 0; c < 8; ++c) {
        const uint8_t* r = base + offsets[c];
        // L0 of the three channels (and the zero padding half) times the weight.
        const __m128 l0 = _mm_mul_ps(_mm256_castps256_ps128(w[c]), _mm_cvtph_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r))));
        l0_sum = _mm_add_ps(l0_sum, l0);
        const __m256 l0_wide = _mm256_castps128_ps256(l0);
        const __m256 s0 = _mm256_permutevar8x32_ps(l0_wide, _mm256_set1_epi32(0));
        const __m256 s1 = _mm256_permutevar8x32_ps(l0_wide, _mm256_set1_epi32(1));
        const __m256 s2 = _mm256_permutevar8x32_ps(l0_wide, _mm256_set1_epi32(2));
        const __m256 q0 = _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r + 8))));
        const __m256 q1 = _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r + 16))));
        const __m256 q2 = _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r + 24))));
        r0 = _mm256_fmadd_ps(s0, _mm256_fmadd_ps(q0, step, lo), r0);
        r1 = _mm256_fmadd_ps(s1, _mm256_fmadd_ps(q1, step, lo), r1);
        r2 = _mm256_fmadd_ps(s2, _mm256_fmadd_ps(q2, step, lo), r2);
    }
    alignas(16) float l0[4];
    _mm_store_ps(l0, l0_sum);
    _mm256_storeu_ps(out + 1, r0);
    _mm256_storeu_ps(out + 10, r1);
    _mm256_storeu_ps(out + 19, r2);
    out[0] = l0[0], out[9] = l0[1], out[18] = l0[2];
}

}  // namespace

void trilinear_halves(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    if (tetprobe::half_simd_available()) trilinear_halves_f16c(base, offsets, frac, out);
    else trilinear_halves_scalar(base, offsets, frac, out);
}

void trilinear_apv(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    if (tetprobe::half_simd_available()) trilinear_apv_f16c(base, offsets, frac, out);
    else trilinear_apv_scalar(base, offsets, frac, out);
}

#else

void trilinear_halves(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    trilinear_halves_scalar(base, offsets, frac, out);
}
void trilinear_apv(const uint8_t* base, const size_t offsets[8], const float frac[3], float out[27]) {
    trilinear_apv_scalar(base, offsets, frac, out);
}

#endif

}  // namespace bench
