#include "bake/inside_probe_fix.h"

#include "bake/inside_test.h"
#include "bake/parallel_jobs.h"
#include "bake/placement_candidates.h"
#include "core/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace tetprobe {

namespace {

std::string point_text(const float* p) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", p[0], p[1], p[2]);
    return text;
}

}  // namespace

std::vector<float> fix_inside_probes(const Scene& scene, const std::vector<float>& positions, InsideFix fix,
                                     double margin, uint32_t threads) {
    if (!(std::isfinite(margin) && margin >= 0))
        throw Error(Status::invalid_argument, "margin must be zero or positive and finite");
    if (fix != InsideFix::drop && fix != InsideFix::push)
        throw Error(Status::invalid_argument, "unknown inside-probe fix mode " + std::to_string(uint32_t(fix)));
    double lo[3], hi[3], origin[3] = {0, 0, 0};
    scene_bounds(scene, lo, hi);
    if (!scene.meshes().empty())
        for (int a = 0; a < 3; ++a) origin[a] = 0.5 * (lo[a] + hi[a]);
    const RayCaster caster(scene, origin);
    const InsideTest test(scene, caster);
    test.require_decidable();
    // A probe pushed out sits a little beyond the margin, so float rounding cannot put it inside it;
    // with margin 0 it still leaves the surface by a relative step.
    double extent = 0;
    for (int a = 0; a < 3; ++a) extent = std::max(extent, hi[a] - lo[a]);
    const double offset = margin * (1.0 + 1e-3) + 1e-5 * extent;

    const size_t count = positions.size() / 3;
    std::vector<float> out(positions);
    std::vector<uint8_t> inside(count, 0), stuck(count, 0);
    run_jobs(count, threads, [&](size_t i) {
        const float local[3] = {float(double(positions[3 * i]) - origin[0]), float(double(positions[3 * i + 1]) - origin[1]),
                                float(double(positions[3 * i + 2]) - origin[2])};
        if (!test.inside(local)) return;
        inside[i] = 1;
        if (fix == InsideFix::drop) return;
        // Candidate exits: (distance from the probe, point), tried nearest first.
        std::vector<std::pair<double, std::array<float, 3>>> exits;
        auto add_exit = [&](const float surface[3], const float* normal) {
            std::array<float, 3> q;
            for (int k = 0; k < 3; ++k) q[k] = float(double(surface[k]) + offset * normal[k]);
            double d2 = 0;
            for (int k = 0; k < 3; ++k) d2 += (double(q[k]) - local[k]) * (double(q[k]) - local[k]);
            exits.push_back({d2, q});
        };
        SurfacePoint nearest;
        if (caster.nearest_surface(local, INFINITY, &nearest)) {
            const float* n = test.free_normal(nearest.mesh, nearest.triangle);
            if (n[0] != 0 || n[1] != 0 || n[2] != 0) add_exit(nearest.point, n);
        }
        for (uint32_t r = 0; r < kInsideTestRays; ++r) {
            const float* d = test.direction(r);
            RayHit hit;
            if (!caster.intersect(local, d, 0.0f, INFINITY, &hit)) continue;
            const float* n = test.free_normal(hit.mesh, hit.triangle);
            if (!(n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0.0f)) continue;
            const float surface[3] = {local[0] + hit.distance * d[0], local[1] + hit.distance * d[1],
                                      local[2] + hit.distance * d[2]};
            add_exit(surface, n);
        }
        std::stable_sort(exits.begin(), exits.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        for (const auto& exit : exits) {
            const float* q = exit.second.data();
            if (!clear_of_surfaces(caster, q, margin) || test.inside(q)) continue;
            for (int k = 0; k < 3; ++k) out[3 * i + k] = float(double(q[k]) + origin[k]);
            return;
        }
        stuck[i] = 1;
    }, Progress{}, "inside probes");

    for (size_t i = 0; i < count; ++i)
        if (stuck[i])
            throw Error(Status::scene, "probe " + std::to_string(i) + " at " + point_text(&positions[3 * i]) +
                                           " is inside geometry and no free point at least the margin from every "
                                           "surface was found near it: drop it instead, or lower the margin");
    if (fix == InsideFix::push) return out;
    std::vector<float> kept;
    for (size_t i = 0; i < count; ++i)
        if (!inside[i]) kept.insert(kept.end(), &positions[3 * i], &positions[3 * i] + 3);
    return kept;
}

}  // namespace tetprobe
