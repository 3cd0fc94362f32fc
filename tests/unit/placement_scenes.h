// Scenes with known insides for the placement and inside-test tests, and an independent brute-force
// distance from a point to a scene's triangles (plane projection or the nearest edge, no Voronoi
// regions), to check what the library computes with Embree's point query.
#pragma once

#include "bake/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace placement_test {

using tetprobe::Material;
using tetprobe::Scene;

inline Material material(bool two_sided, float albedo = 0.6f) {
    Material m;
    m.albedo = {albedo, albedo, albedo};
    m.two_sided = two_sided;
    return m;
}

// An axis-aligned box [lo, hi]; outward = true faces out (a solid), false faces in (a room).
inline void add_box(Scene& scene, const std::array<float, 3>& lo, const std::array<float, 3>& hi, bool outward,
                    bool two_sided = false) {
    std::vector<float> v;
    for (int corner = 0; corner < 8; ++corner)
        for (int a = 0; a < 3; ++a) v.push_back(corner & (1 << a) ? hi[a] : lo[a]);
    std::vector<uint32_t> indices = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                     2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
    if (!outward)
        for (size_t t = 0; t < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
    scene.add_mesh(v.data(), 8, indices.data(), 12, {material(two_sided)}, nullptr);
}

// A UV sphere of radius r around c, faces out; its flat facets lie within r (1 - cos(pi / 24)) of the sphere.
inline void add_sphere(Scene& scene, const std::array<float, 3>& c, float r, bool two_sided = false) {
    const int rings = 24, segments = 48;
    std::vector<float> v;
    v.insert(v.end(), {c[0], c[1] + r, c[2]});
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
            v.push_back(float(c[0] + r * std::sin(theta) * std::cos(phi)));
            v.push_back(float(c[1] + r * std::cos(theta)));
            v.push_back(float(c[2] + r * std::sin(theta) * std::sin(phi)));
        }
    v.insert(v.end(), {c[0], c[1] - r, c[2]});
    const uint32_t bottom = uint32_t(v.size() / 3 - 1);
    auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * segments + (j % segments)); };
    std::vector<uint32_t> t;
    for (int j = 0; j < segments; ++j) t.insert(t.end(), {0u, ring(1, j + 1), ring(1, j)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            t.insert(t.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j)});
            t.insert(t.end(), {ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)});
        }
    for (int j = 0; j < segments; ++j) t.insert(t.end(), {bottom, ring(rings - 1, j), ring(rings - 1, j + 1)});
    scene.add_mesh(v.data(), v.size() / 3, t.data(), t.size() / 3, {material(two_sided)}, nullptr);
}

// A flat quad at height y over [x0, x1] x [z0, z1], facing up.
inline void add_floor(Scene& scene, float x0, float x1, float z0, float z1, float y, bool two_sided = false) {
    const float v[12] = {x0, y, z0, x0, y, z1, x1, y, z1, x1, y, z0};
    const uint32_t t[6] = {0, 1, 2, 0, 2, 3};
    scene.add_mesh(v, 4, t, 2, {material(two_sided)}, nullptr);
}

inline double segment_distance(const double p[3], const double a[3], const double b[3]) {
    double ab[3], ap[3];
    for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ap[k] = p[k] - a[k];
    const double t = std::clamp((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) /
                                    (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]), 0.0, 1.0);
    double d = 0;
    for (int k = 0; k < 3; ++k) d += (ap[k] - t * ab[k]) * (ap[k] - t * ab[k]);
    return std::sqrt(d);
}

// Distance from p to the nearest triangle of the scene, by brute force.
inline double distance_to_scene(const Scene& scene, const float point[3]) {
    const double p[3] = {point[0], point[1], point[2]};
    double best = INFINITY;
    for (const auto& mesh : scene.meshes())
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            double c[3][3];
            for (int i = 0; i < 3; ++i)
                for (int k = 0; k < 3; ++k) c[i][k] = mesh.vertices[3 * size_t(mesh.indices[3 * t + i]) + k];
            double e1[3], e2[3], n[3];
            for (int k = 0; k < 3; ++k) e1[k] = c[1][k] - c[0][k], e2[k] = c[2][k] - c[0][k];
            n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (double& x : n) x /= length;
            const double h = (p[0] - c[0][0]) * n[0] + (p[1] - c[0][1]) * n[1] + (p[2] - c[0][2]) * n[2];
            const double q[3] = {p[0] - h * n[0], p[1] - h * n[1], p[2] - h * n[2]};
            // The projection is inside when it lies on the inner side of all three edges.
            bool inside = true;
            for (int i = 0; i < 3; ++i) {
                const double* a = c[i];
                const double* b = c[(i + 1) % 3];
                double ab[3], aq[3];
                for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], aq[k] = q[k] - a[k];
                const double cross[3] = {ab[1] * aq[2] - ab[2] * aq[1], ab[2] * aq[0] - ab[0] * aq[2], ab[0] * aq[1] - ab[1] * aq[0]};
                if (cross[0] * n[0] + cross[1] * n[1] + cross[2] * n[2] < 0) inside = false;
            }
            double d = std::abs(h);
            if (!inside)
                d = std::min({segment_distance(p, c[0], c[1]), segment_distance(p, c[1], c[2]), segment_distance(p, c[2], c[0])});
            best = std::min(best, d);
        }
    return best;
}

}  // namespace placement_test
