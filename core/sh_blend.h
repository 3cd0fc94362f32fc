// The blend of a query: out = sum_k weights[k] * decoded(record k) for four probes' SH records of one
// encoding (sh_encoding.h), decoding as it weighs (no decoded copy of the store is kept). Each
// encoding has a portable kernel and an F16C/AVX2 one chosen at run time; both do the same float
// operations in the same order (products, then sums from probe 0 to 3, no fused multiply-add), so
// they give the same bits, and weight 1 on one probe gives exactly that probe's decode_sh_record.
//   half:   out_i = ((w0 h0_i + w1 h1_i) + w2 h2_i) + w3 h3_i
//   unorm8: per channel a_k = w_k L_k; out_0 = ((a0 + a1) + a2) + a3;
//           out_i = step_i * (((a0 d0_i + a1 d1_i) + a2 d2_i) + a3 d3_i), d = float(q - zero_i)
// Band 2 of the L1 encodings is written as zero.
#pragma once

#include "core/store_format.h"

#include <cstdint>

namespace tetprobe {

// Reads exactly one record (sh_record_bytes(encoding, false) bytes) from each pointer; pointers may repeat.
using ShBlendFunction = void (*)(const uint8_t* const records[4], const float weights[4], float out[27]);

// The dispatched kernel of an encoding (the F16C/AVX2 one where the CPU has it, see half.h), and the
// portable one.
ShBlendFunction sh_blend_function(ShEncoding encoding);
ShBlendFunction sh_blend_function_portable(ShEncoding encoding);
// The F16C/AVX2 kernel (simd: the caller has checked half_simd_available()) or the portable one.
ShBlendFunction sh_blend_function(ShEncoding encoding, bool simd);

}  // namespace tetprobe
