#include "core/half.h"

#include "core/float_bits.h"

#include <cstring>

#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif

namespace tetprobe {

namespace {

// Drops the low `shift` bits of value, rounding to nearest with ties to even.
uint32_t shift_round_even(uint32_t value, uint32_t shift) {
    const uint32_t kept = value >> shift;
    const uint32_t rest = value & ((1u << shift) - 1u);
    const uint32_t halfway = 1u << (shift - 1u);
    return kept + ((rest > halfway || (rest == halfway && (kept & 1u))) ? 1u : 0u);
}

}  // namespace

float half_to_float(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16;
    const uint32_t exponent = (h >> 10) & 0x1Fu;
    const uint32_t mantissa = h & 0x3FFu;
    if (exponent == 0) {
        // Zero or subnormal: mantissa * 2^-24 is exact in float.
        const float magnitude = float(mantissa) * (1.0f / 16777216.0f);
        return bits_float(float_bits(magnitude) | sign);
    }
    if (exponent == 31) return bits_float(sign | 0x7F800000u | (mantissa << 13));
    return bits_float(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

uint16_t float_to_half(float f) {
    const uint32_t u = float_bits(f);
    const uint32_t sign = (u >> 16) & 0x8000u;
    const uint32_t exponent = (u >> 23) & 0xFFu;
    const uint32_t mantissa = u & 0x7FFFFFu;
    if (exponent == 255) {
        if (mantissa == 0) return uint16_t(sign | 0x7C00u);
        return uint16_t(sign | 0x7E00u | (mantissa >> 13));  // quiet NaN, top payload bits kept
    }
    const int unbiased = int(exponent) - 127;
    if (unbiased > 15) return uint16_t(sign | 0x7C00u);
    if (unbiased >= -14) {
        // Normal half; a rounding carry may move into the exponent (up to infinity), which is right.
        const uint32_t biased = (uint32_t(unbiased + 15) << 23) | mantissa;
        return uint16_t(sign | shift_round_even(biased, 13));
    }
    // Subnormal half (or zero): the value in units of 2^-24 is (1.mantissa) * 2^(unbiased + 1).
    const int shift = -unbiased - 1;  // 14 .. 126
    if (shift > 24) return uint16_t(sign);
    const uint32_t full = mantissa | 0x800000u;
    return uint16_t(sign | shift_round_even(full, uint32_t(shift)));
}

void halves_to_floats_scalar(const uint16_t* in, float* out, size_t n) {
    for (size_t i = 0; i < n; ++i) out[i] = half_to_float(in[i]);
}

namespace {

// The 27 halves at a probe's SH, whichever pointer type the caller holds them by.
inline const uint16_t* halves(const uint16_t* sh) { return sh; }
inline const uint16_t* halves(const uint8_t* record) { return reinterpret_cast<const uint16_t*>(record); }

// The blends read each of the four pointers where the caller put it: copying the array (a compiler
// moves pointer pairs with one 16-byte load) right after the caller stored it stalls store
// forwarding, about 15 ns a query.
template <class Pointer>
inline void blend_scalar(const Pointer* const sh, const float weights[4], float out[27]) {
    for (int i = 0; i < 27; ++i) {
        float sum = weights[0] * half_to_float(halves(sh[0])[i]);
        for (int k = 1; k < 4; ++k) sum = sum + weights[k] * half_to_float(halves(sh[k])[i]);
        out[i] = sum;
    }
}

}  // namespace

void blend_sh_halves_scalar(const uint16_t* const sh[4], const float weights[4], float out[27]) {
    blend_scalar(sh, weights, out);
}

void blend_half_records_scalar(const uint8_t* const records[4], const float weights[4], float out[27]) {
    blend_scalar(records, weights, out);
}

#if defined(__x86_64__)

namespace {

__attribute__((target("avx2,f16c,fma"))) void halves_to_floats_f16c(const uint16_t* in, float* out, size_t n) {
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        const __m128i h = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i));
        _mm256_storeu_ps(out + i, _mm256_cvtph_ps(h));
    }
    for (; i < n; ++i) out[i] = half_to_float(in[i]);
}

// The last 3 of a probe's 27 halves, loaded without reading past them (assembled in a register:
// a narrow copy into memory followed by a wide load would stall store forwarding).
__attribute__((target("avx2,f16c,fma"))) __m128 load_sh_tail(const uint16_t* sh) {
    const uint64_t bits = uint64_t(sh[24]) | (uint64_t(sh[25]) << 16) | (uint64_t(sh[26]) << 32);
    return _mm_cvtph_ps(_mm_cvtsi64_si128(static_cast<long long>(bits)));
}

__attribute__((target("avx2,f16c,fma"))) __m256 load_sh_chunk(const uint16_t* sh, int chunk) {
    return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(sh + 8 * chunk)));
}


