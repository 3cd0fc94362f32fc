// Roots by bracketing: the cubic is monotonic between its critical points, so each monotonic piece
// with a sign change holds exactly one root, found by Newton steps kept inside the bracket. The
// bracket is halved in the ordering of doubles, so even a span of 1e200 closes in ~64 halvings.
#include "core/polynomial_roots.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

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

// The single root in [lo, hi] where f(lo) and f(hi) have opposite signs.
double bracketed_root(const Cubic& f, double lo, double hi, double f_lo) {
    double x = 0.5 * lo + 0.5 * hi;
    if (!(x > lo && x < hi)) x = ordered_midpoint(lo, hi);
    for (int iteration = 0; iteration < 400; ++iteration) {
        const double fx = f.value(x);
        if (fx == 0.0) return x;
        if ((fx < 0) == (f_lo < 0)) {
            lo = x;
            f_lo = fx;
        } else {
            hi = x;
        }
        if (__int128(ordered_key(hi)) - ordered_key(lo) <= 1) break;
        // A Newton step when it stays strictly inside the bracket; every third step halves it.
        const double slope = f.slope(x);
        double next = slope != 0.0 ? x - fx / slope : lo;
        if (iteration % 3 == 2 || !(next > lo && next < hi)) next = ordered_midpoint(lo, hi);
        if (next == x) break;
        x = next;
    }
    return std::fabs(f.value(lo)) <= std::fabs(f.value(hi)) ? lo : hi;
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

    // Points splitting the line into monotonic pieces: the critical points inside the bound.
    double splits[4];
    int split_count = 0;
    splits[split_count++] = -kRootBound;
    double critical[2];
    const int critical_count = quadratic_roots(3.0 * f.a, 2.0 * f.b, f.c, critical);
    std::sort(critical, critical + critical_count);
    for (int i = 0; i < critical_count; ++i)
        if (critical[i] > splits[split_count - 1] && critical[i] < kRootBound) splits[split_count++] = critical[i];
    splits[split_count++] = kRootBound;

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
        if ((f_lo < 0.0 && f_hi > 0.0) || (f_lo > 0.0 && f_hi < 0.0)) add(bracketed_root(f, lo, hi, f_lo));
    }
    std::sort(roots, roots + count);
    return count;
}

}  // namespace tetprobe
