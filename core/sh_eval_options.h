// SH evaluation choices: which bands are used (L2, L1, or L1 with a zonal L2 term estimated from it,
// ZH3) and a deringing window, all expressed as a rewrite of the 27 coefficients, so that a plain L2
// evaluation of the rewritten SH is the chosen evaluation. The contract is written in capi/tetprobe.h.
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
    nonnegative = 2,  // the smallest such strength that keeps every channel's irradiance non-negative
};

struct ShEvalOptions {
    ShOrder order = ShOrder::l2;
    ShWindow window = ShWindow::none;
    float window_strength = 0.0f;  // used by ShWindow::sloan only
};

// Rec. 709 luminance of linear RGB: the weights of the channels' L1 vectors in ZH3's shared axis.
constexpr double kZh3LuminanceWeights[3] = {0.2126, 0.7152, 0.0722};

// Sloan's deringing window ("Deringing Spherical Harmonics", SIGGRAPH Asia 2017 technical briefs): the
// least-squares fit to the coefficients penalised by strength times the squared Laplacian, whose
// eigenvalue on band l is -l(l+1); band 0 keeps 1 and strength 0 is the identity.
double sh_sloan_window(int band, double strength);

// Scales each band of sh by sh_sloan_window (each product rounded once to float); infinite strength
// keeps band 0 only.
void sh_apply_sloan_window(float sh[27], double strength);

// Rewrites sh for the order: L2 leaves it, L1 zeroes band 2, ZH3 replaces band 2 by the zonal term
// about the luminance-weighted L1 direction a, with per-channel coefficient z = L0 r (0.08 + 0.6 r),
// r = |L1 . a| / L0 (the paper's curve fit), written as band-2 coefficients z sqrt(4pi/5) Y2m(a), the
// addition theorem's form of z Y20(a . w). r is clamped to sqrt(3), its largest value for non-negative
// radiance (a single direction), and a channel with L0 <= 0 or SH without an L1 direction gets no term.
void sh_apply_order(float sh[27], ShOrder order);

// The strength of the Sloan window found for already ordered SH: 0 when every channel's irradiance is
// already non-negative, else the bisection (on the float strengths) between a strength that leaves a
// negative minimum and one whose proven lower bound (sh_channel_min_irradiance) is non-negative in
// every channel; the two end adjacent. Channels whose band 0 is not positive cannot be made
// non-negative by any window and are left out. Minimum irradiance is not proven monotone in strength,
// so this is the smallest at the boundary the search brackets, from strength 2^-10 doubled upwards.
// Returns infinity when no finite float strength suffices.
double sh_nonnegative_window_strength(const float ordered_sh[27]);

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
