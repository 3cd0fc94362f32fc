// TEMPORARY: a local stand-in for the SH evaluation options of the `sh` branch (tp_sh_eval_options,
// tp_sh_eval_irradiance_ex, tp_sh_apply_options, tp_sh_min_irradiance), so that the precision benchmark
// builds before that branch is merged. Unused as soon as capi/tetprobe.h declares TP_SH_ORDER_ZH3; delete
// this file after merging main. Only the benchmark includes it; it is not part of any library.
#pragma once

#include "capi/tetprobe.h"

#ifndef TP_SH_ORDER_ZH3

#include <algorithm>
#include <cmath>

#define TP_SH_ORDER_L2 0u
#define TP_SH_ORDER_L1 1u
#define TP_SH_ORDER_ZH3 2u
#define TP_SH_WINDOW_NONE 0u
#define TP_SH_WINDOW_SLOAN 1u
#define TP_SH_WINDOW_NONNEGATIVE 2u
#define TP_BENCH_SH_OPTIONS_SHIM 1

typedef struct tp_sh_eval_options {
    uint32_t struct_size;
    uint32_t order;
    uint32_t window;
    float window_strength;
} tp_sh_eval_options;

namespace sh_options_shim {

constexpr double kPi = 3.14159265358979323846;

inline void basis(const float n[3], float out[9]) {
    const float x = n[0], y = n[1], z = n[2];
    out[0] = 0.282095f;
    out[1] = 0.488603f * y, out[2] = 0.488603f * z, out[3] = 0.488603f * x;
    out[4] = 1.092548f * x * y, out[5] = 1.092548f * y * z, out[6] = 0.315392f * (3 * z * z - 1);
    out[7] = 1.092548f * x * z, out[8] = 0.546274f * (x * x - y * y);
}

// Plain L2 irradiance (the SH contract's convolution).
inline void irradiance(const float sh[27], const float n[3], float rgb[3]) {
    static const float lobe[9] = {float(kPi), float(2 * kPi / 3), float(2 * kPi / 3), float(2 * kPi / 3),
                                  float(kPi / 4), float(kPi / 4), float(kPi / 4), float(kPi / 4), float(kPi / 4)};
    float b[9];
    basis(n, b);
    for (int c = 0; c < 3; ++c) {
        float s = 0;
        for (int i = 0; i < 9; ++i) s += sh[9 * c + i] * b[i] * lobe[i];
        rgb[c] = s;
    }
}

// Band-2 coefficients from L0 and L1 (ZH3, Roughton et al. 2024): a zonal term around the luminance L1 axis.
inline void zh3_from_l1(float sh[27]) {
    float axis[3] = {0, 0, 0};
    static const float luminance[3] = {0.2126f, 0.7152f, 0.0722f};
    for (int c = 0; c < 3; ++c) {
        axis[0] += luminance[c] * sh[9 * c + 3], axis[1] += luminance[c] * sh[9 * c + 1];
        axis[2] += luminance[c] * sh[9 * c + 2];
    }
    const float length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (int c = 0; c < 3; ++c)
        for (int i = 4; i < 9; ++i) sh[9 * c + i] = 0;
    if (!(length > 0)) return;
    for (float& a : axis) a /= length;
    float axis_basis[9];
    basis(axis, axis_basis);
    for (int c = 0; c < 3; ++c) {
        const float l0 = sh[9 * c];
        if (!(l0 > 0)) continue;
        const float along = sh[9 * c + 3] * axis[0] + sh[9 * c + 1] * axis[1] + sh[9 * c + 2] * axis[2];
        const float ratio = std::fabs(along) / l0;
        const float zonal = l0 * (0.08f * ratio + 0.6f * ratio * ratio);
        // A zonal function of coefficient `zonal` around the axis, expressed in the 5 band-2 functions
        // (addition theorem: Y20 around the axis = Y20(pole) * 4pi/5 * sum_m Y2m(axis) Y2m(n)).
        const float scale = zonal * 0.630783f * float(4 * kPi / 5);
        for (int i = 4; i < 9; ++i) sh[9 * c + i] = scale * axis_basis[i];
    }
}

inline void window_bands(float sh[27], float lambda) {
    const float w1 = 1.0f / (1.0f + lambda * 4.0f), w2 = 1.0f / (1.0f + lambda * 36.0f);
    for (int c = 0; c < 3; ++c) {
        for (int i = 1; i < 4; ++i) sh[9 * c + i] *= w1;
        for (int i = 4; i < 9; ++i) sh[9 * c + i] *= w2;
    }
}

inline float min_over_sphere(const float sh[27], float min_rgb[3], float normal[3]) {
    float lowest = INFINITY;
    for (int c = 0; c < 3; ++c) min_rgb[c] = INFINITY;
    const int count = 64;
    for (int i = 0; i < count; ++i) {
        const float z = 1 - 2 * (i + 0.5f) / count, r = std::sqrt(std::max(0.0f, 1 - z * z));
        const float phi = float(i) * 2.39996323f;
        const float n[3] = {r * std::cos(phi), r * std::sin(phi), z};
        float rgb[3];
        irradiance(sh, n, rgb);
        for (int c = 0; c < 3; ++c) {
            min_rgb[c] = std::min(min_rgb[c], rgb[c]);
            if (rgb[c] < lowest) lowest = rgb[c], normal[0] = n[0], normal[1] = n[1], normal[2] = n[2];
        }
    }
    return lowest;
}

}  // namespace sh_options_shim

