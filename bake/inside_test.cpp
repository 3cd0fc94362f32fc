#include "bake/inside_test.h"

#include "bake/parallel_jobs.h"
#include "bake/sampling.h"
#include "core/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

namespace tetprobe {

namespace {

using Corner = std::array<uint32_t, 3>;  // a vertex's exact float bits

Corner corner_of(const Mesh& mesh, uint32_t vertex) {
    Corner c;
    std::memcpy(c.data(), &mesh.vertices[3 * size_t(vertex)], sizeof c);
    return c;
}

// +1: the closed mesh's triangles face out of its enclosed volume, -1: into it, 0: the mesh is open.
int closed_winding(const Mesh& mesh) {
    std::map<std::pair<Corner, Corner>, int> edges;  // directed edge -> uses
    for (size_t t = 0; t < mesh.triangle_count(); ++t)
        for (int e = 0; e < 3; ++e) {
            const Corner a = corner_of(mesh, mesh.indices[3 * t + e]), b = corner_of(mesh, mesh.indices[3 * t + (e + 1) % 3]);
            if (++edges[{a, b}] > 1) return 0;  // two triangles wound the same way along an edge
        }
    for (const auto& edge : edges) {
        auto reverse = edges.find({edge.first.second, edge.first.first});
        if (reverse == edges.end()) return 0;  // a boundary edge
    }
    double volume = 0.0;
    const float* origin = &mesh.vertices[3 * size_t(mesh.indices[0])];
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        double p[3][3];
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) p[i][k] = double(mesh.vertices[3 * size_t(mesh.indices[3 * t + i]) + k]) - origin[k];
        volume += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
                  p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
    }
    return volume > 0 ? 1 : volume < 0 ? -1 : 0;
}

}  // namespace

void scene_bounds(const Scene& scene, double lo[3], double hi[3]) {
    for (int a = 0; a < 3; ++a) lo[a] = INFINITY, hi[a] = -INFINITY;
    for (const Mesh& mesh : scene.meshes())
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], double(mesh.bounds_min[a]));
            hi[a] = std::max(hi[a], double(mesh.bounds_max[a]));
        }
}

InsideTest::InsideTest(const Scene& scene, const RayCaster& caster) : caster_(caster), meshes_(scene.meshes().size()) {
    for (uint32_t m = 0; m < scene.meshes().size(); ++m) {
        const Mesh& mesh = scene.meshes()[m];
        const std::vector<float>& v = caster.local_vertices(m);
        std::vector<float> normals(3 * mesh.triangle_count(), 0.0f);
        int winding = 0;
        bool winding_known = false;
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            // One-sided: the solid is behind the front face, so free space lies along the normal. A
            // closed two-sided mesh: free space lies outside the volume it encloses.
            double s = 1.0;
            if (mesh.materials[mesh.triangle_materials[t]].two_sided) {
                if (!winding_known) winding = closed_winding(mesh), winding_known = true;
                if (winding == 0) continue;
                s = double(winding);
            }
            const uint32_t* tri = &mesh.indices[3 * t];
            double e1[3], e2[3];
            for (int k = 0; k < 3; ++k) {
                e1[k] = double(v[3 * tri[1] + k]) - v[3 * tri[0] + k];
                e2[k] = double(v[3 * tri[2] + k]) - v[3 * tri[0] + k];
            }
            double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(length > 0)) continue;
            for (int k = 0; k < 3; ++k) normals[3 * t + k] = float(s * n[k] / length);
            ++solid_triangles_;
        }
        free_normals_.push_back(std::move(normals));
    }
    directions_.resize(3 * kInsideTestRays);
    for (uint32_t r = 0; r < kInsideTestRays; ++r) {
        double d[3];
        stratified_sphere_direction(0x1d5e7e57ull, 0, r, kInsideTestRays, d);
        for (int k = 0; k < 3; ++k) directions_[3 * r + k] = float(d[k]);
    }
}

void InsideTest::require_decidable() const {
    if (decidable()) return;
    if (meshes_ == 0) throw Error(Status::scene, "the scene has no mesh, so nothing can be inside geometry");
    throw Error(Status::scene,
                "no mesh of the scene has an inside: every mesh is two-sided and open (not closed), so whether a "
                "point is inside geometry cannot be decided; make walls one-sided or close two-sided meshes");
}

bool InsideTest::inside(const float local[3]) const {
    uint32_t solid_hits = 0;
    for (uint32_t r = 0; r < kInsideTestRays; ++r) {
        const float* d = direction(r);
        RayHit hit;
        if (!caster_.intersect(local, d, 0.0f, INFINITY, &hit)) continue;
        const float* n = free_normal(hit.mesh, hit.triangle);
        // Leaving through a solid side means the ray started in the solid.
        if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0.0f) ++solid_hits;
        // Stop as soon as the majority is decided either way.
        if (2 * solid_hits > kInsideTestRays) return true;
        if (2 * (solid_hits + (kInsideTestRays - 1 - r)) <= kInsideTestRays) return false;
    }
    return 2 * solid_hits > kInsideTestRays;
}

std::vector<uint32_t> find_inside_probes(const Scene& scene, const std::vector<float>& positions, uint32_t threads,
                                         bool* decided) {
    double lo[3], hi[3];
    scene_bounds(scene, lo, hi);
    double origin[3] = {0, 0, 0};
    if (!scene.meshes().empty())
        for (int a = 0; a < 3; ++a) origin[a] = 0.5 * (lo[a] + hi[a]);
    const RayCaster caster(scene, origin);
    const InsideTest test(scene, caster);
    if (decided) *decided = test.decidable();
    if (decided && !test.decidable()) return {};
    test.require_decidable();
    const size_t count = positions.size() / 3;
    std::vector<uint8_t> inside(count, 0);
    run_jobs(count, threads, [&](size_t i) {
        const float local[3] = {float(positions[3 * i] - origin[0]), float(positions[3 * i + 1] - origin[1]),
                                float(positions[3 * i + 2] - origin[2])};
        inside[i] = test.inside(local) ? 1 : 0;
    }, Progress{}, "inside test");
    std::vector<uint32_t> indices;
    for (size_t i = 0; i < count; ++i)
        if (inside[i]) indices.push_back(uint32_t(i));
    return indices;
}

}  // namespace tetprobe
