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

// Four halves at record + 2 * index, without reading past them.
TP_SIMD inline __m128 load_4_halves(const uint8_t* record, int index) {
    uint64_t bits;
    std::memcpy(&bits, record + 2 * index, sizeof bits);
    return _mm_cvtph_ps(_mm_cvtsi64_si128(static_cast<long long>(bits)));
}

// The three L0 halves of a record in lanes 0..2, lane 3 zero, assembled in a register (two narrow
// copies to memory followed by a wide load would stall store forwarding).
TP_SIMD inline __m128 load_l0(const uint8_t* record) {
    uint32_t low;
    uint16_t high;
    std::memcpy(&low, record, sizeof low);
    std::memcpy(&high, record + 4, sizeof high);
    const uint64_t bits = uint64_t(low) | (uint64_t(high) << 32);
    return _mm_cvtph_ps(_mm_cvtsi64_si128(static_cast<long long>(bits)));
}

// Lane C of v in every lane.
template <int C>
TP_SIMD inline __m256 broadcast_lane(__m128 v) {
    return _mm256_broadcastss_ps(_mm_shuffle_ps(v, v, _MM_SHUFFLE(C, C, C, C)));
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

// a[k] = weights[k] * the L0s of record k (lanes 0..2); writes the blended L0s, ((a0 + a1) + a2) + a3,
// to out[0], out[9], out[18].
TP_SIMD inline void weigh_l0(const uint8_t* const records[4], const float weights[4], __m128 a[4], float out[27]) {
    for (int k = 0; k < 4; ++k) a[k] = _mm_mul_ps(_mm_set1_ps(weights[k]), load_l0(records[k]));
    const __m128 l0 = _mm_add_ps(_mm_add_ps(_mm_add_ps(a[0], a[1]), a[2]), a[3]);
    out[0] = _mm_cvtss_f32(l0);
    out[9] = _mm_cvtss_f32(_mm_shuffle_ps(l0, l0, _MM_SHUFFLE(1, 1, 1, 1)));
    out[18] = _mm_cvtss_f32(_mm_shuffle_ps(l0, l0, _MM_SHUFFLE(2, 2, 2, 2)));
}

// The 8 codes of channel C (coefficients 1..8) minus their zeros, as floats.
template <int C>
TP_SIMD inline __m256 unorm8_offsets(const uint8_t* record, __m256i zero) {
    const __m128i bytes = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(record + 6 + 8 * C));
    return _mm256_cvtepi32_ps(_mm256_sub_epi32(_mm256_cvtepu8_epi32(bytes), zero));
}

template <int C>
TP_SIMD inline void unorm8_channel(const uint8_t* const r[4], const __m128 a[4], __m256i zero, __m256 step, float out[27]) {
    __m256 sum = _mm256_mul_ps(broadcast_lane<C>(a[0]), unorm8_offsets<C>(r[0], zero));
    sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcast_lane<C>(a[1]), unorm8_offsets<C>(r[1], zero)));
    sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcast_lane<C>(a[2]), unorm8_offsets<C>(r[2], zero)));
    sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcast_lane<C>(a[3]), unorm8_offsets<C>(r[3], zero)));
    _mm256_storeu_ps(out + 9 * C + 1, _mm256_mul_ps(step, sum));
}

TP_SIMD void blend_unorm8_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    __m128 a[4];
    weigh_l0(records, weights, a, out);
    const __m256i zero = _mm256_setr_epi32(kUnorm8Zero[1], kUnorm8Zero[2], kUnorm8Zero[3], kUnorm8Zero[4],
                                           kUnorm8Zero[5], kUnorm8Zero[6], kUnorm8Zero[7], kUnorm8Zero[8]);
    const __m256 step = _mm256_loadu_ps(kUnorm8Step + 1);
    unorm8_channel<0>(records, a, zero, step, out);
    unorm8_channel<1>(records, a, zero, step, out);
    unorm8_channel<2>(records, a, zero, step, out);
}

