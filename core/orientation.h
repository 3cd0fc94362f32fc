// Exact orientation predicates on float32 points: a double-precision filter with Shewchuk's static
// error bound, and an exact evaluation (expansion arithmetic) when the filter cannot decide. Queries
// may call them: nothing allocates, and the filtered versions are inline.
#pragma once

#include <cmath>

namespace tetprobe {

// Shewchuk's static error bound factors for determinants evaluated in double from double
// differences of the inputs (the rounding of the differences included): the sign of a computed
// determinant D is certain when |D| > factor * permanent, where permanent is the same expression
// evaluated with absolute values (of the rounded differences). eps = 2^-53.
constexpr double kOrientationEps = 0x1p-53;
constexpr double kOrient3dErrorFactor = (7.0 + 56.0 * kOrientationEps) * kOrientationEps;
constexpr double kOrient2dErrorFactor = (3.0 + 16.0 * kOrientationEps) * kOrientationEps;

// Exact sign (-1, 0, +1) of det[b - a, c - a, d - a] (rows), for float32 coordinates.
// Positive when (b-a, c-a, d-a) is right-handed; e.g. a=0, b=x, c=y, d=z gives +1.
int orient3d_exact(const float a[3], const float b[3], const float c[3], const float d[3]);
// Exact sign of det[b - a, c - a] for 2D float32 points (x, y): positive when a, b, c turn counter-
// clockwise.
int orient2d_exact(const float a[2], const float b[2], const float c[2]);

// The same determinants' values, from the exact expansion rounded to double (within an ulp or so,
// and with the exact sign): what weights are computed from where the filter could not decide, so
// that a sliver's barycentrics keep double precision too.
double orient3d_exact_value(const float a[3], const float b[3], const float c[3], const float d[3]);
double orient2d_exact_value(const float a[2], const float b[2], const float c[2]);

// The filter alone: true, with the sign in *sign, when the double evaluation decides it; false when
// only the exact evaluation can. Exposed so tests and benchmarks can see how often it falls back.
// The evaluation order follows Shewchuk's orient3d (each cofactor, then times the third difference),
// which the bound is proved for; a fused multiply-add only removes roundings from it. Nothing can
// underflow: float differences are zero or at least 2^-149 in magnitude, their triple products at
// least 2^-447, far above double's normal range limit 2^-1022; nor overflow (at most 2^129 cubed).
// So permanent == 0 means every product has an exactly zero difference in it (a double difference
// of two floats rounds to zero only when they are equal), and D is exactly zero.
inline bool orient3d_filter(const float a[3], const float b[3], const float c[3], const float d[3], int* sign) {
    const double ux = double(b[0]) - a[0], uy = double(b[1]) - a[1], uz = double(b[2]) - a[2];
    const double vx = double(c[0]) - a[0], vy = double(c[1]) - a[1], vz = double(c[2]) - a[2];
    const double wx = double(d[0]) - a[0], wy = double(d[1]) - a[1], wz = double(d[2]) - a[2];
    const double vxwy = vx * wy, wxvy = wx * vy;
    const double wxuy = wx * uy, uxwy = ux * wy;
    const double uxvy = ux * vy, vxuy = vx * uy;
    const double det = uz * (vxwy - wxvy) + vz * (wxuy - uxwy) + wz * (uxvy - vxuy);
    const double permanent = (std::fabs(vxwy) + std::fabs(wxvy)) * std::fabs(uz) +
                             (std::fabs(wxuy) + std::fabs(uxwy)) * std::fabs(vz) +
                             (std::fabs(uxvy) + std::fabs(vxuy)) * std::fabs(wz);
    const double bound = kOrient3dErrorFactor * permanent;
    if (det > bound) return *sign = 1, true;
    if (-det > bound) return *sign = -1, true;
    if (permanent == 0) return *sign = 0, true;
    return false;  // also for NaN and infinite inputs
}

// The 2D filter, like orient3d_filter (Shewchuk's orient2d, differences relative to a).
inline bool orient2d_filter(const float a[2], const float b[2], const float c[2], int* sign) {
    const double left = (double(b[0]) - a[0]) * (double(c[1]) - a[1]);
    const double right = (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
    const double det = left - right;
    const double permanent = std::fabs(left) + std::fabs(right);
    const double bound = kOrient2dErrorFactor * permanent;
    if (det > bound) return *sign = 1, true;
    if (-det > bound) return *sign = -1, true;
    if (permanent == 0) return *sign = 0, true;
    return false;
}

// The same signs as the exact versions, filtered: a double evaluation with the bound above, the
// exact one when it cannot decide.
inline int orient3d(const float a[3], const float b[3], const float c[3], const float d[3]) {
    int sign;
    return orient3d_filter(a, b, c, d, &sign) ? sign : orient3d_exact(a, b, c, d);
}

inline int orient2d(const float a[2], const float b[2], const float c[2]) {
    int sign;
    return orient2d_filter(a, b, c, &sign) ? sign : orient2d_exact(a, b, c);
}

}  // namespace tetprobe
