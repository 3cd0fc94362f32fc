// IEEE 754 binary16 ("half") conversion and the SH blend that reads half coefficients. The batch
// and blend paths use F16C/AVX2/FMA when the CPU has them (chosen once at run time), else portable
// scalar code; the scalar versions stay available so tests and the benchmark can compare them.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetprobe {

// Exact conversion of a half to float (subnormals, infinities and NaN included).
float half_to_float(uint16_t h);
// Float to half with round-to-nearest-even; overflow gives infinity, NaN stays NaN.
uint16_t float_to_half(float f);

// Converts n halves to floats (dispatched).
void halves_to_floats(const uint16_t* in, float* out, size_t n);
void halves_to_floats_scalar(const uint16_t* in, float* out, size_t n);

// out[i] = ((w0 h0 + w1 h1) + w2 h2) + w3 h3 for the 27 coefficients of four probes (dispatched; both
// paths give the same bits, see sh_blend.h). Reads exactly 27 halves from each pointer; pointers may repeat.
void blend_sh_halves(const uint16_t* const sh[4], const float weights[4], float out[27]);
void blend_sh_halves_scalar(const uint16_t* const sh[4], const float weights[4], float out[27]);
// The same on a store's SH records (sh_blend.h), each pointer read where the caller put it.
void blend_half_records_scalar(const uint8_t* const records[4], const float weights[4], float out[27]);

#if defined(__x86_64__)
// The F16C kernel itself, for a caller that has checked half_simd_available() once.
void blend_sh_halves_f16c(const uint16_t* const sh[4], const float weights[4], float out[27]);
void blend_half_records_f16c(const uint8_t* const records[4], const float weights[4], float out[27]);
#endif

// True when the dispatched paths use the F16C/AVX2/FMA code on this CPU.
bool half_simd_available();

}  // namespace tetprobe
