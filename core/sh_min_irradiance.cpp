#include "core/sh_min_irradiance.h"

#include "core/sh.h"

#include <Eigen/Dense>

#include <cmath>

namespace tetprobe {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// One channel's irradiance as c + b.n + n^T A n on the unit sphere (3z^2 - 1 contributes to c and A).
struct IrradianceQuadratic {
    double c;
    Vector3d b;
    Matrix3d a;

    double at(const Vector3d& n) const { return c + b.dot(n) + n.dot(a * n); }
};

IrradianceQuadratic irradiance_quadratic(const float s[9]) {
    const double a0 = sh_cosine_lobe_band(0), a1 = sh_cosine_lobe_band(1), a2 = sh_cosine_lobe_band(2);
    IrradianceQuadratic q;
    q.c = a0 * kShY00 * s[0] - a2 * kShY20 * s[6];
    q.b = a1 * kShY1 * Vector3d(s[3], s[1], s[2]);
    const double xy = 0.5 * a2 * kShY2 * s[4], yz = 0.5 * a2 * kShY2 * s[5], xz = 0.5 * a2 * kShY2 * s[7];
    q.a << a2 * kShY22 * s[8], xy, xz,
           xy, -a2 * kShY22 * s[8], yz,
           xz, yz, 3.0 * a2 * kShY20 * s[6];
    return q;
}

}  // namespace

ShChannelMinimum sh_channel_min_irradiance(const float coefficients[9]) {
    const IrradianceQuadratic q = irradiance_quadratic(coefficients);
    const Eigen::SelfAdjointEigenSolver<Matrix3d> eigen(q.a);
    const Vector3d eigenvalues = eigen.eigenvalues();  // ascending
    const Matrix3d basis = eigen.eigenvectors();
    const Vector3d bp = basis.transpose() * q.b;
    const double lowest = eigenvalues[0];

    // |n(mu)|^2 with n(mu) = -(A - mu I)^-1 b / 2 grows monotonically as mu rises towards the lowest
    // eigenvalue; at mu = lowest - |b|/2 every term is at most bp_i^2 / |b|^2, so the root lies above.
    auto squared_norm = [&](double mu) {
        double sum = 0;
        for (int i = 0; i < 3; ++i) {
            const double t = bp[i] / (2.0 * (eigenvalues[i] - mu));
            sum += t * t;
        }
        return sum;
    };
    double below = lowest - 0.5 * q.b.norm(), above = lowest;
    if (below == above) below = std::nextafter(lowest, -INFINITY);
    for (int iteration = 0; iteration < 2200; ++iteration) {
        const double mid = 0.5 * (below + above);
        if (!(mid > below && mid < above)) break;
        (squared_norm(mid) < 1.0 ? below : above) = mid;
    }
    // Lagrange dual at mu < lowest: min over all of R^3 of c + mu + b.n + n^T (A - mu I) n <= E on the sphere.
    double dual = q.c + below;
    for (int i = 0; i < 3; ++i) dual -= bp[i] * bp[i] / (4.0 * (eigenvalues[i] - below));

    ShChannelMinimum best{INFINITY, dual, {0, 0, 1}};
    auto consider = [&](const Vector3d& n) {
        const double length = n.norm();
        if (!(length > 0) || !std::isfinite(length)) return;
        const Vector3d unit = n / length;
        const double value = q.at(unit);
        if (value < best.value) {
            best.value = value;
            for (int k = 0; k < 3; ++k) best.normal[k] = unit[k];
        }
    };

    Vector3d secular;
    for (int i = 0; i < 3; ++i) secular[i] = -bp[i] / (2.0 * (eigenvalues[i] - below));
    consider(basis * secular);

    // Hard case: mu = lowest; eigenvalues within rounding of it share its eigenspace, filled along basis 0.
    const double spread = 1e-12 * (std::fabs(eigenvalues[0]) + std::fabs(eigenvalues[1]) + std::fabs(eigenvalues[2]));
    Vector3d hard = Vector3d::Zero();
    for (int i = 1; i < 3; ++i)
        if (eigenvalues[i] - lowest > spread) hard[i] = -bp[i] / (2.0 * (eigenvalues[i] - lowest));
    const double rest = hard.squaredNorm();
    if (rest <= 1.0) {
        hard[0] = (bp[0] > 0 ? -1.0 : 1.0) * std::sqrt(1.0 - rest);
        consider(basis * hard);
    }
    for (int i = 0; i < 3; ++i) {
        consider(basis.col(i));
        consider(-basis.col(i));
    }
    if (best.lower_bound > best.value) best.lower_bound = best.value;
    return best;
}

void sh_min_irradiance(const float sh[27], float out_min_rgb[3], float out_normal[3]) {
    double smallest = INFINITY;
    for (int c = 0; c < 3; ++c) {
        const ShChannelMinimum m = sh_channel_min_irradiance(sh + 9 * c);
        out_min_rgb[c] = float(m.value);
        if (c == 0 || m.value < smallest) {
            smallest = m.value;
            for (int k = 0; k < 3; ++k) out_normal[k] = float(m.normal[k]);
        }
    }
}

}  // namespace tetprobe
