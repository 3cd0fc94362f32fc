// The probe sets tetprobe is measured with on a real level, each a choice among the same candidates (the
// walkable placement's candidates, tp_place_probes without pruning): placement itself (tp_place_probes,
// walkable, target N), a random subsample (seeded), a uniform lattice pick, and all candidates. Every
// chosen probe's SH is the candidates' one bake (the level's probe settings), so choices differ only in
// which probes they keep.
#pragma once

#include "level_reference.h"

#include <cstdint>
#include <vector>

namespace bench {

struct PlacementRules {
    float spacing = 1.0f;        // walkable mode's candidate grid (metres)
    float walk_min_height = 0.0f, walk_max_height = 2.0f;  // tp_placement_options' defaults
    uint32_t rays = 128;         // placement's own candidate bake (its default)
};

struct CandidateSet {
    std::vector<float> positions, sh;  // 3 and 27 floats per candidate
    double find_seconds = 0, bake_seconds = 0;
};

// The candidates and their bake. Throws std::runtime_error with tp_last_error.
CandidateSet find_candidates(const Level& level, const PlacementRules& rules, const LevelSettings& settings);

// tp_place_probes with target N (error bound 0): the placed positions; *seconds its time.
std::vector<float> placed_probes(const Level& level, const PlacementRules& rules, uint32_t target, double* seconds);

// One placement to `target` probes (walkable, error bound 0) with its error curve, its time and how often it
// reported progress: the curve's points before the last are the greedy's rounds; the positions are the set for
// target, exchanged there (a prefix of them is the greedy's set for that count only where no exchange ran,
// e.g. targets of about 1,000 and more).
struct PlacementRun {
    std::vector<float> positions;
    std::vector<float> curve;  // (probes, estimated error) pairs, counts increasing
    double seconds = 0;
    size_t progress_calls = 0;
};
PlacementRun placement_run(const Level& level, const PlacementRules& rules, uint32_t target, uint32_t threads);

// The curve's estimated error at `probes`: exact at a round's count, else linear in log(probes) between the
// rounds around it; NaN outside the curve.
double curve_error_at(const std::vector<float>& curve, size_t probes);

// Indices of N candidates: a seeded random subsample; a uniform lattice pick (the cells of the coarsest cubic
// lattice that has at least N occupied cells each keep the candidate nearest their centre, the N nearest of
// those are kept).
std::vector<uint32_t> random_pick(size_t candidates, size_t n, uint64_t seed);
std::vector<uint32_t> lattice_pick(const std::vector<float>& positions, size_t n);

// The candidates at the given positions (exactly equal floats), with their SH; positions that are not
// candidates are baked. Returns 27 floats per position.
std::vector<float> sh_of(const Level& level, const CandidateSet& candidates, const std::vector<float>& positions,
                         const LevelSettings& settings);

}  // namespace bench
