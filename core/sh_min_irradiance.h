// The smallest irradiance of L2 SH over all unit normals: the "negative irradiance" an L2 (or L1, or
// windowed) reconstruction produces, found as the global minimum of a quadratic on the sphere.
#pragma once

namespace tetprobe {

struct ShChannelMinimum {
    double value;        // the irradiance at normal (an upper bound of the minimum that it attains)
    double lower_bound;  // a proven lower bound of the minimum (Lagrange dual); equal to value up to rounding
    double normal[3];    // unit normal where value occurs
};

// Minimum over unit normals n of one channel's irradiance E(n) = c + b.n + n^T A n (9 coefficients in
// the contract's order). The global minimiser of a quadratic on the sphere solves (A - mu I) n = -b/2
// with A - mu I positive semidefinite (the trust-region subproblem): mu is the root of a monotone
// secular equation below A's smallest eigenvalue, found by bisection in double, or, in the "hard
// case", that eigenvalue itself with the rest of n along its eigenvector. Both candidates and the six
// eigenvector directions are evaluated and the smallest kept; the dual value at the bisected mu bounds
// the minimum from below, so no sampling density has to be trusted.
ShChannelMinimum sh_channel_min_irradiance(const float coefficients[9]);

// Per channel minimum of sh_channel_min_irradiance; out_normal is where the smallest of the three occurs.
void sh_min_irradiance(const float sh[27], float out_min_rgb[3], float out_normal[3]);

}  // namespace tetprobe
