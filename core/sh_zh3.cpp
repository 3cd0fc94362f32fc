#include "core/sh_zh3.h"

#include "core/sh.h"

#include <cmath>

namespace tetprobe {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

void sh_apply_zh3(float sh[27]) {
    // L1 vectors in (x, y, z) order: coefficients 3, 1, 2.
    double axis[3] = {0, 0, 0};
    double l1[3][3];
    for (int c = 0; c < 3; ++c) {
        l1[c][0] = sh[9 * c + 3];
        l1[c][1] = sh[9 * c + 1];
        l1[c][2] = sh[9 * c + 2];
        for (int k = 0; k < 3; ++k) axis[k] += kZh3LuminanceWeights[c] * l1[c][k];
    }
    for (int c = 0; c < 3; ++c)
        for (int i = 4; i < 9; ++i) sh[9 * c + i] = 0.0f;
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

}  // namespace tetprobe
