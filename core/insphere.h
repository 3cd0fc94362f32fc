// The Delaunay decision on float32 points: is e inside the sphere through a, b, c, d (the circle
// through a, b, c)? A double-precision filter with Shewchuk's error bound, an exact fallback (the
// determinant of the coordinates scaled to integers, core/exact_integer.h), and the tie rule for points
// exactly on the sphere: TetGen 1.5's symbolic perturbation by point index, so that a degenerate set
// (lattices, cospherical probes) has one Delaunay tessellation, the one TetGen builds for the points
// in the same order.
//
// The perturbation lifts point i to |p_i|^2 + eps_i with eps_0 >> eps_1 >> ... > 0 (the lower the
// index, the larger), the lift whose decisions TetGen's insphere_s makes: on an exact tie, the five
// points sorted by index decide by the orientation of the four after the first (or, if those are
// coplanar, of the first with the last three). Four coplanar points of a hull side are decided the
// same way, in the plane (incircle_perturbed), which is what TetGen's coplanar hull faces inherit.
#pragma once

#include "core/orientation.h"

#include <cmath>
#include <cstdint>

namespace tetprobe {

// Shewchuk's bounds for his insphere and incircle evaluations (the ones below, differences relative
// to the last point, rounding of the differences included). eps = 2^-53. Float differences and their
// products of degree 5 never underflow nor overflow in double (see orientation.h), so the bounds hold
// for every finite float input.
constexpr double kInsphereErrorFactor = (16.0 + 224.0 * kOrientationEps) * kOrientationEps;
constexpr double kIncircleErrorFactor = (10.0 + 96.0 * kOrientationEps) * kOrientationEps;

// +1 when e lies inside the sphere through a, b, c, d, -1 outside, 0 on it, for a positively oriented
// tetrahedron (orient3d(a, b, c, d) > 0, the store's convention); the signs flip for a negative one.
int insphere_exact(const float a[3], const float b[3], const float c[3], const float d[3], const float e[3]);
// +1 when d lies inside the circle through a, b, c, counter-clockwise (orient2d(a, b, c) > 0).
int incircle_exact(const float a[2], const float b[2], const float c[2], const float d[2]);

// The filters alone, like orientation.h's: true with the sign when the double evaluation decides it.
// A zero bound means every term of the determinant has an exactly zero factor: the sign is 0.
// The filters take float coordinates, or doubles holding floats (the bound assumes float inputs).
template <class Real>
inline bool insphere_filter(const Real a[3], const Real b[3], const Real c[3], const Real d[3], const Real e[3],
                            int* sign) {
    const double ex = e[0], ey = e[1], ez = e[2];
    const double aex = a[0] - ex, aey = a[1] - ey, aez = a[2] - ez;
    const double bex = b[0] - ex, bey = b[1] - ey, bez = b[2] - ez;
    const double cex = c[0] - ex, cey = c[1] - ey, cez = c[2] - ez;
    const double dex = d[0] - ex, dey = d[1] - ey, dez = d[2] - ez;
    const double ab = aex * bey - bex * aey, bc = bex * cey - cex * bey;
    const double cd = cex * dey - dex * cey, da = dex * aey - aex * dey;
    const double ac = aex * cey - cex * aey, bd = bex * dey - dex * bey;
    const double abc = aez * bc - bez * ac + cez * ab;
    const double bcd = bez * cd - cez * bd + dez * bc;
    const double cda = cez * da + dez * ac + aez * cd;
    const double dab = dez * ab + aez * bd + bez * da;
    const double alift = aex * aex + aey * aey + aez * aez;
    const double blift = bex * bex + bey * bey + bez * bez;
    const double clift = cex * cex + cey * cey + cez * cez;
    const double dlift = dex * dex + dey * dey + dez * dez;
    // Shewchuk's insphere: positive inside for his orientation, which is minus the store's.
    const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    // Shewchuk's permanent sums, per point, its lift times three terms |x y| + |x' y'| times |z|: at
    // most 6 X Y Z (alift + blift + clift + dlift) for X, Y, Z the largest |difference| per axis. The
    // factor 1 + 2^-40 covers the rounding of both evaluations (a dozen operations on non-negative
    // numbers each), so the bound is at least Shewchuk's.
    auto largest = [](double p, double q, double r, double s) {
        p = std::fabs(p), q = std::fabs(q), r = std::fabs(r), s = std::fabs(s);
        p = p > q ? p : q;
        r = r > s ? r : s;
        return p > r ? p : r;
    };
    const double x = largest(aex, bex, cex, dex), y = largest(aey, bey, cey, dey), z = largest(aez, bez, cez, dez);
    const double permanent_bound = 6 * (x * y * z) * ((alift + blift) + (clift + dlift));
    const double bound = (kInsphereErrorFactor * (1 + 0x1p-40)) * permanent_bound;
    if (det > bound) return *sign = -1, true;
    if (-det > bound) return *sign = 1, true;
    if (permanent_bound == 0) return *sign = 0, true;
    return false;  // also for NaN and infinite inputs
}

template <class Real>
inline bool incircle_filter(const Real a[2], const Real b[2], const Real c[2], const Real d[2], int* sign) {
    const double adx = double(a[0]) - d[0], ady = double(a[1]) - d[1];
    const double bdx = double(b[0]) - d[0], bdy = double(b[1]) - d[1];
    const double cdx = double(c[0]) - d[0], cdy = double(c[1]) - d[1];
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, alift = adx * adx + ady * ady;
    const double cdxady = cdx * ady, adxcdy = adx * cdy, blift = bdx * bdx + bdy * bdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady, clift = cdx * cdx + cdy * cdy;
    const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                             (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                             (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
    const double bound = kIncircleErrorFactor * permanent;
    if (det > bound) return *sign = 1, true;
    if (-det > bound) return *sign = -1, true;
    if (permanent == 0) return *sign = 0, true;
    return false;
}

inline int insphere(const float a[3], const float b[3], const float c[3], const float d[3], const float e[3]) {
    int sign;
    return insphere_filter(a, b, c, d, e, &sign) ? sign : insphere_exact(a, b, c, d, e);
}

inline int incircle(const float a[2], const float b[2], const float c[2], const float d[2]) {
    int sign;
    return incircle_filter(a, b, c, d, &sign) ? sign : incircle_exact(a, b, c, d);
}

// The tie rule alone: the sign insphere_perturbed gives where insphere is exactly 0 (points[] =
// {a, b, c, d, e}, indices distinct).
int insphere_tie(const float* const points[5], const uint32_t indices[5]);
// The same for incircle_perturbed (points[] = {a, b, c, d}, 2D).
int incircle_tie(const float* const points[4], const uint32_t indices[4]);

// insphere(a, b, c, d, e) for points[] = {a, b, c, d, e} with the tie broken by the points' indices
// (distinct): never 0 when a, b, c, d span a tetrahedron and e is none of them.
inline int insphere_perturbed(const float* const points[5], const uint32_t indices[5]) {
    const int sign = insphere(points[0], points[1], points[2], points[3], points[4]);
    return sign != 0 ? sign : insphere_tie(points, indices);
}

// incircle(a, b, c, d) for points[] = {a, b, c, d} (2D), the tie broken by index as TetGen breaks it
// for a flat set triangulated under an apex of a higher index (bake/flat_delaunay.cpp).
inline int incircle_perturbed(const float* const points[4], const uint32_t indices[4]) {
    const int sign = incircle(points[0], points[1], points[2], points[3]);
    return sign != 0 ? sign : incircle_tie(points, indices);
}

}  // namespace tetprobe
