#include "bake/probe_placement.h"

#include "bake/lighting_bake.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <string>

namespace tetprobe {

namespace {

// The part of the caller's progress each stage reports into.
constexpr double kCandidatesEnd = 0.3, kBakeEnd = 0.6;

}  // namespace

size_t placement_bound(const Scene& scene, const PlacementSettings& settings) {
    return candidate_bound(scene, settings.rules);
}

Placement place_probes(const Scene& scene, const PlacementSettings& settings) {
    if (!(settings.error_bound >= 0) || !std::isfinite(settings.error_bound))
        throw Error(Status::invalid_argument, "error_bound must be zero (none) or positive");
    if (settings.rays == 0) throw Error(Status::invalid_argument, "rays must be at least 1");
    const Progress& progress = settings.progress;

    const Candidates candidates = find_candidates(scene, settings.rules, settings.threads, progress.part(0, kCandidatesEnd));
    const size_t count = candidates.positions.size() / 3;
    if (count == 0)
        throw Error(Status::degenerate, "no candidate passes the rules: every one of the " +
                                            std::to_string(candidates.grid_points) +
                                            " grid points is inside geometry, closer than the margin to a surface" +
                                            (settings.rules.mode == PlacementMode::walkable ? " or not above a floor" : "") +
                                            " (lower the spacing or the margin)");
    if (settings.target_count > count)
        throw Error(Status::invalid_argument, "target_count " + std::to_string(settings.target_count) + " is more than the " +
                                                  std::to_string(count) + " candidates that pass the rules (of " +
                                                  std::to_string(candidates.grid_points) +
                                                  " grid points): lower the spacing or the target");

    Placement placement;
    placement.candidates = count;
    placement.held_out = candidates.held_out.size() / 3;
    const bool pruning = (settings.target_count > 0 && settings.target_count < count) ||
                         (settings.target_count == 0 && settings.error_bound > 0);
    if (!pruning) {
        placement.positions = candidates.positions;
        placement.curve.push_back({uint32_t(count), 0.0});
        progress.report(1.0, "done");
        return placement;
    }

    BakeSettings bake;
    bake.rays = settings.rays;
    bake.bounces = settings.bounces;
    bake.seed = settings.seed;
    bake.threads = settings.threads;
    bake.progress = progress.part(kCandidatesEnd, kBakeEnd);
    const std::vector<float> sh = bake_lighting(scene, candidates.positions, bake);

    PruneSettings prune;
    prune.target_count = settings.target_count;
    prune.error_bound = settings.error_bound;
    prune.threads = settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
    const PruneResult pruned = prune_probes(candidates.positions, sh, candidates.held_out, prune, progress.part(kBakeEnd, 1.0));
    for (uint32_t i : pruned.kept)
        for (int a = 0; a < 3; ++a) placement.positions.push_back(candidates.positions[3 * size_t(i) + a]);
    placement.curve = pruned.curve;
    progress.report(1.0, "done");
    return placement;
}

}  // namespace tetprobe
