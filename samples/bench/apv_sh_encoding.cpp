#include "apv_sh_encoding.h"

#include "core/half.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace bench {

void apv_ratio_range(int k, float* lo, float* hi) {
    const float l1 = std::sqrt(3.0f), l2 = 0.5f * std::sqrt(15.0f), l20 = std::sqrt(5.0f);
    if (k <= 3) *lo = -l1, *hi = l1;                        // L1: Y ∝ x, y, z
    else if (k == 6) *lo = -0.5f * l20, *hi = l20;          // L20 ∝ 3z^2 - 1
    else *lo = -l2, *hi = l2;                               // the other L2
}

void apv_encode(const float sh[27], uint8_t record[kApvRecordBytes]) {
    std::memset(record, 0, kApvRecordBytes);
    for (int c = 0; c < 3; ++c) {
        const uint16_t l0 = tetprobe::float_to_half(std::max(0.0f, sh[9 * c]));
        std::memcpy(record + 2 * c, &l0, 2);
        const float base = tetprobe::half_to_float(l0);  // what the decoder multiplies by
        for (int k = 1; k < 9; ++k) {
            float lo, hi;
            apv_ratio_range(k, &lo, &hi);
            const float ratio = base > 0 ? sh[9 * c + k] / base : 0.0f;
            const float t = (std::min(std::max(ratio, lo), hi) - lo) / (hi - lo);
            record[8 + 8 * c + (k - 1)] = uint8_t(std::lround(t * 255.0f));
        }
    }
}

void apv_decode(const uint8_t record[kApvRecordBytes], float sh[27]) {
    for (int c = 0; c < 3; ++c) {
        uint16_t l0;
        std::memcpy(&l0, record + 2 * c, 2);
        const float base = tetprobe::half_to_float(l0);
        sh[9 * c] = base;
        for (int k = 1; k < 9; ++k) {
            float lo, hi;
            apv_ratio_range(k, &lo, &hi);
            sh[9 * c + k] = base * (lo + float(record[8 + 8 * c + (k - 1)]) * ((hi - lo) / 255.0f));
        }
    }
}

}  // namespace bench