// The 3 codes of channel C (coefficients 1..3) minus their zeros, as floats (lane 3 zero), from a
// 15-byte record's bytes 6..14, read without going past them.
template <int C>
TP_SIMD inline __m128 unorm8_l1_offsets(const uint8_t* record, __m128i zero) {
    uint64_t bits;
    std::memcpy(&bits, record + 6, sizeof bits);  // bytes 6..13
    const uint32_t codes = C == 0   ? uint32_t(bits & 0xFFFFFFu)
                           : C == 1 ? uint32_t((bits >> 24) & 0xFFFFFFu)
                                    : uint32_t(bits >> 48) | (uint32_t(record[14]) << 16);
    return _mm_cvtepi32_ps(_mm_sub_epi32(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(int(codes))), zero));
}

template <int C>
TP_SIMD inline void unorm8_l1_channel(const uint8_t* const r[4], const __m128 a[4], __m128i zero, __m128 step, float out[27]) {
    __m128 sum = _mm_mul_ps(_mm_shuffle_ps(a[0], a[0], _MM_SHUFFLE(C, C, C, C)), unorm8_l1_offsets<C>(r[0], zero));
    sum = _mm_add_ps(sum, _mm_mul_ps(_mm_shuffle_ps(a[1], a[1], _MM_SHUFFLE(C, C, C, C)), unorm8_l1_offsets<C>(r[1], zero)));
    sum = _mm_add_ps(sum, _mm_mul_ps(_mm_shuffle_ps(a[2], a[2], _MM_SHUFFLE(C, C, C, C)), unorm8_l1_offsets<C>(r[2], zero)));
    sum = _mm_add_ps(sum, _mm_mul_ps(_mm_shuffle_ps(a[3], a[3], _MM_SHUFFLE(C, C, C, C)), unorm8_l1_offsets<C>(r[3], zero)));
    // Coefficients 1..3, and +0 for coefficient 4 (band 2 is zero; the lane's product may be -0).
    _mm_storeu_ps(out + 9 * C + 1, _mm_blend_ps(_mm_mul_ps(step, sum), _mm_setzero_ps(), 8));
}

TP_SIMD void blend_unorm8_l1_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    const __m256 zeros = _mm256_setzero_ps();
    _mm256_storeu_ps(out + 1, zeros);
    _mm256_storeu_ps(out + 10, zeros);
    _mm256_storeu_ps(out + 19, zeros);
    __m128 a[4];
    weigh_l0(records, weights, a, out);
    const __m128i zero = _mm_setr_epi32(kUnorm8Zero[1], kUnorm8Zero[2], kUnorm8Zero[3], 0);
    const __m128 step = _mm_setr_ps(kUnorm8Step[1], kUnorm8Step[2], kUnorm8Step[3], 0.0f);
    unorm8_l1_channel<0>(records, a, zero, step, out);
    unorm8_l1_channel<1>(records, a, zero, step, out);
    unorm8_l1_channel<2>(records, a, zero, step, out);
}

#undef TP_SIMD

#endif

}  // namespace

ShBlendFunction sh_blend_function_portable(ShEncoding encoding) {
    switch (encoding) {
        case kShHalfL1: return blend_half_l1_portable;
        case kShUnorm8: return blend_unorm8_portable<9>;
        case kShUnorm8L1: return blend_unorm8_portable<4>;
        default: return blend_half_records_scalar;
    }
}

ShBlendFunction sh_blend_function(ShEncoding encoding, bool simd) {
#if defined(__x86_64__)
    if (simd) {
        switch (encoding) {
            case kShHalfL1: return blend_half_l1_simd;
            case kShUnorm8: return blend_unorm8_simd;
            case kShUnorm8L1: return blend_unorm8_l1_simd;
            default: return blend_half_records_f16c;
        }
    }
#else
    (void)simd;
#endif
    return sh_blend_function_portable(encoding);
}

ShBlendFunction sh_blend_function(ShEncoding encoding) { return sh_blend_function(encoding, half_simd_available()); }

}  // namespace tetprobe
