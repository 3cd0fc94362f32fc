// Greedy insertion of probes among baked candidates, and the error it reports.
//
// The error is the real-level benchmark's quantity (level_metric.h), estimated: at validation points
// (free points of the same volume, never chosen, so the choice cannot fit them), the root mean square
// over points and the 6 axis normals of |interpolated - baked| luminance irradiance, relative to the
// mean baked there. Both sides come from the noisy candidate bake (placement_signal.h); the expected
// square of the noise (the point's own, and the chosen probes' carried by the interpolation) is
// subtracted, so the estimate is the error of a noise-free bake. Points that do not count (near a
// point light, see PlacementSettings) are left out of it.
//
// The choice: a well-spread start (farthest points), then rounds. Each round builds the store of the
// chosen probes, interpolates every candidate, and per cell finds the held-out candidate whose
// insertion would lower the summed squared error at the held-out candidates most (insertion_gain.h);
// cells are ranked by that gain (noise-corrected, trusted only when it stands out from the noise; an
// outer cell without a trusted gain by the largest error one candidate's insertion removes at itself,
// when that stands out; the others by the volume a candidate would take over, for coverage), and the
// best of each cell joins a batch unless its cavity touches one already chosen this round. Batches
// grow with the set (a quarter of it), so the whole curve costs a few dozen rounds. At a target the set
// is then refined by exchanges (a probe out, a better candidate in, kept when the held-out candidates'
// error drops beyond its noise; bounded in work, so mostly for sets of hundreds): the result for a target
// is its own set, which need not be a prefix of a larger target's (an error bound's result and large
// targets are the greedy's order). The curve's points before the last are the greedy's
// rounds; its last point is the result's estimate.
#pragma once

#include "bake/placement_signal.h"
#include "bake/progress.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

// Points with their signal: the candidates, or the validation points.
struct SignalPoints {
    std::vector<float> positions;  // 3 per point, world
    PointSignal signal;
    std::vector<uint8_t> counted;  // per point: counts in the error
};

struct SelectionSettings {
    uint32_t target_count = 0;  // stop at this many (0: no target)
    double error_bound = 0;     // stop at the first count whose estimate is at most this (0: none)
    uint32_t threads = 1;
    bool exchange = true;       // refine a target's set by exchanges (off: every count a prefix of the greedy's order)
};

struct ErrorCurvePoint {
    uint32_t probes = 0;
    double error = 0;  // estimated, see above
};

struct Selection {
    std::vector<uint32_t> order;         // candidate indices in the order chosen (an exchanged probe's
                                         // replacement takes its place): the result
    std::vector<ErrorCurvePoint> curve;  // one point per round, counts increasing, ending at the result
};

// Chooses probes among the candidates until the target or the bound (one of them is set). The result
// depends only on the input, not on the thread count. Throws Error(Status::cancelled) from progress.
Selection select_probes(const SignalPoints& candidates, const SignalPoints& validation, const SelectionSettings& settings,
                        const Progress& progress);

}  // namespace tetprobe
