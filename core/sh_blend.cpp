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
#define TP_SIMD_INLINE __attribute__((target("avx2,f16c,fma"), always_inline)) inline

// The SIMD kernels name every intermediate (the four records, their weights and weighted L0s) as its
// own variable, never an array: arrays of vectors filled in loops went through the stack (stored
// through one register, read back through the stack pointer), and the unorm8 kernel took 2 to 10 times
// as long on the benchmark machine (AMD EPYC, Zen 4), depending on where the stack sat; without them
// it is within 1.5x of the half kernel. Each record pointer is read once, where the caller put it.

// Four halves at record + 2 * index, without reading past them.
TP_SIMD_INLINE __m128 load_4_halves(const uint8_t* record, int index) {
    return _mm_cvtph_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(record + 2 * index)));
}

// The three L0 halves of an 8-bit record in lanes 0..2, lane 3 zero (bytes 0..7 are inside every
// 8-bit record; bytes 6 and 7 are masked off).
TP_SIMD_INLINE __m128 load_l0(const uint8_t* record) {
    const __m128i bits = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(record));
    return _mm_cvtph_ps(_mm_and_si128(bits, _mm_set_epi64x(0, 0x0000FFFFFFFFFFFFll)));
}

// Lane C of v in every lane of a 256-bit vector.
template <int C>
TP_SIMD_INLINE __m256 broadcast_lane(__m128 v) {
    if (C == 0) return _mm256_broadcastss_ps(v);
    return _mm256_permutevar8x32_ps(_mm256_castps128_ps256(v), _mm256_set1_epi32(C));
}

// w * the first 8 halves of a half_l1 record (red and green), and w * its last 4 (blue).
TP_SIMD_INLINE __m256 weigh_red_green(const uint8_t* record, __m256 w) {
    return _mm256_mul_ps(w, _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(record))));
}
TP_SIMD_INLINE __m128 weigh_blue(const uint8_t* record, __m256 w) {
    return _mm_mul_ps(_mm256_castps256_ps128(w), load_4_halves(record, 8));
}

TP_SIMD void blend_half_l1_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    const uint8_t* const r0 = records[0];
    const uint8_t* const r1 = records[1];
    const uint8_t* const r2 = records[2];
    const uint8_t* const r3 = records[3];
    const __m256 w0 = _mm256_set1_ps(weights[0]), w1 = _mm256_set1_ps(weights[1]);
    const __m256 w2 = _mm256_set1_ps(weights[2]), w3 = _mm256_set1_ps(weights[3]);
    __m256 red_green = weigh_red_green(r0, w0);
    red_green = _mm256_add_ps(red_green, weigh_red_green(r1, w1));
    red_green = _mm256_add_ps(red_green, weigh_red_green(r2, w2));
    red_green = _mm256_add_ps(red_green, weigh_red_green(r3, w3));
    __m128 blue = weigh_blue(r0, w0);
    blue = _mm_add_ps(blue, weigh_blue(r1, w1));
    blue = _mm_add_ps(blue, weigh_blue(r2, w2));
    blue = _mm_add_ps(blue, weigh_blue(r3, w3));
    const __m256 zero = _mm256_setzero_ps();
    _mm256_storeu_ps(out + 1, zero);
    _mm256_storeu_ps(out + 10, zero);
    _mm256_storeu_ps(out + 19, zero);
    _mm_storeu_ps(out, _mm256_castps256_ps128(red_green));
    _mm_storeu_ps(out + 9, _mm256_extractf128_ps(red_green, 1));
    _mm_storeu_ps(out + 18, blue);
}

// The 8 codes of channel C (coefficients 1..8) minus their zeros, as floats.
template <int C>
TP_SIMD_INLINE __m256 unorm8_offsets(const uint8_t* record, __m256i zero) {
    const __m128i bytes = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(record + 6 + 8 * C));
    return _mm256_cvtepi32_ps(_mm256_sub_epi32(_mm256_cvtepu8_epi32(bytes), zero));
}

// Coefficients 1..8 of channel C: step * (((a0 d0 + a1 d1) + a2 d2) + a3 d3), a_k the weighted L0s.
template <int C>
TP_SIMD_INLINE void unorm8_channel(const uint8_t* r0, const uint8_t* r1, const uint8_t* r2, const uint8_t* r3, __m128 a0,
                                   __m128 a1, __m128 a2, __m128 a3, __m256i zero, __m256 step, float out[27]) {
    __m256 sum = _mm256_mul_ps(broadcast_lane<C>(a0), unorm8_offsets<C>(r0, zero));
    sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcast_lane<C>(a1), unorm8_offsets<C>(r1, zero)));
    sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcast_lane<C>(a2), unorm8_offsets<C>(r2, zero)));
    sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcast_lane<C>(a3), unorm8_offsets<C>(r3, zero)));
    _mm256_storeu_ps(out + 9 * C + 1, _mm256_mul_ps(step, sum));
}

// The blended L0s ((a0 + a1) + a2) + a3 to out[0], out[9], out[18].
TP_SIMD_INLINE void store_l0(__m128 a0, __m128 a1, __m128 a2, __m128 a3, float out[27]) {
    const __m128 l0 = _mm_add_ps(_mm_add_ps(_mm_add_ps(a0, a1), a2), a3);
    _mm_store_ss(out, l0);
    out[9] = _mm_cvtss_f32(_mm_movehdup_ps(l0));
    out[18] = _mm_cvtss_f32(_mm_movehl_ps(l0, l0));
}

