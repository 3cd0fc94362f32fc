// Automatic probe placement: candidates where objects can be (bake/placement_candidates.h), baked at a
// low ray count in two halves (bake/placement_signal.h), then chosen by greedy insertion where the
// interpolation misses the baked light most (bake/probe_selection.h), with the error of every count
// estimated at validation points. Deterministic for a seed: the same scene and settings give the same
// positions and error curve on any thread count.
#pragma once

#include "bake/placement_candidates.h"
#include "bake/probe_selection.h"
#include "bake/progress.h"
#include "bake/scene.h"
#include "core/option_defaults.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

struct PlacementSettings {
    CandidateRules rules;
    uint32_t target_count = 0;  // 0: no target
    double error_bound = kDefaultPlacementErrorBound;  // 0: no bound (see bake/probe_selection.h for the error)
    uint32_t rays = kDefaultPlacementRays;              // the candidates' low-sample bake
    uint32_t bounces = kDefaultBakeBounces;
    uint64_t seed = 0;
    uint32_t threads = 0;       // 0 = all cores
    // Points closer than this to a point or spot light do not count in the error, and are chosen only
    // when a target needs more probes than the others (the light's inverse-square peak there is no
    // interpolation's to follow; the real-level benchmark leaves such points out alike).
    double light_clearance = kDefaultPlacementLightClearance;
    Progress progress;          // stages "candidates", "bake", "select", "exchange", "done"
};

struct Placement {
    std::vector<float> positions;        // 3 per probe, world, in the order chosen (refined at the target:
                                         // a smaller target's placement need not be a prefix of it; an
                                         // error-bound result and large targets are the greedy's order)
    std::vector<ErrorCurvePoint> curve;  // estimated error against the probe count, increasing counts;
                                         // empty when nothing was chosen (all candidates returned)
    size_t candidates = 0;               // candidates that passed the rules
    size_t validation_points = 0;
    size_t unreached = 0;                // candidates no playable seed reaches (left out)
};

// The upper bound of the probes place_probes returns (see candidate_bound); throws as candidate_bound.
size_t placement_bound(const Scene& scene, const PlacementSettings& settings);

// Places probes in the scene. Without a target and a bound every candidate is returned, unbaked.
// Throws Error: invalid_argument (bad settings, a target above the candidates, too many candidates),
// scene (no mesh, nothing with an inside, no candidate a playable seed sees), degenerate (fewer than
// four candidates pass the rules), cancelled (the progress callback).
Placement place_probes(const Scene& scene, const PlacementSettings& settings);

}  // namespace tetprobe
