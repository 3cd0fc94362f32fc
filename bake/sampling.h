// Deterministic sampling for the bake: every random number is a hash of (seed, probe, ray,
// dimension), so a probe's result does not depend on which thread traced it or in what order.
#pragma once

#include <cmath>
#include <cstdint>

namespace tetprobe {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64's finalizer: a bijective 64-bit mix with good avalanche.
inline uint64_t mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A uniform number in [0, 1) for one (seed, probe, ray, dimension) tuple.
inline double sample_uniform(uint64_t seed, uint64_t probe, uint64_t ray, uint64_t dimension) {
    uint64_t h = mix64(seed ^ mix64(probe ^ mix64(ray ^ mix64(dimension))));
    return double(h >> 11) * (1.0 / 9007199254740992.0);  // 53 bits
}

// Direction `ray` of `rays` over the unit sphere, uniform density: equal-area bands in z (one
// sample jittered within each band) and a golden-ratio sequence in azimuth, rotated per probe.
// Well spread for any ray count, unlike a square grid.
inline void stratified_sphere_direction(uint64_t seed, uint64_t probe, uint32_t ray, uint32_t rays, double out[3]) {
    const double jitter = sample_uniform(seed, probe, ray, 0);
    const double rotation = sample_uniform(seed, probe, 0xffffffffull, 1);
    double z = 1.0 - 2.0 * (double(ray) + jitter) / double(rays);
    double turn = double(ray) * 0.6180339887498949 + rotation;
    double phi = 2.0 * kPi * (turn - std::floor(turn));
    double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
    out[0] = r * std::cos(phi);
    out[1] = r * std::sin(phi);
    out[2] = z;
}

// Cosine-weighted direction about unit normal n (pdf cos(theta) / pi) from two uniforms.
inline void cosine_direction(const double n[3], double u1, double u2, double out[3]) {
    double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    double x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::fmax(0.0, 1.0 - u1));
    // An orthonormal frame around n (Duff et al., "Building an Orthonormal Basis, Revisited").
    double sign = std::copysign(1.0, n[2]);
    double a = -1.0 / (sign + n[2]), b = n[0] * n[1] * a;
    double t[3] = {1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]};
    double s[3] = {b, sign + n[1] * n[1] * a, -n[1]};
    for (int k = 0; k < 3; ++k) out[k] = x * t[k] + y * s[k] + z * n[k];
}

// Barycentric weights of a uniformly distributed point on a triangle from two uniforms (the
// square-root warp: u1 picks the distance from the first corner, u2 the place across).
inline void uniform_triangle_weights(double u1, double u2, double weights[3]) {
    double s = std::sqrt(u1);
    weights[0] = 1.0 - s;
    weights[1] = s * (1.0 - u2);
    weights[2] = s * u2;
}

}  // namespace tetprobe
