// The SH encodings of the store (store_format.h): the size of one probe's record, encoding 27
// floats into a record and decoding a record back. The blend that decodes while it weighs four
// records is in sh_blend.h; decode_sh_record is by definition what that blend gives with weight 1.
//
// The 8-bit encodings keep L0 of each channel as a half and store coefficient i >= 1 as its ratio to
// that L0, in 8 bits over the range a non-negative radiance can reach. Why that range: for radiance
// L(w) >= 0, c_i / c_0 = (integral of L Y_i) / (integral of L Y_00) is the mean of Y_i / Y_00 under
// the distribution proportional to L, so it lies in [min Y_i / Y_00, max Y_i / Y_00] over the sphere,
// and a delta of radiance reaches either end. With Y_00 = 1 / (2 sqrt(pi)) (capi/tetprobe.h):
//   band 1 (sqrt(3/4pi) times y, z, x):             [-sqrt(3), sqrt(3)]
//   xy, yz, xz (sqrt(15/pi) / 2 times the product), x^2 - y^2 (sqrt(15/pi) / 4 times it):
//                                                   [-sqrt(15) / 2, sqrt(15) / 2]
//   3z^2 - 1 (sqrt(5/pi) / 4 times it, from -1 to 2): [-sqrt(5) / 2, sqrt(5)]
// Code q of coefficient i means the ratio step_i * (q - zero_i), so that a ratio of 0 (ambient light)
// is exact: the symmetric ranges put zero at 128 and the ends at 1 and 255 (code 0 is one step beyond
// the range, valid but never written), Y20's range puts -sqrt(5)/2 at 0, zero at 85 and sqrt(5) at 255.
// The decoded coefficient is step_i * (L * float(q - zero_i)) in float, L the channel's decoded L0.
//
// Encoding: L0 is rounded to the nearest half (clamped to +-65504, as the half encoding does); each
// ratio c_i / L is written as the code whose decoded value (the float expression above) is nearest
// c_i, clamped to the codes 0..255. A channel whose half L0 is zero decodes to zero; one whose L0 is
// negative (not a non-negative radiance) keeps its L0 and its ratios clamped to the range.
// Bound, for a non-negative radiance with 2^-14 <= c_0 <= 65504: |decoded c_0 - c_0| <= 2^-11 c_0 (the
// half rounding) and |decoded c_i - c_i| <= c_0 (step_i / 2 + max_i / 1024), max_i the larger end of the
// range in magnitude. Why: with L the half of c_0 (|L - c_0| <= 2^-11 c_0) the ratio written is
// r = c_i / L, within max_i 2^-11 (1 + 2^-10) of the true ratio (inside the range), so clamping it to
// the range moves it no farther; the nearest code is within half a step of the clamped ratio, and
// L (half step + that distance) <= c_0 (1 + 2^-11)(step / 2 + max 2^-11 (1 + 2^-10)) plus a few float
// roundings of the decode, all below c_0 (step / 2 + max / 1024). Tested in test_sh_encoding.cpp.
#pragma once

#include "core/store_format.h"

#include <cstdint>

namespace tetprobe {

// Coefficients stored per channel: 9 (L2) or 4 (L1; band 2 reads as zero).
uint32_t sh_encoding_coefficients(ShEncoding encoding);
// True for the two 8-bit encodings (a half L0 per channel, then a byte per other coefficient).
bool sh_encoding_is_unorm8(ShEncoding encoding);
// Bytes of one probe's record: packed, or padded for the fast layout (64, 32, 32, 16).
uint32_t sh_record_bytes(ShEncoding encoding, bool padded);

// The 8-bit coefficients' codes: coefficient i (1..8) decodes to kUnorm8Step[i] * (L * (q - kUnorm8Zero[i])).
// Index 0 (L0, a half) is unused.
// Defined here (not in the .cpp) so that the blend kernels see them as constants.
namespace unorm8_range {
inline constexpr double kSqrt3 = 1.7320508075688772935;
inline constexpr double kSqrt15Half = 1.9364916731037084426;  // sqrt(15) / 2
inline constexpr double kSqrt5 = 2.2360679774997896964;
}  // namespace unorm8_range
inline constexpr float kUnorm8Step[9] = {
    0.0f,
    float(unorm8_range::kSqrt3 / 127),      float(unorm8_range::kSqrt3 / 127),      float(unorm8_range::kSqrt3 / 127),
    float(unorm8_range::kSqrt15Half / 127), float(unorm8_range::kSqrt15Half / 127), float(unorm8_range::kSqrt5 / 170),
    float(unorm8_range::kSqrt15Half / 127), float(unorm8_range::kSqrt15Half / 127)};
inline constexpr int32_t kUnorm8Zero[9] = {0, 128, 128, 128, 128, 128, 85, 128, 128};
// The larger end of each coefficient's ratio range in magnitude (sqrt(3), sqrt(15)/2, sqrt(5)).
inline constexpr double kUnorm8RatioMax[9] = {
    1.0,
    unorm8_range::kSqrt3,      unorm8_range::kSqrt3,      unorm8_range::kSqrt3,      unorm8_range::kSqrt15Half,
    unorm8_range::kSqrt15Half, unorm8_range::kSqrt5,      unorm8_range::kSqrt15Half, unorm8_range::kSqrt15Half};

// Writes one probe's 27 finite floats as a record of sh_record_bytes(encoding, false) bytes (the
// caller zeroes any padding).
void encode_sh_record(ShEncoding encoding, const float sh[27], uint8_t* record);
// The record's 27 coefficients (zero where the encoding stores none): bit for bit what
// blend_sh_records gives with weight 1 on this record (and 0 on the others), up to the sign of zero.
void decode_sh_record(ShEncoding encoding, const uint8_t* record, float out[27]);
// Index of the first half of a record that is not finite (inf or NaN), or -1.
int first_nonfinite_sh_half(ShEncoding encoding, const uint8_t* record);

}  // namespace tetprobe
