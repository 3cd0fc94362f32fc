// The effects plan: what a bake of a scene at given probes has to simulate, derived before any ray
// is cast, so that the bake simulates exactly the effects the scene has and the tool can say which.
#pragma once

#include "bake/scene.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tetprobe {

struct EffectsPlan {
    uint32_t lights = 0;
    std::vector<uint32_t> direct_lights;  // baked lights whose range reaches a probe
    uint32_t out_of_range_lights = 0;     // baked lights whose range reaches no probe
    uint32_t realtime_lights = 0;         // baked for their bounced light only
    std::vector<uint32_t> bounce_lights;  // lights lighting surfaces that bounce toward the probes
    bool sky = false;                     // a non-black sky
    std::vector<uint32_t> emissive_meshes;
    uint32_t bounces = 0;                 // 0 when nothing can bounce
    bool shadows = false;                 // some simulated light casts shadows
    uint32_t meshes = 0;
    // Per scene light: the meshes in its occlusion set for shadow rays from the probes (empty for
    // lights without direct shadows). With culling, only meshes meeting the shadow caster volume
    // of the probes' bounding box.
    std::vector<std::vector<uint32_t>> occluders;
    uint32_t shadow_casters = 0;            // sum of the occlusion sets' sizes
    uint32_t shadow_caster_candidates = 0;  // sum over direct shadowing lights of the meshes considered
    // Probes inside geometry (bake/inside_test.h), filled by add_inside_probes; inside_decided is
    // false when no mesh has an inside.
    std::vector<uint32_t> inside_probes;
    bool inside_decided = true;

    // True when the sphere of directions has to be sampled (sky, emission or bounces).
    bool sampled() const { return sky || !emissive_meshes.empty() || bounces > 0; }

    // One line: "direct: 2 lights (1 out of range); sky: off; emissive: 3 meshes; bounces: 2;
    // shadow casters: 41/120 meshes", with "; realtime: N lights (bounced only)" after the direct
    // part when the scene has realtime lights, and "; inside geometry: 2 probes (4, 17)" (the first
    // eight indices) when probes are inside, or "; inside geometry: undecided (no mesh has an inside)".
    std::string summary() const;
};

// Derives the plan for probes at `positions` (3 floats each, world units) and the requested number
// of bounces. culling = false puts every mesh into every shadowing light's occlusion set.
EffectsPlan derive_effects_plan(const Scene& scene, const std::vector<float>& positions, uint32_t bounces,
                                bool culling);

// Fills the plan's inside_probes for the probes at `positions` (casts rays; see bake/inside_test.h).
void add_inside_probes(EffectsPlan& plan, const Scene& scene, const std::vector<float>& positions, uint32_t threads);

// The probes' bounding box, inflated a little so that a flat or single-probe set still bounds a
// volume, as six inward planes (nx, ny, nz, d).
std::vector<std::array<double, 4>> probe_region_planes(const std::vector<float>& positions);

}  // namespace tetprobe
