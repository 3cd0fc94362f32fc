// Automatic probe placement: candidates on a grid (bake/placement_candidates.h), baked at a low ray
// count with the lighting bake, then pruned by error (bake/probe_pruning.h). Deterministic for a
// seed: the same scene and settings give the same positions and error curve on any thread count.
#pragma once

#include "bake/placement_candidates.h"
#include "bake/probe_pruning.h"
#include "bake/progress.h"
#include "bake/scene.h"
#include "core/option_defaults.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

struct PlacementSettings {
    CandidateRules rules;
    uint32_t target_count = 0;  // 0: no target
    double error_bound = kDefaultPlacementErrorBound;  // 0: no bound (see bake/probe_pruning.h for the error)
    uint32_t rays = kDefaultPlacementRays;              // the candidates' low-sample bake
    uint32_t bounces = kDefaultBakeBounces;
    uint64_t seed = 0;
    uint32_t threads = 0;       // 0 = all cores
    Progress progress;          // stages "candidates", "bake", "prune", "done"
};

struct Placement {
    std::vector<float> positions;        // 3 per probe, world, in grid order
    std::vector<ErrorCurvePoint> curve;  // error against the number of probes
    size_t candidates = 0;               // candidates that passed the rules
    size_t held_out = 0;
};

// The upper bound of the probes place_probes returns (see candidate_bound); throws as
// candidate_bound.
size_t placement_bound(const Scene& scene, const PlacementSettings& settings);

// Places probes in the scene. Throws Error: invalid_argument (bad settings, a target count above the
// candidates), scene (no mesh, nothing with an inside), degenerate (no candidate passes the rules),
// cancelled (the progress callback).
Placement place_probes(const Scene& scene, const PlacementSettings& settings);

}  // namespace tetprobe
