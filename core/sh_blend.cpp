#include "core/sh_blend.h"

#include "core/half.h"
#include "core/sh_encoding.h"

#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace tetprobe {

namespace {

inline float half_at(const uint8_t* record, int index) {
    uint16_t h;
    std::memcpy(&h, record + 2 * index, sizeof h);
    return half_to_float(h);
}

// ---- portable kernels

void blend_half_portable(const uint8_t* const records[4], const float weights[4], float out[27]) {
    const uint16_t* sh[4];
    for (int k = 0; k < 4; ++k) sh[k] = reinterpret_cast<const uint16_t*>(records[k]);
    blend_sh_halves_scalar(sh, weights, out);
}

void blend_half_l1_portable(const uint8_t* const records[4], const float weights[4], float out[27]) {
    for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < 4; ++i) {
            float sum = weights[0] * half_at(records[0], 4 * c + i);
            for (int k = 1; k < 4; ++k) sum = sum + weights[k] * half_at(records[k], 4 * c + i);
            out[9 * c + i] = sum;
        }
        for (int i = 4; i < 9; ++i) out[9 * c + i] = 0.0f;
    }
}

// coefficients: 9 or 4 per channel (the bytes of a channel are coefficients - 1).
template <int kCoefficients>
void blend_unorm8_portable(const uint8_t* const records[4], const float weights[4], float out[27]) {
    constexpr int kBytes = kCoefficients - 1;
    for (int c = 0; c < 3; ++c) {
        float a[4];
        for (int k = 0; k < 4; ++k) a[k] = weights[k] * half_at(records[k], c);
        out[9 * c] = ((a[0] + a[1]) + a[2]) + a[3];
        for (int i = 1; i < kCoefficients; ++i) {
            const int at = 6 + c * kBytes + (i - 1);
            float sum = a[0] * float(int32_t(records[0][at]) - kUnorm8Zero[i]);
            for (int k = 1; k < 4; ++k) sum = sum + a[k] * float(int32_t(records[k][at]) - kUnorm8Zero[i]);
            out[9 * c + i] = kUnorm8Step[i] * sum;
        }
        for (int i = kCoefficients; i < 9; ++i) out[9 * c + i] = 0.0f;
    }
}

#if defined(__x86_64__)

#define TP_SIMD __attribute__((target("avx2,f16c,fma")))

void blend_half_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    const uint16_t* sh[4];
    for (int k = 0; k < 4; ++k) sh[k] = reinterpret_cast<const uint16_t*>(records[k]);
    blend_sh_halves(sh, weights, out);
}

// Four halves at record + 2 * index, without reading past them.
TP_SIMD inline __m128 load_4_halves(const uint8_t* record, int index) {
    uint64_t bits;
    std::memcpy(&bits, record + 2 * index, sizeof bits);
    return _mm_cvtph_ps(_mm_cvtsi64_si128(static_cast<long long>(bits)));
}

// The three L0 halves of a record in lanes 0..2, lane 3 zero.
TP_SIMD inline __m128 load_l0(const uint8_t* record) {
    uint64_t bits = 0;
    std::memcpy(&bits, record, 6);
    return _mm_cvtph_ps(_mm_cvtsi64_si128(static_cast<long long>(bits)));
}

TP_SIMD void blend_half_l1_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    __m128 sum[3];
    for (int c = 0; c < 3; ++c) {
        sum[c] = _mm_mul_ps(_mm_set1_ps(weights[0]), load_4_halves(records[0], 4 * c));
        for (int k = 1; k < 4; ++k)
            sum[c] = _mm_add_ps(sum[c], _mm_mul_ps(_mm_set1_ps(weights[k]), load_4_halves(records[k], 4 * c)));
    }
    const __m256 zero = _mm256_setzero_ps();
    _mm256_storeu_ps(out + 1, zero);
    _mm256_storeu_ps(out + 10, zero);
    _mm256_storeu_ps(out + 19, zero);
    for (int c = 0; c < 3; ++c) _mm_storeu_ps(out + 9 * c, sum[c]);
}

