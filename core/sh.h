// Real L2 spherical harmonics: the contract is written in capi/tetprobe.h. 27 floats per probe,
// channel-major [r0..r8, g0..g8, b0..b8].
#pragma once

namespace tetprobe {

constexpr int kShCoefficients = 9;
constexpr int kShFloats = 27;

// The contract's constants (capi/tetprobe.h) at full precision: sqrt(1/4pi), sqrt(3/4pi),
// sqrt(15/4pi), sqrt(5/16pi), sqrt(15/16pi).
constexpr double kShY00 = 0.28209479177387814;
constexpr double kShY1 = 0.4886025119029199;
constexpr double kShY2 = 1.0925484305920792;
constexpr double kShY20 = 0.31539156525252005;
constexpr double kShY22 = 0.5462742152960396;

// The band (0, 1 or 2) of each of the 9 coefficients.
constexpr int kShBandOfCoefficient[9] = {0, 1, 1, 1, 2, 2, 2, 2, 2};

// The 9 basis functions at unit direction (x, y, z), in the contract's order.
void sh_basis(double x, double y, double z, double out[9]);
void sh_basis(float x, float y, float z, float out[9]);

// Band factors of the clamped-cosine convolution: pi, 2pi/3, pi/4 for bands 0, 1, 2.
double sh_cosine_lobe_band(int band);

// Radiance arriving from unit direction d.
void sh_eval_radiance(const float sh[27], const float d[3], float out_rgb[3]);
// Irradiance on a surface with unit normal n.
void sh_eval_irradiance(const float sh[27], const float n[3], float out_rgb[3]);
// Irradiance from the first `bands` bands (1, 2 or 3) only: bit for bit what sh_eval_irradiance gives
// when the higher bands are zero, without reading them.
void sh_eval_irradiance_bands(const float sh[27], const float n[3], int bands, float out_rgb[3]);
// A proven bound on how far one channel's sh_eval_irradiance (in float) lies from the exact irradiance
// of the same float coefficients at n / |n|, for any float normal n with ||n| - 1| <= 2^-23 (a unit
// vector rounded to float, or normalised in double and rounded): 21 u S with u = 2^-24 and S the sum
// over coefficients of band factor * |coefficient| * the largest magnitude its basis path reaches.
double sh_irradiance_rounding_bound(const float channel[9]);
// Adds uniform radiance rgb from all directions.
void sh_add_ambient(float sh[27], const float rgb[3]);
// Adds a delta of radiance arriving from -travel_direction whose irradiance facing it is rgb.
void sh_add_directional(float sh[27], const float travel_direction[3], const float rgb[3]);

}  // namespace tetprobe
