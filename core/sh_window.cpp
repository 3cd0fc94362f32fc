#include "core/sh_window.h"

#include "core/float_bits.h"
#include "core/sh.h"
#include "core/sh_min_irradiance.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace tetprobe {

namespace {

// Whether every channel with a positive band 0 keeps its float irradiance provably non-negative under
// the window: the dual lower bound of the exact minimum must clear the float evaluation's rounding.
bool windowed_nonnegative(const float ordered_sh[27], double strength) {
    float windowed[27];
    std::memcpy(windowed, ordered_sh, sizeof windowed);
    sh_apply_sloan_window(windowed, strength);
    for (int c = 0; c < 3; ++c) {
        if (!(ordered_sh[9 * c] > 0)) continue;
        const float* channel = windowed + 9 * c;
        if (!(sh_channel_min_irradiance(channel).lower_bound >= sh_irradiance_rounding_bound(channel))) return false;
    }
    return true;
}

}  // namespace

double sh_sloan_window(int band, double strength) {
    if (band == 0) return 1.0;
    const double laplacian = double(band) * (band + 1);
    return 1.0 / (1.0 + strength * laplacian * laplacian);
}

void sh_apply_sloan_window(float sh[27], double strength) {
    if (strength == 0) return;
    for (int c = 0; c < 3; ++c)
        for (int i = 1; i < 9; ++i) {
            const double window = std::isinf(strength) ? 0.0 : sh_sloan_window(kShBandOfCoefficient[i], strength);
            sh[9 * c + i] = float(double(sh[9 * c + i]) * window);
        }
}

double sh_nonnegative_window_strength(const float ordered_sh[27]) {
    if (windowed_nonnegative(ordered_sh, 0.0)) return 0.0;
    // Non-negative floats order as their bit patterns, so bisecting the bits ends on adjacent floats.
    float failing = 0.0f, passing = 1.0f / 1024.0f;
    while (!windowed_nonnegative(ordered_sh, passing)) {
        failing = passing;
        if (passing > std::numeric_limits<float>::max() / 2) return INFINITY;
        passing *= 2.0f;
    }
    uint32_t low = float_bits(failing), high = float_bits(passing);
    while (high - low > 1) {
        const uint32_t mid = low + (high - low) / 2;
        (windowed_nonnegative(ordered_sh, bits_float(mid)) ? high : low) = mid;
    }
    return bits_float(high);
}

}  // namespace tetprobe
