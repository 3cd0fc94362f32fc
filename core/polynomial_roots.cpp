// Roots by bracketing: the cubic is monotonic between its critical points, so each monotonic piece
// with a sign change holds exactly one root, found by Newton steps kept inside the bracket. The
// bracket is halved in the ordering of doubles, so even a span of 1e200 closes in ~64 halvings.
#include "core/polynomial_roots.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace tetprobe {

namespace {

constexpr double kRootBound = 1e100;

struct Cubic {
    double a, b, c, d;
    double value(double t) const { return ((a * t + b) * t + c) * t + d; }
    double slope(double t) const { return (3.0 * a * t + 2.0 * b) * t + c; }
    // Size of the terms at t: the scale against which a value counts as zero.
    double magnitude(double t) const {
        const double u = std::fabs(t);
        return ((std::fabs(a) * u + std::fabs(b)) * u + std::fabs(c)) * u + std::fabs(d);
    }
};

// Doubles mapped to integers of the same order (-0 and +0 coincide).
int64_t ordered_key(double x) {
    int64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return bits < 0 ? -(bits & INT64_MAX) : bits;
}

double from_ordered_key(int64_t key) {
    const int64_t bits = key < 0 ? ((-key) | INT64_MIN) : key;
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

double ordered_midpoint(double lo, double hi) {
    // In 128 bits: the keys of -1e100 and +1e100 are further apart than int64 can hold.
    return from_ordered_key(int64_t((__int128(ordered_key(lo)) + ordered_key(hi)) / 2));
}

bool within_one_magnitude(double lo, double hi) { return (lo > 0 && hi <= 4 * lo) || (hi < 0 && lo >= 4 * hi); }

double bisection_point(double lo, double hi) {
    // Arithmetic halving within one order of magnitude, halving in the ordering of doubles across many.
    return within_one_magnitude(lo, hi) ? 0.5 * lo + 0.5 * hi : ordered_midpoint(lo, hi);
}

// The single root in [lo, hi] where f(lo) and f(hi) have opposite signs (f monotonic there):
// Newton steps while they stay inside the bracket and keep shrinking, else halving.
double bracketed_root(const Cubic& f, double lo, double hi, double f_lo, double f_hi, double estimate) {
    // Start at the closed-form estimate, else a Newton step from whichever end lands inside.
    double x = estimate;
    if (!(x > lo && x < hi)) x = lo - f_lo / f.slope(lo);
    if (!(x > lo && x < hi)) x = hi - f_hi / f.slope(hi);
    if (!(x > lo && x < hi)) x = bisection_point(lo, hi);
    double last_step = std::numeric_limits<double>::infinity();
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double fx = f.value(x);
        // At or below the rounding noise of evaluating f, x is as good as any root double.
        if (std::fabs(fx) <= 8e-16 * f.magnitude(x)) return x;
        if ((fx < 0) == (f_lo < 0)) {
            lo = x;
            f_lo = fx;
        } else {
            hi = x;
        }
        if (__int128(ordered_key(hi)) - ordered_key(lo) <= 1) break;
        const double step = fx / f.slope(x);
        double next = x - step;
        const bool newton_ok = next > lo && next < hi && std::fabs(step) < 0.75 * last_step;
        if (newton_ok && std::fabs(step) <= 4e-16 * std::fabs(next)) return next;  // converged
        // Newton from far away only halves x per step: every fourth step halves a bracket that still
        // spans orders of magnitude in the ordering of doubles instead.
        if (!newton_ok || (iteration % 4 == 3 && !within_one_magnitude(lo, hi))) next = bisection_point(lo, hi);
        last_step = newton_ok ? std::fabs(step) : std::numeric_limits<double>::infinity();
        x = next;
    }
    return std::fabs(f.value(lo)) <= std::fabs(f.value(hi)) ? lo : hi;
}

// Closed-form estimates of the real roots of a monic-normalised cubic (Cardano, or the
// trigonometric form for three real roots). Cancellation can make them inexact; they only seed the
// bracketed search.
int cubic_estimates(const Cubic& f, double out[3]) {
    const double b = f.b / f.a, c = f.c / f.a, d = f.d / f.a;
    const double shift = b / 3.0;
    const double p = c - b * shift;                          // depressed: y^3 + p y + q, t = y - b/3
    const double q = (2.0 * b * b * b - 9.0 * b * c + 27.0 * d) / 27.0;
    const double discriminant = 0.25 * q * q + p * p * p / 27.0;
    if (!std::isfinite(discriminant)) return 0;
    if (discriminant > 0) {
        const double root = std::sqrt(discriminant);
        out[0] = std::cbrt(-0.5 * q + root) + std::cbrt(-0.5 * q - root) - shift;
        return 1;
    }
    if (p == 0) {
        out[0] = -shift;
        return 1;
    }
    const double m = 2.0 * std::sqrt(-p / 3.0);
    const double cosine = std::max(-1.0, std::min(1.0, 3.0 * q / (p * m)));
    const double angle = std::acos(cosine) / 3.0;
    constexpr double kThird = 2.0943951023931954923;  // 2 pi / 3
    for (int k = 0; k < 3; ++k) out[k] = m * std::cos(angle - kThird * k) - shift;
    return 3;
}

// Real roots of p t^2 + q t + r (p may be zero), unsorted; used for critical points.
int quadratic_roots(double p, double q, double r, double out[2]) {
    if (p == 0.0) {
        if (q == 0.0) return 0;
        out[0] = -r / q;
        return std::isfinite(out[0]) ? 1 : 0;
    }
    const double discriminant = q * q - 4.0 * p * r;
    if (discriminant < 0.0) return 0;
    const double s = q >= 0.0 ? -0.5 * (q + std::sqrt(discriminant)) : -0.5 * (q - std::sqrt(discriminant));
    int n = 0;
    if (s == 0.0) {
        out[n++] = 0.0;  // q = 0 and r = 0: a double root at 0
        return n;
    }
    const double first = s / p, second = r / s;
    if (std::isfinite(first)) out[n++] = first;
    if (std::isfinite(second)) out[n++] = second;
    return n;
}

}  // namespace

