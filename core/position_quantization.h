// Quantised probe positions (store_format.h, kPositionsUnorm16): 16 bits per axis over a box [lo, hi]
// of floats, decoded to the same float on every platform (IEEE double arithmetic, then one rounding).
#pragma once

#include <cstdint>

namespace tetprobe {

constexpr uint32_t kPositionCodeMax = 65535;

// float(lo + (q / 65535) * (hi - lo)) evaluated in double, clamped to [lo, hi]: monotone in q,
// lo at 0 and (when hi - lo is exact in double, as for any box of a probe set) hi at 65535.
float decode_position(uint16_t q, float lo, float hi);
// The code whose decoded value is nearest p (ties to the lower code). A decoded value encodes to a
// code that decodes to it again.
uint16_t encode_position(float p, float lo, float hi);
// The largest gap between the decoded values of neighbouring codes (a step, (hi - lo) / 65535, to
// within a float rounding): a position moves by at most half of it when quantised.
double position_max_gap(float lo, float hi);
// p moved to its quantised value: decode_position(encode_position(p, lo, hi), lo, hi).
inline float quantize_position(float p, float lo, float hi) { return decode_position(encode_position(p, lo, hi), lo, hi); }

}  // namespace tetprobe
