#include "bake/probe_placement.h"

#include "bake/placement_signal.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <unordered_map>

namespace tetprobe {

namespace {

// The part of the caller's progress each stage reports into.
constexpr double kCandidatesEnd = 0.25, kBakeEnd = 0.6;
// A tetrahedral set needs four probes.
constexpr size_t kLeastCandidates = 4;

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// Per point: 1 when it is at least `clearance` from every point and spot light (a hash grid of the
// lights by cells of the clearance).
std::vector<uint8_t> clear_of_lights(const Scene& scene, const std::vector<float>& points, double clearance) {
    const size_t count = points.size() / 3;
    std::vector<uint8_t> clear(count, 1);
    if (!(clearance > 0)) return clear;
    auto key = [&](double x, double y, double z) {
        const int64_t c[3] = {int64_t(std::floor(x / clearance)), int64_t(std::floor(y / clearance)), int64_t(std::floor(z / clearance))};
        return uint64_t(c[0] * 73856093) ^ uint64_t(c[1] * 19349663) ^ uint64_t(c[2] * 83492791);
    };
    std::unordered_multimap<uint64_t, const Light*> grid;
    for (const Light& light : scene.lights())
        if (light.positional()) grid.emplace(key(light.position[0], light.position[1], light.position[2]), &light);
    if (grid.empty()) return clear;
    for (size_t i = 0; i < count; ++i) {
        const double p[3] = {points[3 * i], points[3 * i + 1], points[3 * i + 2]};
        for (int dz = -1; dz <= 1 && clear[i]; ++dz)
            for (int dy = -1; dy <= 1 && clear[i]; ++dy)
                for (int dx = -1; dx <= 1 && clear[i]; ++dx) {
                    const auto range = grid.equal_range(key(p[0] + dx * clearance, p[1] + dy * clearance, p[2] + dz * clearance));
                    for (auto it = range.first; it != range.second; ++it) {
                        double d2 = 0;
                        for (int a = 0; a < 3; ++a) d2 += (p[a] - it->second->position[a]) * (p[a] - it->second->position[a]);
                        if (d2 < clearance * clearance) clear[i] = 0;
                    }
                }
    }
    return clear;
}

}  // namespace

size_t placement_bound(const Scene& scene, const PlacementSettings& settings) {
    return candidate_bound(scene, settings.rules, settings.threads);
}

Placement place_probes(const Scene& scene, const PlacementSettings& settings) {
    if (!(settings.error_bound >= 0) || !std::isfinite(settings.error_bound))
        throw Error(Status::invalid_argument, "error_bound must be zero (none) or positive");
    if (!(settings.light_clearance >= 0) || !std::isfinite(settings.light_clearance))
        throw Error(Status::invalid_argument, "light_clearance must be zero or positive and finite");
    if (settings.rays < 2) throw Error(Status::invalid_argument, "rays must be at least 2 (two half bakes measure the noise)");
    const Progress& progress = settings.progress;

    Candidates found = find_candidates(scene, settings.rules, settings.seed, settings.threads, progress.part(0, kCandidatesEnd));
    const size_t count = found.positions.size() / 3;
    const std::string tested = std::to_string(found.tested) + " points tested" +
                               (found.unreached ? ", " + std::to_string(found.unreached) + " unreachable from the playable seeds" : "");
    if (count < kLeastCandidates) {
        const std::string what = count == 0 ? "no candidate passes"
                               : "only " + std::to_string(count) + (count == 1 ? " candidate passes" : " candidates pass");
        throw Error(Status::degenerate,
                    what + " the rules (spacing " + number(settings.rules.spacing) + ", " + tested + "): every point is inside geometry, " +
                        "closer than the margin to a surface" +
                        (settings.rules.mode == PlacementMode::walkable ? ", not above a floor" : "") +
                        " or out of the playable space; a probe volume needs at least 4 (lower the spacing or the margin)");
    }
    if (settings.target_count > count)
        throw Error(Status::invalid_argument, "target_count " + std::to_string(settings.target_count) + " is more than the " +
                                                  std::to_string(count) + " candidates that pass the rules (spacing " +
                                                  number(settings.rules.spacing) + ", " + tested + "): lower the spacing or the target");

    Placement placement;
    placement.candidates = count;
    placement.unreached = found.unreached;
    if (settings.target_count == 0 && settings.error_bound == 0) {
        placement.positions = std::move(found.positions);
        progress.report(1.0, "done");
        return placement;
    }

    // One bake of candidates and validation points together.
    SignalPoints candidates, validation;
    candidates.positions = std::move(found.positions);
    validation.positions = std::move(found.validation);
    placement.validation_points = validation.positions.size() / 3;
    std::vector<float> both = candidates.positions;
    both.insert(both.end(), validation.positions.begin(), validation.positions.end());
    BakeSettings bake;
    bake.rays = settings.rays;
    bake.bounces = settings.bounces;
    bake.seed = settings.seed;
    bake.threads = settings.threads;
    PointSignal signal = measure_signal(scene, both, bake, progress.part(kCandidatesEnd, kBakeEnd));
    both.clear();
    both.shrink_to_fit();
    const auto split = [&](SignalPoints& part, size_t first, size_t n) {
        part.signal.value.assign(signal.value.begin() + std::ptrdiff_t(kSignalSize * first),
                                 signal.value.begin() + std::ptrdiff_t(kSignalSize * (first + n)));
        part.signal.noise.assign(signal.noise.begin() + std::ptrdiff_t(first), signal.noise.begin() + std::ptrdiff_t(first + n));
    };
    split(candidates, 0, count);
    split(validation, count, placement.validation_points);
    signal = PointSignal();
    candidates.counted = clear_of_lights(scene, candidates.positions, settings.light_clearance);
    validation.counted = clear_of_lights(scene, validation.positions, settings.light_clearance);
    // Lights everywhere: the clearance would leave nothing to measure, so everything counts.
    if (size_t(std::count(candidates.counted.begin(), candidates.counted.end(), 1)) < kLeastCandidates ||
        std::count(validation.counted.begin(), validation.counted.end(), 1) == 0) {
        std::fill(candidates.counted.begin(), candidates.counted.end(), 1);
        std::fill(validation.counted.begin(), validation.counted.end(), 1);
    }

    SelectionSettings select;
    select.target_count = settings.target_count;
    select.error_bound = settings.error_bound;
    select.threads = settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
    const Selection chosen = select_probes(candidates, validation, select, progress.part(kBakeEnd, 1.0));
    placement.positions.reserve(3 * chosen.order.size());
    for (uint32_t i : chosen.order)
        placement.positions.insert(placement.positions.end(), &candidates.positions[3 * size_t(i)],
                                   &candidates.positions[3 * size_t(i)] + 3);
    placement.curve = chosen.curve;
    progress.report(1.0, "done");
    return placement;
}

}  // namespace tetprobe
