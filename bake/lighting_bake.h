// The lighting bake: per probe, the L2 SH of incoming radiance (27 floats, channel-major), simulating
// only what the effects plan calls for.
#pragma once

#include "bake/effects_plan.h"
#include "bake/progress.h"
#include "bake/scene.h"
#include "core/option_defaults.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

struct BakeSettings {
    uint32_t rays = kDefaultBakeRays;        // sampled directions per probe
    uint32_t bounces = kDefaultBakeBounces;  // surface reflections between an emitter and the probe
    uint64_t seed = 0;
    uint32_t threads = 0;    // 0 = all cores
    bool culling = true;     // false: every mesh occludes every light (test aid)
    bool emitter_sampling = true;  // false: emission is found only by rays that hit it (test and benchmark aid)
    Progress progress;             // stage "bake"; cancelling throws Error(Status::cancelled)
};

struct BakeStats {
    uint64_t rays_cast = 0;  // closest-hit and occlusion rays traced through Embree
    double seconds = 0;      // wall time of the tracing (not of building the ray-casting scenes)
};

// Bakes the probes at `positions` (3 floats each, world units) and returns 27 floats per probe.
// Delta lights in the plan's direct set are projected analytically with one shadow ray; the sphere
// of directions is sampled (stratified, deterministic per seed, probe and ray) for sky, emission
// and bounces, which are path traced with next-event estimation of the lights. Emissive triangles
// are also sampled directly, from the probe and from each reflection (points drawn in proportion
// to emitted power, with a shadow ray), and combined with the rays that hit them by multiple
// importance sampling, so a small bright emitter converges with few rays. The projection
// solves the least-squares fit of the samples (their Gram matrix), so radiance that is itself in
// the L2 span, such as a uniform or SH sky, comes out exact. Results do not depend on the thread
// count. A progress callback that returns non-zero throws Error(Status::cancelled).
std::vector<float> bake_lighting(const Scene& scene, const std::vector<float>& positions,
                                 const BakeSettings& settings, EffectsPlan* plan_out = nullptr,
                                 BakeStats* stats = nullptr);

}  // namespace tetprobe
