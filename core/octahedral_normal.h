// Hull normals in 32 bits (store_format.h): the octahedral map of the unit sphere onto [-1, 1]^2,
// 16 signed bits per coordinate, decoded to the same float vector on every platform.
#pragma once

#include <cstdint>

namespace tetprobe {

// u = max(code[0] / 32767, -1), v likewise; (u, v, 1 - |u| - |v|), folded to (+-(1 - |v|), +-(1 - |u|), z)
// where z < 0 (signs of u and v, +0 counting as positive), normalised in double, rounded to float.
void decode_normal(const int16_t code[2], float out[3]);
// The code whose decoded direction makes the smallest angle with n (non-zero), ties to the lower
// code (code[0], then code[1]). A decoded normal encodes to a code that decodes to it again.
void encode_normal(const double n[3], int16_t code[2]);
// n moved to its stored value: decode_normal(encode_normal(n)).
void quantize_normal(const double n[3], float out[3]);

}  // namespace tetprobe
