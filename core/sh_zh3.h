// ZH3's "hallucinated" zonal L2 term (Roughton, Sloan et al., "ZH3: Quadratic Zonal Harmonics", I3D
// 2024): band 2 estimated from bands 0 and 1, written as ordinary L2 coefficients.
#pragma once

namespace tetprobe {

// Rec. 709 luminance of linear RGB: the weights of the channels' L1 vectors in ZH3's shared axis.
constexpr double kZh3LuminanceWeights[3] = {0.2126, 0.7152, 0.0722};

// Replaces band 2 of sh by the zonal term about the luminance-weighted L1 direction a, with per-channel
// coefficient z = L0 r (0.08 + 0.6 r), r = |L1 . a| / L0 (the paper's curve fit), written as band-2
// coefficients z sqrt(4pi/5) Y2m(a), the addition theorem's form of z Y20(a . w). r is clamped to
// sqrt(3), its largest value for non-negative radiance (a single direction); a channel with L0 <= 0 or
// SH without an L1 direction gets no term. Band 2 of the input is not read.
void sh_apply_zh3(float sh[27]);

}  // namespace tetprobe
