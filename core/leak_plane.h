// The wall plane of a blocked probe pair (store_format.h, LeakEdge): a plane N . x = offset in the
// store's local frame, whose normal N is the integer vector of an octahedral code (so that the side a
// point lies on is decided exactly), facing the probe it belongs to.
//
// Why integers: with N's components integers of at most 15 bits and the point's and offset's float32,
// every product N_k * x_k is exact in double (15 + 24 significant bits), so the sign of
// N . x - offset is the exact sign of a sum of four doubles: a filtered double sum decides it when its
// value exceeds the sum's rounding bound, an exact expansion sum otherwise. No tolerance moves the plane.
#pragma once

#include <cstdint>

namespace tetprobe {

// The octahedral code's direction as integers (not unit): u = max(code[0], -32767), v likewise,
// (u, v, 32767 - |u| - |v|), folded below the equator to (+-(32767 - |v|), +-(32767 - |u|), z) (signs of
// u and v, 0 counting as positive): the same folding as decode_normal (core/octahedral_normal.h), which
// is this vector normalised. Every component is within +-32767, and the vector is never zero.
void leak_plane_normal(const int16_t code[2], int32_t out[3]);

// Exact sign (-1, 0, +1) of N . point - offset for the code's integer normal N (point local, float32).
int leak_plane_side(const int16_t code[2], float offset, const float point[3]);

// A wall plane as the run time tests it: the code's integer normal (leak_plane_normal), decoded once on
// load, and the offset.
struct LeakPlane {
    int32_t normal[3];
    float offset;
};

// The same side test on a decoded plane: what a query calls, so that it decodes nothing.
int leak_plane_side(const LeakPlane& plane, const float point[3]);

// The stored plane of a wall seen from probe `own` (the probe it faces) across the segment to `other`:
// the code of `normal` turned towards own, and an offset through `crossing` (a point on the segment),
// such that own is strictly on the positive side and other strictly on the negative side (exactly, by
// leak_plane_side). Where the encoded wall normal cannot separate the pair (a wall grazing the segment,
// within the code's precision), the segment's own direction is used. False when no float offset lies
// strictly between the two probes (probes a few float steps apart).
bool make_leak_plane(const double normal[3], const double crossing[3], const float own[3], const float other[3],
                     int16_t code[2], float* offset);

}  // namespace tetprobe
