#include "core/position_quantization.h"

namespace tetprobe {

float decode_position(uint16_t q, float lo, float hi) {
    const double t = double(q) / double(kPositionCodeMax);
    const float p = float(double(lo) + t * (double(hi) - double(lo)));
    return p < lo ? lo : (p > hi ? hi : p);
}

uint16_t encode_position(float p, float lo, float hi) {
    // The first code decoding to p or above (decoding is monotone), then the nearer of it and the one below.
    uint32_t first = 0, count = kPositionCodeMax + 1;
    while (count > 0) {
        const uint32_t half = count / 2;
        if (decode_position(uint16_t(first + half), lo, hi) < p) {
            first += half + 1;
            count -= half + 1;
        } else {
            count = half;
        }
    }
    if (first > kPositionCodeMax) return uint16_t(kPositionCodeMax);
    if (first == 0) return 0;
    const double above = double(decode_position(uint16_t(first), lo, hi)) - double(p);
    const double below = double(p) - double(decode_position(uint16_t(first - 1), lo, hi));
    return uint16_t(below <= above && above > 0 ? first - 1 : first);
}

double position_max_gap(float lo, float hi) {
    double gap = 0, previous = double(decode_position(0, lo, hi));
    for (uint32_t q = 1; q <= kPositionCodeMax; ++q) {
        const double value = double(decode_position(uint16_t(q), lo, hi));
        gap = value - previous > gap ? value - previous : gap;
        previous = value;
    }
    return gap;
}

}  // namespace tetprobe
