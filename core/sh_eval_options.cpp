#include "core/sh_eval_options.h"

#include "core/sh.h"
#include "core/sh_min_irradiance.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace tetprobe {

namespace {

constexpr double kPi = 3.14159265358979323846;

void zero_band2(float sh[27]) {
    for (int c = 0; c < 3; ++c)
        for (int i = 4; i < 9; ++i) sh[9 * c + i] = 0.0f;
}

void apply_zh3(float sh[27]) {
    // L1 vectors in (x, y, z) order: coefficients 3, 1, 2.
    double axis[3] = {0, 0, 0};
    for (int c = 0; c < 3; ++c) {
        axis[0] += kZh3LuminanceWeights[c] * sh[9 * c + 3];
        axis[1] += kZh3LuminanceWeights[c] * sh[9 * c + 1];
        axis[2] += kZh3LuminanceWeights[c] * sh[9 * c + 2];
    }
    double l1[3][3];
    for (int c = 0; c < 3; ++c) {
        l1[c][0] = sh[9 * c + 3];
        l1[c][1] = sh[9 * c + 1];
        l1[c][2] = sh[9 * c + 2];
    }
    zero_band2(sh);
    const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(length > 0) || !std::isfinite(length)) return;
    for (double& v : axis) v /= length;
    double basis[9];
    sh_basis(axis[0], axis[1], axis[2], basis);
    const double addition_theorem = std::sqrt(4.0 * kPi / 5.0);
    const double largest_ratio = std::sqrt(3.0);
    for (int c = 0; c < 3; ++c) {
        const double l0 = sh[9 * c];
        if (!(l0 > 0)) continue;
        const double along = std::fabs(l1[c][0] * axis[0] + l1[c][1] * axis[1] + l1[c][2] * axis[2]);
        const double ratio = std::fmin(along / l0, largest_ratio);
        const double zonal = l0 * ratio * (0.08 + 0.6 * ratio);
        for (int i = 4; i < 9; ++i) sh[9 * c + i] = float(zonal * addition_theorem * basis[i]);
    }
}

// Whether every channel with a positive band 0 has a proven non-negative irradiance under the window.
bool windowed_nonnegative(const float ordered_sh[27], double strength) {
    float windowed[27];
    std::memcpy(windowed, ordered_sh, sizeof windowed);
    sh_apply_sloan_window(windowed, strength);
    for (int c = 0; c < 3; ++c) {
        if (!(ordered_sh[9 * c] > 0)) continue;
        if (sh_channel_min_irradiance(windowed + 9 * c).lower_bound < 0) return false;
    }
    return true;
}

uint32_t float_bits(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

float bits_float(uint32_t bits) {
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
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

void sh_apply_order(float sh[27], ShOrder order) {
    switch (order) {
        case ShOrder::l2: return;
        case ShOrder::l1: zero_band2(sh); return;
        case ShOrder::zh3: apply_zh3(sh); return;
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

void sh_apply_eval_options(float sh[27], const ShEvalOptions& options) {
    sh_apply_order(sh, options.order);
    switch (options.window) {
        case ShWindow::none: return;
        case ShWindow::sloan: sh_apply_sloan_window(sh, options.window_strength); return;
        case ShWindow::nonnegative: sh_apply_sloan_window(sh, sh_nonnegative_window_strength(sh)); return;
    }
}

void sh_eval_irradiance_with_options(const float sh[27], const float n[3], const ShEvalOptions& options,
                                     float out_rgb[3]) {
    if (options.window == ShWindow::none && options.order != ShOrder::zh3) {
        sh_eval_irradiance_bands(sh, n, options.order == ShOrder::l1 ? 2 : 3, out_rgb);
        return;
    }
    float rewritten[27];
    std::memcpy(rewritten, sh, sizeof rewritten);
    sh_apply_eval_options(rewritten, options);
    sh_eval_irradiance(rewritten, n, out_rgb);
}

void sh_min_irradiance_with_options(const float sh[27], const ShEvalOptions& options, float out_min_rgb[3],
                                    float out_normal[3]) {
    float rewritten[27];
    std::memcpy(rewritten, sh, sizeof rewritten);
    sh_apply_eval_options(rewritten, options);
    sh_min_irradiance(rewritten, out_min_rgb, out_normal);
}

}  // namespace tetprobe