int cubic_real_roots(double a, double b, double c, double d, double roots[3]) {
    const double scale = std::max(std::max(std::fabs(a), std::fabs(b)), std::max(std::fabs(c), std::fabs(d)));
    if (!(scale > 0.0) || !std::isfinite(scale)) return 0;
    const Cubic f{a / scale, b / scale, c / scale, d / scale};

    // Every root lies within Fujiwara's bound, which stays moderate unless a root is truly huge.
    const double lead = f.a != 0 ? f.a : (f.b != 0 ? f.b : f.c);
    double bound;
    if (f.a != 0)
        bound = 2 * std::max({std::fabs(f.b / lead), std::sqrt(std::fabs(f.c / lead)), std::cbrt(std::fabs(f.d / (2 * lead)))});
    else if (f.b != 0)
        bound = 2 * std::max(std::fabs(f.c / lead), std::sqrt(std::fabs(f.d / (2 * lead))));
    else if (f.c != 0)
        bound = 2 * std::fabs(f.d / lead);
    else
        return 0;  // a non-zero constant
    bound = std::isfinite(bound) ? std::min(bound * (1 + 1e-12) + 1e-300, kRootBound) : kRootBound;

    // Points splitting the line into monotonic pieces: the critical points inside the bound.
    double splits[4];
    int split_count = 0;
    splits[split_count++] = -bound;
    double critical[2];
    const int critical_count = quadratic_roots(3.0 * f.a, 2.0 * f.b, f.c, critical);
    if (critical_count == 2 && critical[1] < critical[0]) std::swap(critical[0], critical[1]);
    for (int i = 0; i < critical_count; ++i)
        if (critical[i] > splits[split_count - 1] && critical[i] < bound) splits[split_count++] = critical[i];
    splits[split_count++] = bound;

    double estimates[3];
    const int estimate_count = f.a != 0 ? cubic_estimates(f, estimates) : quadratic_roots(f.b, f.c, f.d, estimates);
    auto estimate_in = [&](double lo, double hi) {
        for (int i = 0; i < estimate_count; ++i)
            if (estimates[i] > lo && estimates[i] < hi) return estimates[i];
        return std::numeric_limits<double>::quiet_NaN();
    };

    int count = 0;
    auto add = [&](double t) {
        if (count > 0 && std::fabs(t - roots[count - 1]) <= 1e-12 * std::max(1.0, std::fabs(t))) return;
        if (count < 3) roots[count++] = t;
    };
    for (int i = 0; i + 1 < split_count; ++i) {
        const double lo = splits[i], hi = splits[i + 1];
        const double f_lo = f.value(lo), f_hi = f.value(hi);
        const bool interior_split = i > 0;
        // A critical point where the cubic touches zero is a (double) root without a sign change.
        if (interior_split && std::fabs(f_lo) <= 1e-14 * f.magnitude(lo)) {
            add(lo);
            continue;
        }
        if (f_lo == 0.0 && i == 0) add(lo);
        if ((f_lo < 0.0 && f_hi > 0.0) || (f_lo > 0.0 && f_hi < 0.0)) add(bracketed_root(f, lo, hi, f_lo, f_hi, estimate_in(lo, hi)));
    }
    // Intervals come in ascending order, so the roots already do.
    return count;
}

}  // namespace tetprobe