TP_SIMD void blend_unorm8_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    const uint8_t* const r0 = records[0];
    const uint8_t* const r1 = records[1];
    const uint8_t* const r2 = records[2];
    const uint8_t* const r3 = records[3];
    const __m128 a0 = _mm_mul_ps(_mm_set1_ps(weights[0]), load_l0(r0));
    const __m128 a1 = _mm_mul_ps(_mm_set1_ps(weights[1]), load_l0(r1));
    const __m128 a2 = _mm_mul_ps(_mm_set1_ps(weights[2]), load_l0(r2));
    const __m128 a3 = _mm_mul_ps(_mm_set1_ps(weights[3]), load_l0(r3));
    const __m256i zero = _mm256_setr_epi32(kUnorm8Zero[1], kUnorm8Zero[2], kUnorm8Zero[3], kUnorm8Zero[4],
                                           kUnorm8Zero[5], kUnorm8Zero[6], kUnorm8Zero[7], kUnorm8Zero[8]);
    const __m256 step = _mm256_setr_ps(kUnorm8Step[1], kUnorm8Step[2], kUnorm8Step[3], kUnorm8Step[4],
                                       kUnorm8Step[5], kUnorm8Step[6], kUnorm8Step[7], kUnorm8Step[8]);
    store_l0(a0, a1, a2, a3, out);
    unorm8_channel<0>(r0, r1, r2, r3, a0, a1, a2, a3, zero, step, out);
    unorm8_channel<1>(r0, r1, r2, r3, a0, a1, a2, a3, zero, step, out);
    unorm8_channel<2>(r0, r1, r2, r3, a0, a1, a2, a3, zero, step, out);
}

// unorm8_l1 works on 12 lanes, [L0, c1, c2, c3] for each channel (red and green in a 256-bit vector,
// blue in a 128-bit one), so that the blend comes out in the layout of out: in each channel's L0 lane
// the "code" is a constant 1 (a zero byte minus zero -1), so the lane sums w_k L_k, exactly the L0
// blend, and its step is 1.
// Record k's terms: lane i of each channel is a_k * d_i with a_k = w_k * L_k.
TP_SIMD_INLINE void unorm8_l1_terms(const uint8_t* record, float weight, __m256& red_green, __m128& blue) {
    const __m128i low = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(record));       // bytes 0..7
    const __m128i high = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(record + 7));  // bytes 7..14
    const __m128 l0 = _mm_cvtph_ps(_mm_and_si128(low, _mm_set_epi64x(0, 0x0000FFFFFFFFFFFFll)));
    const __m128 a = _mm_mul_ps(_mm_set1_ps(weight), l0);
    // Index i < 8 is byte i, index 8 + j byte 7 + j: the codes r1..r3, g1..g3, b1..b3 are at indices
    // 6, 7, 9, 10, 11, 12, 13, 14, 15; -1 gives a zero byte.
    const __m128i bytes = _mm_unpacklo_epi64(low, high);
    const __m256i red_green_codes = _mm256_shuffle_epi8(
        _mm256_broadcastsi128_si256(bytes),
        _mm256_setr_epi8(-1, -1, -1, -1, 6, -1, -1, -1, 7, -1, -1, -1, 9, -1, -1, -1,        //
                         -1, -1, -1, -1, 10, -1, -1, -1, 11, -1, -1, -1, 12, -1, -1, -1));
    const __m128i blue_codes = _mm_shuffle_epi8(bytes, _mm_setr_epi8(-1, -1, -1, -1, 13, -1, -1, -1, 14, -1, -1, -1, 15, -1, -1, -1));
    const __m128i zero = _mm_setr_epi32(-1, kUnorm8Zero[1], kUnorm8Zero[2], kUnorm8Zero[3]);
    const __m256 red_green_d = _mm256_cvtepi32_ps(_mm256_sub_epi32(red_green_codes, _mm256_broadcastsi128_si256(zero)));
    const __m128 blue_d = _mm_cvtepi32_ps(_mm_sub_epi32(blue_codes, zero));
    const __m256 red_green_a = _mm256_permutevar8x32_ps(_mm256_castps128_ps256(a), _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1));
    red_green = _mm256_mul_ps(red_green_a, red_green_d);
    blue = _mm_mul_ps(_mm_shuffle_ps(a, a, _MM_SHUFFLE(2, 2, 2, 2)), blue_d);
}

TP_SIMD void blend_unorm8_l1_simd(const uint8_t* const records[4], const float weights[4], float out[27]) {
    __m256 red_green, red_green_k;
    __m128 blue, blue_k;
    unorm8_l1_terms(records[0], weights[0], red_green, blue);
    unorm8_l1_terms(records[1], weights[1], red_green_k, blue_k);
    red_green = _mm256_add_ps(red_green, red_green_k), blue = _mm_add_ps(blue, blue_k);
    unorm8_l1_terms(records[2], weights[2], red_green_k, blue_k);
    red_green = _mm256_add_ps(red_green, red_green_k), blue = _mm_add_ps(blue, blue_k);
    unorm8_l1_terms(records[3], weights[3], red_green_k, blue_k);
    red_green = _mm256_add_ps(red_green, red_green_k), blue = _mm_add_ps(blue, blue_k);
    const __m128 step = _mm_setr_ps(1.0f, kUnorm8Step[1], kUnorm8Step[2], kUnorm8Step[3]);
    red_green = _mm256_mul_ps(_mm256_set_m128(step, step), red_green);
    blue = _mm_mul_ps(step, blue);
    const __m256 zeros = _mm256_setzero_ps();
    _mm256_storeu_ps(out + 1, zeros);
    _mm256_storeu_ps(out + 10, zeros);
    _mm256_storeu_ps(out + 19, zeros);
    _mm_storeu_ps(out, _mm256_castps256_ps128(red_green));
    _mm_storeu_ps(out + 9, _mm256_extractf128_ps(red_green, 1));
    _mm_storeu_ps(out + 18, blue);
}

#undef TP_SIMD_INLINE
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
