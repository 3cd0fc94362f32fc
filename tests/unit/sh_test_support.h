// Helpers shared by the SH option tests: directions over the sphere, the double reference of the
// irradiance, random SH.
#pragma once

#include "core/sh.h"
#include "core/sh_eval_options.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace tetprobe {
namespace sh_test {

constexpr double kPi = 3.14159265358979323846;

struct Direction {
    double x, y, z;
};

// N points spread evenly over the sphere (the Fibonacci lattice).
inline std::vector<Direction> fibonacci_sphere(int count) {
    std::vector<Direction> out;
    out.reserve(count);
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double z = 1.0 - (i + 0.5) * 2.0 / count;
        const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
        out.push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
    }
    return out;
}

// The contract's irradiance in double, from the float coefficients: the slow reference.
inline double irradiance(const float channel[9], const Direction& n) {
    double basis[9];
    sh_basis(n.x, n.y, n.z, basis);
    double sum = 0;
    for (int i = 0; i < 9; ++i) sum += sh_cosine_lobe_band(kShBandOfCoefficient[i]) * channel[i] * basis[i];
    return sum;
}

inline double sampled_min(const float channel[9], const std::vector<Direction>& directions) {
    double smallest = INFINITY;
    for (const Direction& d : directions) smallest = std::min(smallest, irradiance(channel, d));
    return smallest;
}

// Random SH with band 0 in [0.5, 1.5] and bands 1-2 in [-spread, spread]: often negative somewhere.
inline void random_sh(std::mt19937& rng, float sh[27], float spread = 0.6f) {
    std::uniform_real_distribution<float> l0(0.5f, 1.5f), rest(-spread, spread);
    for (int c = 0; c < 3; ++c) {
        sh[9 * c] = l0(rng);
        for (int i = 1; i < 9; ++i) sh[9 * c + i] = rest(rng);
    }
}

inline Direction unit(double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    return {x / l, y / l, z / l};
}

inline void to_float(const Direction& d, float out[3]) {
    out[0] = float(d.x);
    out[1] = float(d.y);
    out[2] = float(d.z);
}

// Largest magnitude of one channel's irradiance terms: the scale float rounding is measured against.
inline double term_scale(const float channel[9]) {
    double sum = 0;
    for (int i = 0; i < 9; ++i) sum += sh_cosine_lobe_band(kShBandOfCoefficient[i]) * std::fabs(channel[i]) * 1.1;
    return sum;
}

inline ShEvalOptions options(ShOrder order, ShWindow window = ShWindow::none, float strength = 0.0f) {
    ShEvalOptions o;
    o.order = order;
    o.window = window;
    o.window_strength = strength;
    return o;
}

}  // namespace sh_test
}  // namespace tetprobe