inline tp_status tp_sh_eval_options_init(tp_sh_eval_options* options) {
    if (!options) return TP_ERROR_INVALID_ARGUMENT;
    *options = {sizeof(tp_sh_eval_options), TP_SH_ORDER_L2, TP_SH_WINDOW_NONE, 1.0f};
    return TP_OK;
}

inline tp_status tp_sh_apply_options(float sh[27], const tp_sh_eval_options* options) {
    if (!sh || !options) return TP_ERROR_INVALID_ARGUMENT;
    if (options->order == TP_SH_ORDER_L1)
        for (int c = 0; c < 3; ++c)
            for (int i = 4; i < 9; ++i) sh[9 * c + i] = 0;
    if (options->order == TP_SH_ORDER_ZH3) sh_options_shim::zh3_from_l1(sh);
    if (options->window == TP_SH_WINDOW_SLOAN) sh_options_shim::window_bands(sh, 0.01f * options->window_strength);
    if (options->window == TP_SH_WINDOW_NONNEGATIVE) {
        float min_rgb[3], n[3];
        if (sh_options_shim::min_over_sphere(sh, min_rgb, n) < 0) {
            float lo = 0, hi = 1;
            float trial[27];
            for (int step = 0; step < 12; ++step) {
                const float mid = 0.5f * (lo + hi);
                std::copy(sh, sh + 27, trial);
                sh_options_shim::window_bands(trial, mid);
                (sh_options_shim::min_over_sphere(trial, min_rgb, n) < 0 ? lo : hi) = mid;
            }
            sh_options_shim::window_bands(sh, hi);
        }
    }
    return TP_OK;
}

inline tp_status tp_sh_eval_irradiance_ex(const float sh[27], const float normal[3], const tp_sh_eval_options* options,
                                          float rgb[3]) {
    if (!sh || !normal || !options || !rgb) return TP_ERROR_INVALID_ARGUMENT;
    float applied[27];
    std::copy(sh, sh + 27, applied);
    tp_sh_apply_options(applied, options);
    sh_options_shim::irradiance(applied, normal, rgb);
    return TP_OK;
}

inline tp_status tp_sh_min_irradiance(const float sh[27], const tp_sh_eval_options* options, float min_rgb[3],
                                      float normal[3]) {
    if (!sh || !options || !min_rgb || !normal) return TP_ERROR_INVALID_ARGUMENT;
    float applied[27];
    std::copy(sh, sh + 27, applied);
    tp_sh_apply_options(applied, options);
    sh_options_shim::min_over_sphere(applied, min_rgb, normal);
    return TP_OK;
}

#endif  // TP_SH_ORDER_ZH3
