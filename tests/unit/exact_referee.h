// The exact referee for the walk: whether a point lies in an inner cell, decided with Shewchuk's
// exact orientation predicate (TetGen's copy, which the library links anyway; independent of
// core/orientation.cpp). The stored positions are floats and the query is the float local point the
// run time decides with (reference::local_point), so every input is exact and the answer has no
// rounding at all.
#pragma once

#include "core/store_data.h"
#include "reference_interpolator.h"

// TetGen 1.5's robust predicates (global functions in libtet; REAL is double).
void exactinit(int verbose, int noexact, int nofilter, double maxx, double maxy, double maxz);
double orient3dexact(double* pa, double* pb, double* pc, double* pd);

namespace exact {

// Inner cell c of a 3D store holds p (inside or on its boundary), exactly.
inline bool cell_holds(const tetprobe::StoreData& d, uint32_t c, const reference::Vec& point) {
    static const bool initialised = (exactinit(0, 0, 0, 1.0, 1.0, 1.0), true);
    (void)initialised;
    double v[4][3], p[3] = {point.x(), point.y(), point.z()};
    for (uint32_t k = 0; k < 4; ++k) {
        const reference::Vec x = reference::position(d, reference::vertex(d, c, k));
        for (int a = 0; a < 3; ++a) v[k][a] = x[a];
    }
    // Face k is opposite vertex k: p must be on vertex k's side of it, or on it.
    static const int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    for (int k = 0; k < 4; ++k) {
        double* a = v[kFace[k][0]];
        double* b = v[kFace[k][1]];
        double* e = v[kFace[k][2]];
        const double vertex_side = orient3dexact(a, b, e, v[k]);
        const double point_side = orient3dexact(a, b, e, p);
        if (point_side != 0 && (point_side > 0) != (vertex_side > 0)) return false;
    }
    return true;
}

}  // namespace exact