bool cpu_has_f16c_avx2_fma() {
    __builtin_cpu_init();
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
    const bool f16c = (ecx >> 29) & 1u;
    return f16c && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

}  // namespace

namespace {

template <class Pointer>
__attribute__((target("avx2,f16c,fma"))) inline void blend_f16c(const Pointer* const sh, const float weights[4],
                                                                 float out[27]) {
    const __m256 w0 = _mm256_set1_ps(weights[0]);
    const __m256 w1 = _mm256_set1_ps(weights[1]);
    const __m256 w2 = _mm256_set1_ps(weights[2]);
    const __m256 w3 = _mm256_set1_ps(weights[3]);
    for (int chunk = 0; chunk < 3; ++chunk) {
        // Products then sums, no fused multiply-add: the portable kernel's rounding, bit for bit.
        __m256 sum = _mm256_mul_ps(w0, load_sh_chunk(halves(sh[0]), chunk));
        sum = _mm256_add_ps(sum, _mm256_mul_ps(w1, load_sh_chunk(halves(sh[1]), chunk)));
        sum = _mm256_add_ps(sum, _mm256_mul_ps(w2, load_sh_chunk(halves(sh[2]), chunk)));
        sum = _mm256_add_ps(sum, _mm256_mul_ps(w3, load_sh_chunk(halves(sh[3]), chunk)));
        _mm256_storeu_ps(out + 8 * chunk, sum);
    }
    __m128 tail = _mm_mul_ps(_mm256_castps256_ps128(w0), load_sh_tail(halves(sh[0])));
    tail = _mm_add_ps(tail, _mm_mul_ps(_mm256_castps256_ps128(w1), load_sh_tail(halves(sh[1]))));
    tail = _mm_add_ps(tail, _mm_mul_ps(_mm256_castps256_ps128(w2), load_sh_tail(halves(sh[2]))));
    tail = _mm_add_ps(tail, _mm_mul_ps(_mm256_castps256_ps128(w3), load_sh_tail(halves(sh[3]))));
    _mm_storel_pi(reinterpret_cast<__m64*>(out + 24), tail);
    _mm_store_ss(out + 26, _mm_movehl_ps(tail, tail));
}

}  // namespace

__attribute__((target("avx2,f16c,fma"))) void blend_sh_halves_f16c(const uint16_t* const sh[4], const float weights[4],
                                                                    float out[27]) {
    blend_f16c(sh, weights, out);
}

__attribute__((target("avx2,f16c,fma"))) void blend_half_records_f16c(const uint8_t* const records[4],
                                                                       const float weights[4], float out[27]) {
    blend_f16c(records, weights, out);
}

bool half_simd_available() {
    static const bool available = cpu_has_f16c_avx2_fma();
    return available;
}

void halves_to_floats(const uint16_t* in, float* out, size_t n) {
    if (half_simd_available())
        halves_to_floats_f16c(in, out, n);
    else
        halves_to_floats_scalar(in, out, n);
}

void blend_sh_halves(const uint16_t* const sh[4], const float weights[4], float out[27]) {
    if (half_simd_available())
        blend_sh_halves_f16c(sh, weights, out);
    else
        blend_sh_halves_scalar(sh, weights, out);
}

#else

bool half_simd_available() { return false; }

void halves_to_floats(const uint16_t* in, float* out, size_t n) { halves_to_floats_scalar(in, out, n); }

void blend_sh_halves(const uint16_t* const sh[4], const float weights[4], float out[27]) {
    blend_sh_halves_scalar(sh, weights, out);
}

#endif

}  // namespace tetprobe