// a[k][c] = weights[k] * L0 of channel c of record k; returns the blended L0s (lanes 0..2).
TP_SIMD inline __m128 weigh_l0(const uint8_t* const records[4], const float weights[4], float a[4][4]) {
    __m128 sum = _mm_setzero_ps();
    for (int k = 0; k < 4; ++k) {
        const __m128 ak = _mm_mul_ps(_mm_set1_ps(weights[k]), load_l0(records[k]));
        _mm_storeu_ps(a[k], ak);
        sum = k == 0 ? ak : _mm_add_ps(sum, ak);
    }
    return sum;
}

TP_SIMD void blend_unorm8_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    float a[4][4], l0[4];
    _mm_storeu_ps(l0, weigh_l0(records, weights, a));
    const __m256i zero = _mm256_setr_epi32(kUnorm8Zero[1], kUnorm8Zero[2], kUnorm8Zero[3], kUnorm8Zero[4],
                                           kUnorm8Zero[5], kUnorm8Zero[6], kUnorm8Zero[7], kUnorm8Zero[8]);
    const __m256 step = _mm256_loadu_ps(kUnorm8Step + 1);
    for (int c = 0; c < 3; ++c) {
        __m256 sum = _mm256_setzero_ps();
        for (int k = 0; k < 4; ++k) {
            const __m128i bytes = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(records[k] + 6 + 8 * c));
            const __m256 d = _mm256_cvtepi32_ps(_mm256_sub_epi32(_mm256_cvtepu8_epi32(bytes), zero));
            const __m256 product = _mm256_mul_ps(_mm256_set1_ps(a[k][c]), d);
            sum = k == 0 ? product : _mm256_add_ps(sum, product);
        }
        _mm256_storeu_ps(out + 9 * c + 1, _mm256_mul_ps(step, sum));
        out[9 * c] = l0[c];
    }
}

// Three bytes as the low lanes of four 32-bit integers (lane 3 zero), without reading past them.
TP_SIMD inline __m128i load_3_bytes(const uint8_t* at) {
    const uint32_t bits = uint32_t(at[0]) | (uint32_t(at[1]) << 8) | (uint32_t(at[2]) << 16);
    return _mm_cvtepu8_epi32(_mm_cvtsi32_si128(int(bits)));
}

TP_SIMD void blend_unorm8_l1_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    float a[4][4], l0[4];
    _mm_storeu_ps(l0, weigh_l0(records, weights, a));
    const __m128i zero = _mm_setr_epi32(kUnorm8Zero[1], kUnorm8Zero[2], kUnorm8Zero[3], 0);
    const __m128 step = _mm_setr_ps(kUnorm8Step[1], kUnorm8Step[2], kUnorm8Step[3], 0.0f);
    const __m256 zeros = _mm256_setzero_ps();
    _mm256_storeu_ps(out + 1, zeros);
    _mm256_storeu_ps(out + 10, zeros);
    _mm256_storeu_ps(out + 19, zeros);
    for (int c = 0; c < 3; ++c) {
        __m128 sum = _mm_setzero_ps();
        for (int k = 0; k < 4; ++k) {
            const __m128 d = _mm_cvtepi32_ps(_mm_sub_epi32(load_3_bytes(records[k] + 6 + 3 * c), zero));
            const __m128 product = _mm_mul_ps(_mm_set1_ps(a[k][c]), d);
            sum = k == 0 ? product : _mm_add_ps(sum, product);
        }
        float lanes[4];
        _mm_storeu_ps(lanes, _mm_mul_ps(step, sum));
        out[9 * c] = l0[c];
        for (int i = 0; i < 3; ++i) out[9 * c + 1 + i] = lanes[i];
    }
}

#undef TP_SIMD

#endif

}  // namespace

ShBlendFunction sh_blend_function_portable(ShEncoding encoding) {
    switch (encoding) {
        case kShHalfL1: return blend_half_l1_portable;
        case kShUnorm8: return blend_unorm8_portable<9>;
        case kShUnorm8L1: return blend_unorm8_portable<4>;
        default: return blend_half_portable;
    }
}

ShBlendFunction sh_blend_function(ShEncoding encoding) {
#if defined(__x86_64__)
    if (half_simd_available()) {
        switch (encoding) {
            case kShHalfL1: return blend_half_l1_simd;
            case kShUnorm8: return blend_unorm8_simd;
            case kShUnorm8L1: return blend_unorm8_l1_simd;
            default: return blend_half_simd;
        }
    }
#endif
    return sh_blend_function_portable(encoding);
}

}  // namespace tetprobe
