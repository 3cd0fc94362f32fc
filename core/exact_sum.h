// Exact sums of doubles (Shewchuk 1997): two-sum and grow-expansion with zero elimination. An
// expansion is a list of non-overlapping doubles in increasing magnitude whose exact sum is the
// value; its sign is that of its last (largest) component. Shared by the exact predicates
// (orientation.cpp, leak_plane.cpp).
#pragma once

namespace tetprobe {

// s + e == a + b exactly, s = fl(a + b) (Knuth's two-sum: no ordering of |a|, |b| needed).
inline void two_sum(double a, double b, double& s, double& e) {
    s = a + b;
    const double b_virtual = s - a;
    const double a_virtual = s - b_virtual;
    e = (a - a_virtual) + (b - b_virtual);
}

// Adds b to the expansion e[0..n) (non-overlapping, increasing magnitude, no zeros) in place and
// returns the new length, at most n + 1.
inline int grow_expansion(double* e, int n, double b) {
    double q = b;
    int m = 0;
    for (int i = 0; i < n; ++i) {
        double s, h;
        two_sum(q, e[i], s, h);
        q = s;
        if (h != 0) e[m++] = h;  // m <= i: e[i] has been read already
    }
    if (q != 0) e[m++] = q;
    return m;
}

// The sign (-1, 0, +1) of an expansion's exact sum.
inline int expansion_sign(const double* e, int n) { return n == 0 ? 0 : (e[n - 1] > 0) - (e[n - 1] < 0); }

}  // namespace tetprobe
