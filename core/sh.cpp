#include "core/sh.h"

#include <cmath>

namespace tetprobe {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

// One body for both precisions: the constants are rounded to T once, then used as in the contract.
template <class T>
void sh_basis_in(T x, T y, T z, T out[9]) {
    const T c00 = T(kShY00), c1 = T(kShY1), c2 = T(kShY2), c20 = T(kShY20), c22 = T(kShY22);
    out[0] = c00;
    out[1] = c1 * y;
    out[2] = c1 * z;
    out[3] = c1 * x;
    out[4] = c2 * x * y;
    out[5] = c2 * y * z;
    out[6] = c20 * (T(3) * z * z - T(1));
    out[7] = c2 * x * z;
    out[8] = c22 * (x * x - y * y);
}

void sh_basis(double x, double y, double z, double out[9]) { sh_basis_in(x, y, z, out); }
void sh_basis(float x, float y, float z, float out[9]) { sh_basis_in(x, y, z, out); }

double sh_cosine_lobe_band(int band) {
    switch (band) {
        case 0: return kPi;
        case 1: return 2.0 * kPi / 3.0;
        case 2: return kPi / 4.0;
        default: return 0.0;
    }
}

void sh_eval_radiance(const float sh[27], const float d[3], float out_rgb[3]) {
    float basis[9];
    sh_basis(d[0], d[1], d[2], basis);
    for (int c = 0; c < 3; ++c) {
        float sum = 0.0f;
        for (int i = 0; i < 9; ++i) sum += sh[9 * c + i] * basis[i];
        out_rgb[c] = sum;
    }
}

// The first Count coefficients of each channel against the convolved basis, summed in order
// (sh_irradiance_rounding_bound counts this path's roundings: change both together).
template <int Count>
void sh_eval_irradiance_first(const float sh[27], const float n[3], float out_rgb[3]) {
    float basis[9];
    sh_basis(n[0], n[1], n[2], basis);
    for (int i = 0; i < Count; ++i) basis[i] *= float(sh_cosine_lobe_band(kShBandOfCoefficient[i]));
    for (int c = 0; c < 3; ++c) {
        float sum = 0.0f;
        for (int i = 0; i < Count; ++i) sum += sh[9 * c + i] * basis[i];
        out_rgb[c] = sum;
    }
}

void sh_eval_irradiance(const float sh[27], const float n[3], float out_rgb[3]) {
    sh_eval_irradiance_first<9>(sh, n, out_rgb);
}

void sh_eval_irradiance_bands(const float sh[27], const float n[3], int bands, float out_rgb[3]) {
    switch (bands) {
        case 1: sh_eval_irradiance_first<1>(sh, n, out_rgb); return;
        case 2: sh_eval_irradiance_first<4>(sh, n, out_rgb); return;
        default: sh_eval_irradiance_first<9>(sh, n, out_rgb); return;
    }
}

double sh_irradiance_rounding_bound(const float channel[9]) {
    // Each term's path in sh_eval_irradiance_first rounds at most 16 times: basis constant, up to three
    // operations on x, y, z (3z z - 1 and x x - y y err by at most 3u times 3z^2 + 1 and x^2 + y^2,
    // hence the factors 4 and 1 below), the multiply by the constant, band factor and its multiply,
    // the coefficient multiply and 8 additions: at most gamma_16 < 16.0001u of S. A normal of length
    // 1 + d moves each term of degree <= 2 by at most (2|d| + d^2) of it: 4.0002u of S. 21u covers
    // both, their product and the double rounding of S and of the minimum it is compared with.
    const double largest_basis[9] = {kShY00, kShY1, kShY1, kShY1, kShY2, kShY2, 4.0 * kShY20, kShY2, kShY22};
    double sum = 0;
    for (int i = 0; i < 9; ++i)
        sum += sh_cosine_lobe_band(kShBandOfCoefficient[i]) * std::fabs(double(channel[i])) * largest_basis[i];
    return 21.0 * std::ldexp(sum, -24);
}

void sh_add_ambient(float sh[27], const float rgb[3]) {
    // Uniform radiance L projects onto Y00 only: L * 4pi * Y00 = L * 2 sqrt(pi).
    const float scale = float(4.0 * kPi * kShY00);
    for (int c = 0; c < 3; ++c) sh[9 * c] += rgb[c] * scale;
}

void sh_add_directional(float sh[27], const float travel_direction[3], const float rgb[3]) {
    // A delta of radiance from w = -travel_direction whose irradiance facing it is E projects to
    // E * Y_i(w): the integral of the delta against each basis function.
    double basis[9];
    sh_basis(-double(travel_direction[0]), -double(travel_direction[1]), -double(travel_direction[2]), basis);
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 9; ++i) sh[9 * c + i] += float(double(rgb[c]) * basis[i]);
}

}  // namespace tetprobe
