// Real roots of polynomials up to degree 3, robust when the leading coefficients are tiny or zero
// (an outer cell's cubic degenerates to a quadratic or a line when hull normals are parallel).
#pragma once

namespace tetprobe {

// Real roots of a t^3 + b t^2 + c t + d = 0, ascending, each polished to full double precision;
// returns how many (0..3). Any coefficient may be zero; roots beyond |t| = 1e100 are not reported,
// and neither are roots of the all-zero polynomial. Double roots are reported once.
int cubic_real_roots(double a, double b, double c, double d, double roots[3]);

}  // namespace tetprobe
