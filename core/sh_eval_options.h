// SH evaluation choices: which bands are used (L2, L1, or L1 with a zonal L2 term estimated from it,
// ZH3, see sh_zh3.h) and a deringing window (sh_window.h), all expressed as a rewrite of the 27
// coefficients, so that a plain L2 evaluation of the rewritten SH is the chosen evaluation. The
// contract is written in capi/tetprobe.h.
#pragma once

#include <cstdint>

namespace tetprobe {

enum class ShOrder : uint32_t {
    l2 = 0,   // all 27 floats
    l1 = 1,   // bands 0 and 1: 12 floats
    zh3 = 2,  // L1 plus a zonal L2 term estimated from the L1 data (Roughton et al., I3D 2024)
};

enum class ShWindow : uint32_t {
    none = 0,
    sloan = 1,        // band l scaled by 1 / (1 + strength (l (l + 1))^2)
    nonnegative = 2,  // the smallest such strength that keeps every channel's float irradiance non-negative
};

struct ShEvalOptions {
    ShOrder order = ShOrder::l2;
    ShWindow window = ShWindow::none;
    float window_strength = 0.0f;  // used by ShWindow::sloan only
};

// Rewrites sh for the order: L2 leaves it, L1 zeroes band 2, ZH3 replaces band 2 (sh_apply_zh3).
void sh_apply_order(float sh[27], ShOrder order);

// Applies the order, then the window (the window sees what the order produced).
void sh_apply_eval_options(float sh[27], const ShEvalOptions& options);

// Irradiance for unit normal n under the options: bit for bit sh_eval_irradiance of the rewritten SH
// (for L1 without a window, without reading band 2).
void sh_eval_irradiance_with_options(const float sh[27], const float n[3], const ShEvalOptions& options,
                                     float out_rgb[3]);

// sh_min_irradiance of the SH rewritten under the options.
void sh_min_irradiance_with_options(const float sh[27], const ShEvalOptions& options, float out_min_rgb[3],
                                    float out_normal[3]);

}  // namespace tetprobe
