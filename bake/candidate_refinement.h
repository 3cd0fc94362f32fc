// Where the light changes between neighbouring candidates, placement adds candidates half way between
// them: a difference of baked values far above what the two-half bake measures as noise is light that
// changes within a spacing, the place a coarse lattice cannot follow.
#pragma once

#include "bake/placement_signal.h"

#include <cstddef>
#include <vector>

namespace tetprobe {

// A changing pair's difference exceeds this many noise deviations of the difference.
constexpr double kRefineDeviations = 4.0;

// Refinement adds at most this many candidates per coarse one: it bounds the extra bake and selection
// time and memory (a quarter more), and keeps the strongest changes.
constexpr double kRefineShare = 0.25;

struct ChangingPairs {
    std::vector<float> a, b;  // 3 floats per pair each: the two candidates (world)
};

// Pairs of candidates at most 1.5 spacings apart whose signal differs by more than kRefineDeviations
// deviations of its noise, the largest difference beyond the noise first, at most `limit` pairs.
ChangingPairs changing_pairs(const std::vector<float>& positions, const PointSignal& signal, double spacing, size_t limit);

}  // namespace tetprobe
