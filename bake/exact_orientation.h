// Orientation signs for the bake, decided exactly: a double evaluation with Shewchuk's error bound
// (computed from the operands, so it holds for any inputs), and TetGen's exact predicate where the
// bound leaves the sign unsure. These are the store's conventions (store_format.h), which the run
// time decides the same way on the same float positions:
//   orient3d(a, b, c, d) = det[b - a, c - a, d - a] (rows)  — note TetGen's orient3d is MINUS this;
//   orient2d(a, b, c)    = det[b - a, c - a] in the plane coordinates (u, v).
#pragma once

namespace tetprobe {

// +1, 0 or -1: the exact sign of orient3d(a, b, c, d) on the given doubles.
int orient3d_sign(const double* a, const double* b, const double* c, const double* d);

// +1, 0 or -1: the exact sign of orient2d(a, b, c) on the given doubles (two coordinates each).
int orient2d_sign(const double* a, const double* b, const double* c);

}  // namespace tetprobe
