#include "probe_choices.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <tuple>

namespace bench {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

tp_placement_options options_of(const PlacementRules& rules, uint32_t target) {
    tp_placement_options o;
    tp_placement_options_init(&o);
    o.mode = TP_PLACEMENT_WALKABLE;
    o.spacing = rules.spacing;
    o.walk_min_height = rules.walk_min_height;
    o.walk_max_height = rules.walk_max_height;
    o.rays = rules.rays;
    o.target_count = target;
    o.error_bound = 0;
    return o;
}

std::vector<float> place(const Level& level, const tp_placement_options& o) {
    size_t bound = 0;
    if (tp_place_probes_bound(level.handle.get(), &o, &bound) != TP_OK)
        throw std::runtime_error(level.name + ": tp_place_probes_bound: " + tp_last_error());
    std::vector<float> positions(3 * bound);
    size_t count = 0;
    if (tp_place_probes(level.handle.get(), &o, positions.data(), bound, &count, nullptr, 0, nullptr) != TP_OK)
        throw std::runtime_error(level.name + ": tp_place_probes: " + tp_last_error());
    positions.resize(3 * count);
    return positions;
}

}  // namespace

CandidateSet find_candidates(const Level& level, const PlacementRules& rules, const LevelSettings& settings) {
    CandidateSet c;
    auto start = std::chrono::steady_clock::now();
    c.positions = place(level, options_of(rules, 0));
    c.find_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    c.sh = bake_probes(level, c.positions, settings);
    c.bake_seconds = seconds_since(start);
    return c;
}

std::vector<float> placed_probes(const Level& level, const PlacementRules& rules, uint32_t target, double* seconds) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<float> p = place(level, options_of(rules, target));
    *seconds = seconds_since(start);
    return p;
}

PlacementRun placement_run(const Level& level, const PlacementRules& rules, uint32_t target, uint32_t threads) {
    tp_placement_options o = options_of(rules, target);
    o.threads = threads;
    PlacementRun run;
    o.progress = [](void* user, float, const char*) -> int {
        ++*static_cast<size_t*>(user);
        return 0;
    };
    o.progress_user = &run.progress_calls;
    size_t bound = 0;
    if (tp_place_probes_bound(level.handle.get(), &o, &bound) != TP_OK)
        throw std::runtime_error(level.name + ": tp_place_probes_bound: " + tp_last_error());
    run.positions.resize(3 * bound);
    run.curve.resize(2 * bound);
    size_t count = 0, points = 0;
    const auto start = std::chrono::steady_clock::now();
    if (tp_place_probes(level.handle.get(), &o, run.positions.data(), bound, &count, run.curve.data(), bound, &points) != TP_OK)
        throw std::runtime_error(level.name + ": tp_place_probes: " + tp_last_error());
    run.seconds = seconds_since(start);
    run.positions.resize(3 * count);
    run.curve.resize(2 * points);
    return run;
}

double curve_error_at(const std::vector<float>& curve, size_t probes) {
    const size_t points = curve.size() / 2;
    for (size_t k = 0; k < points; ++k) {
        const double n = curve[2 * k];
        if (n == double(probes)) return curve[2 * k + 1];
        if (n > double(probes)) {
            if (k == 0) return NAN;
            const double n0 = curve[2 * k - 2], e0 = curve[2 * k - 1], e1 = curve[2 * k + 1];
            const double t = std::log(double(probes) / n0) / std::log(n / n0);
            return e0 + t * (e1 - e0);
        }
    }
    return NAN;
}

std::vector<uint32_t> random_pick(size_t candidates, size_t n, uint64_t seed) {
    std::vector<uint32_t> all(candidates);
    std::iota(all.begin(), all.end(), 0u);
    std::mt19937_64 rng(seed);
    for (size_t i = 0; i < std::min(n, candidates); ++i)
        std::swap(all[i], all[i + size_t(rng() % (candidates - i))]);
    all.resize(std::min(n, candidates));
    std::sort(all.begin(), all.end());
    return all;
}

std::vector<uint32_t> lattice_pick(const std::vector<float>& positions, size_t n) {
    const size_t count = positions.size() / 3;
    if (n >= count) {
        std::vector<uint32_t> all(count);
        std::iota(all.begin(), all.end(), 0u);
        return all;
    }
    float lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (size_t i = 0; i < positions.size(); ++i)
        lo[i % 3] = std::min(lo[i % 3], positions[i]), hi[i % 3] = std::max(hi[i % 3], positions[i]);
    // Per occupied cell of spacing d: the candidate nearest its centre and that distance.
    auto pick = [&](double d) {
        std::map<std::tuple<int64_t, int64_t, int64_t>, std::pair<double, uint32_t>> cells;
        for (size_t i = 0; i < count; ++i) {
            int64_t c[3];
            double d2 = 0;
            for (int k = 0; k < 3; ++k) {
                const double u = (positions[3 * i + size_t(k)] - lo[k]) / d;
                c[k] = int64_t(std::floor(u));
                d2 += (u - double(c[k]) - 0.5) * (u - double(c[k]) - 0.5);
            }
            auto it = cells.emplace(std::make_tuple(c[0], c[1], c[2]), std::make_pair(d2, uint32_t(i))).first;
            if (d2 < it->second.first) it->second = {d2, uint32_t(i)};
        }
        std::vector<std::pair<double, uint32_t>> chosen;
        for (const auto& cell : cells) chosen.push_back(cell.second);
        return chosen;
    };
    double fine = 1e-6, coarse = 2.0 * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-3f});
    for (int step = 0; step < 60; ++step) {  // the coarsest spacing with at least n occupied cells
        const double mid = std::sqrt(fine * coarse);
        (pick(mid).size() >= n ? fine : coarse) = mid;
    }
    std::vector<std::pair<double, uint32_t>> chosen = pick(fine);
    std::sort(chosen.begin(), chosen.end());
    std::vector<uint32_t> out;
    for (size_t i = 0; i < n && i < chosen.size(); ++i) out.push_back(chosen[i].second);
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<float> sh_of(const Level& level, const CandidateSet& candidates, const std::vector<float>& positions,
                         const LevelSettings& settings) {
    std::map<std::tuple<float, float, float>, uint32_t> index;
    for (size_t i = 0; i < candidates.positions.size() / 3; ++i)
        index.emplace(std::make_tuple(candidates.positions[3 * i], candidates.positions[3 * i + 1], candidates.positions[3 * i + 2]),
                      uint32_t(i));
    const size_t count = positions.size() / 3;
    std::vector<float> sh(27 * count), missing;
    std::vector<size_t> missing_at;
    for (size_t i = 0; i < count; ++i) {
        const auto it = index.find(std::make_tuple(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]));
        if (it == index.end()) {
            missing.insert(missing.end(), &positions[3 * i], &positions[3 * i] + 3);
            missing_at.push_back(i);
        } else {
            std::copy(&candidates.sh[27 * it->second], &candidates.sh[27 * it->second] + 27, &sh[27 * i]);
        }
    }
    if (!missing.empty()) {
        const std::vector<float> baked = bake_probes(level, missing, settings);
        for (size_t m = 0; m < missing_at.size(); ++m) std::copy(&baked[27 * m], &baked[27 * m] + 27, &sh[27 * missing_at[m]]);
    }
    return sh;
}

}  // namespace bench
