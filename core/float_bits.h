// A float's IEEE bits and back, without aliasing (half conversion, bisection over floats).
#pragma once

#include <cstdint>
#include <cstring>

namespace tetprobe {

inline uint32_t float_bits(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

inline float bits_float(uint32_t bits) {
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

}  // namespace tetprobe
