#include "core/sh_encoding.h"

#include "core/half.h"

#include <cmath>
#include <cstring>

namespace tetprobe {

namespace {

constexpr float kHalfMax = 65504.0f;

uint16_t read_half(const uint8_t* at) {
    uint16_t h;
    std::memcpy(&h, at, sizeof h);
    return h;
}

void write_half(uint8_t* at, float value) {
    value = value < -kHalfMax ? -kHalfMax : (value > kHalfMax ? kHalfMax : value);
    const uint16_t h = float_to_half(value);
    std::memcpy(at, &h, sizeof h);
}

// Coefficient i of a channel whose L0 decodes to l, from code q (the blend's expression with weight 1).
inline float unorm8_value(int i, float l, int32_t q) { return kUnorm8Step[i] * (l * float(q - kUnorm8Zero[i])); }

// The code whose decoded value is nearest c (ties to the lower code).
uint8_t unorm8_code(int i, float l, float c) {
    if (l == 0.0f) return uint8_t(kUnorm8Zero[i]);
    double t = double(c) / double(l) / double(kUnorm8Step[i]) + kUnorm8Zero[i];
    t = t < 0.0 ? 0.0 : (t > 255.0 ? 255.0 : t);  // also catches a ratio that overflowed to infinity
    const int32_t guess = int32_t(std::lround(t));
    int32_t best = -1;
    double best_error = 0;
    for (int32_t q = guess - 1; q <= guess + 1; ++q) {
        if (q < 0 || q > 255) continue;
        const double error = std::fabs(double(unorm8_value(i, l, q)) - double(c));
        if (best < 0 || error < best_error) best = q, best_error = error;
    }
    return uint8_t(best);
}

}  // namespace


uint32_t sh_encoding_coefficients(ShEncoding encoding) {
    return encoding == kShHalfL1 || encoding == kShUnorm8L1 ? 4u : 9u;
}

bool sh_encoding_is_unorm8(ShEncoding encoding) { return encoding == kShUnorm8 || encoding == kShUnorm8L1; }

uint32_t sh_record_bytes(ShEncoding encoding, bool padded) {
    switch (encoding) {
        case kShHalf: return padded ? 64u : 54u;
        case kShHalfL1: return padded ? 32u : 24u;
        case kShUnorm8: return padded ? 32u : 30u;
        case kShUnorm8L1: return padded ? 16u : 15u;
        default: return 0u;
    }
}

void encode_sh_record(ShEncoding encoding, const float sh[27], uint8_t* record) {
    const uint32_t per_channel = sh_encoding_coefficients(encoding);
    if (!sh_encoding_is_unorm8(encoding)) {
        for (uint32_t c = 0; c < 3; ++c)
            for (uint32_t i = 0; i < per_channel; ++i) write_half(record + 2 * (c * per_channel + i), sh[9 * c + i]);
        return;
    }
    const uint32_t bytes = per_channel - 1;  // per channel, after the three L0 halves
    for (uint32_t c = 0; c < 3; ++c) {
        write_half(record + 2 * c, sh[9 * c]);
        const float l = half_to_float(read_half(record + 2 * c));
        for (uint32_t i = 1; i < per_channel; ++i) record[6 + c * bytes + (i - 1)] = unorm8_code(int(i), l, sh[9 * c + i]);
    }
}

void decode_sh_record(ShEncoding encoding, const uint8_t* record, float out[27]) {
    const uint32_t per_channel = sh_encoding_coefficients(encoding);
    for (int i = 0; i < 27; ++i) out[i] = 0.0f;
    if (!sh_encoding_is_unorm8(encoding)) {
        for (uint32_t c = 0; c < 3; ++c)
            for (uint32_t i = 0; i < per_channel; ++i) out[9 * c + i] = half_to_float(read_half(record + 2 * (c * per_channel + i)));
        return;
    }
    const uint32_t bytes = per_channel - 1;
    for (uint32_t c = 0; c < 3; ++c) {
        const float l = half_to_float(read_half(record + 2 * c));
        out[9 * c] = l;
        for (uint32_t i = 1; i < per_channel; ++i) out[9 * c + i] = unorm8_value(int(i), l, record[6 + c * bytes + (i - 1)]);
    }
}

int first_nonfinite_sh_half(ShEncoding encoding, const uint8_t* record) {
    const int halves = sh_encoding_is_unorm8(encoding) ? 3 : 3 * int(sh_encoding_coefficients(encoding));
    for (int i = 0; i < halves; ++i)
        if ((read_half(record + 2 * i) & 0x7C00u) == 0x7C00u) return i;
    return -1;
}

}  // namespace tetprobe
