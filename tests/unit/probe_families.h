// Probe sets of the hard-case families (issue 3) for the builder's tests: each a list of world-space
// float positions with a name.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace families {

struct ProbeSet {
    std::string name;
    std::vector<float> positions;  // 3 per probe, world
    size_t count() const { return positions.size() / 3; }
    void add(double x, double y, double z) {
        positions.push_back(float(x));
        positions.push_back(float(y));
        positions.push_back(float(z));
    }
};

inline ProbeSet random_cloud(size_t n, uint32_t seed, double scale = 10, double offset = 0) {
    ProbeSet s{"random", {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (size_t i = 0; i < n; ++i) s.add(offset + scale * u(rng), offset + scale * u(rng), offset + scale * u(rng));
    return s;
}

inline ProbeSet lattice(int nx, int ny, int nz, double spacing = 1, double jitter = 0, uint32_t seed = 1) {
    ProbeSet s{"lattice " + std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz), {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                // Jitter of a few float ulps of the coordinate: the "lattice plus 2 eps" family.
                const double j = jitter * spacing * std::max({nx, ny, nz});
                s.add(x * spacing + j * u(rng), y * spacing + j * u(rng), z * spacing + j * u(rng));
            }
    return s;
}

// A lattice squashed along z by `squash` (a slab much thinner than wide, still 3D at default tolerance).
inline ProbeSet slab(int n, double squash) {
    ProbeSet s{"slab", {}};
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) s.add(x, y, z * squash * n);
    return s;
}

// A level: a sparse cloud over a kilometre, and a dense, jittered room of probes half a metre apart
// far from the set's centroid (where float rows relative to the origin lost 1e-4).
inline ProbeSet dense_room_in_a_level(uint32_t seed) {
    ProbeSet s{"dense room in a level", {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1000), j(-0.01, 0.01);
    for (int i = 0; i < 200; ++i) s.add(u(rng), u(rng), u(rng));
    for (int z = 0; z < 6; ++z)
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 6; ++x) s.add(100 + 0.5 * x + j(rng), 200 + 0.5 * y + j(rng), 300 + 0.5 * z + j(rng));
    return s;
}

inline ProbeSet plane(int n, uint32_t seed) {
    ProbeSet s{"plane", {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 10);
    for (int i = 0; i < n; ++i) s.add(u(rng), u(rng), 2.0);
    return s;
}

// Points of a tilted plane with coordinates rounded to a millimetre (not exactly coplanar in float).
inline ProbeSet tilted_plane_rounded(int n, uint32_t seed) {
    ProbeSet s{"tilted plane, rounded", {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-10, 10);
    for (int i = 0; i < n; ++i) {
        const double a = u(rng), b = u(rng);
        const double x = 0.8 * a + 0.1 * b, y = 0.36 * a - 0.6 * b, z = 0.48 * a + 0.8 * b + 3;
        s.add(std::round(x * 1000) / 1000, std::round(y * 1000) / 1000, std::round(z * 1000) / 1000);
    }
    return s;
}

inline ProbeSet line(int n) {
    ProbeSet s{"line", {}};
    for (int i = 0; i < n; ++i) s.add(1 + 0.5 * i, 2 - 0.25 * i, 3 + 0.75 * i);
    return s;
}

// A race track: a flat stadium-shaped loop of probes along both edges of the road (straights with
// many collinear probes, then half circles), in a slightly tilted plane.
inline ProbeSet racetrack(int per_edge) {
    ProbeSet s{"racetrack", {}};
    const double kPi = 3.14159265358979323846, straight = 60;
    for (double radius : {15.0, 27.0}) {
        const double perimeter = 2 * straight + 2 * kPi * radius;
        for (int i = 0; i < per_edge; ++i) {
            double d = perimeter * i / per_edge, x, y;
            if (d < straight) {
                x = -straight / 2 + d, y = -radius;
            } else if ((d -= straight) < kPi * radius) {
                x = straight / 2 + radius * std::sin(d / radius), y = -radius * std::cos(d / radius);
            } else if ((d -= kPi * radius) < straight) {
                x = straight / 2 - d, y = radius;
            } else {
                d -= straight;
                x = -straight / 2 - radius * std::sin(d / radius), y = radius * std::cos(d / radius);
            }
            s.add(100 + x, 5 + 0.05 * x, -50 + y);
        }
    }
    return s;
}

// An n^3 lattice of unit spacing under a random rotation (a uniformly random unit quaternion from
// seed), centred on (offset, offset, offset).
inline ProbeSet rotated_lattice(int n, uint32_t seed, double offset = 0) {
    ProbeSet s{"lattice " + std::to_string(n) + "^3 rotated (" + std::to_string(seed) + ")" +
                   (offset != 0 ? " at " + std::to_string(int64_t(offset)) : std::string()),
               {}};
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    double q[4], norm = 0;
    for (double& c : q) {
        c = g(rng);
        norm += c * c;
    }
    norm = std::sqrt(norm);
    for (double& c : q) c /= norm;
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
    const double c = 0.5 * (n - 1);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double p[3] = {i - c, j - c, k - c};
                s.add(offset + r[0][0] * p[0] + r[0][1] * p[1] + r[0][2] * p[2],
                      offset + r[1][0] * p[0] + r[1][1] * p[1] + r[1][2] * p[2],
                      offset + r[2][0] * p[0] + r[2][1] * p[1] + r[2][2] * p[2]);
            }
    return s;
}

// A sparse cloud over a kilometre and `count` probes in a cube `width` wide (1 cm: 1e-5 of the
// extent) far from the centre.
inline ProbeSet cluster_in_a_level(int count, double width, uint32_t seed) {
    ProbeSet s{"cluster of " + std::to_string(count) + " in " + std::to_string(width) + " inside a kilometre", {}};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1000), v(0, width);
    for (int i = 0; i < 100; ++i) s.add(u(rng), u(rng), u(rng));
    for (int i = 0; i < count; ++i) s.add(321.5 + v(rng), 654.25 + v(rng), 123.75 + v(rng));
    return s;
}

}  // namespace families
