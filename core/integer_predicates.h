// Exact orientation and in-sphere signs of float32 points in fixed-width integer arithmetic: the
// coordinates scaled by their largest common power of two are integers, and when they span less
// than 2^40 (nearby points of similar magnitude; lattices), the determinants fit 128-bit integers
// (256-bit for the in-sphere's final sum). The common exact case of the Delaunay builders (exact
// zeros on lattices and cospherical sets) costs a few dozen integer operations this way; wider
// inputs answer false and take the general exact path (insphere.cpp, orientation.cpp).
#pragma once

#include "core/orientation.h"

#include <cstdint>

namespace tetprobe {

// Each returns true with the exact sign in *sign (the conventions of orientation.h and insphere.h),
// or false when the points' coordinates span too many bits for this path.
bool orient3d_integer(const float a[3], const float b[3], const float c[3], const float d[3], int* sign);
bool orient2d_integer(const float a[2], const float b[2], const float c[2], int* sign);
bool insphere_integer(const float a[3], const float b[3], const float c[3], const float d[3], const float e[3], int* sign);
bool incircle_integer(const float a[2], const float b[2], const float c[2], const float d[2], int* sign);

// The exact orientation signs, this path first and orientation.h's expansions otherwise.
int orient3d_exact_fast(const float a[3], const float b[3], const float c[3], const float d[3]);
int orient2d_exact_fast(const float a[2], const float b[2], const float c[2]);

// orientation.h's orient3d and orient2d (the same signs), with this path before the expansions.
inline int orient3d_fast(const float a[3], const float b[3], const float c[3], const float d[3]) {
    int sign;
    return orient3d_filter(a, b, c, d, &sign) ? sign : orient3d_exact_fast(a, b, c, d);
}
inline int orient2d_fast(const float a[2], const float b[2], const float c[2]) {
    int sign;
    return orient2d_filter(a, b, c, &sign) ? sign : orient2d_exact_fast(a, b, c);
}

}  // namespace tetprobe
