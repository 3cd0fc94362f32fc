// Candidate probe positions for automatic placement: a grid over the scene's bounds, kept where a
// probe is useful and safe. Kept points are outside geometry (bake/inside_test.h), at least `margin`
// from every surface, and in the walkable mode within a height band above an upward-facing surface
// (up is +y: the first surface straight below faces up, within 45 degrees, and lies between
// walk_min_height and walk_max_height below the point). The same rules pick held-out points on the
// grid shifted by half a spacing (the cells' centres), where pruning measures its error.
#pragma once

#include "bake/parallel_jobs.h"
#include "bake/ray_caster.h"
#include "bake/scene.h"
#include "core/option_defaults.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetprobe {

enum class PlacementMode : uint32_t { whole = 0, walkable = 1 };

// Grid points (candidates and held-out points together) above this are refused: each is tested with
// dozens of rays and kept ones are baked.
constexpr size_t kMaxPlacementGridPoints = 250000;

struct CandidateRules {
    PlacementMode mode = PlacementMode::whole;
    double spacing = kDefaultPlacementSpacing;        // world units between grid points
    double margin = kDefaultPlacementMargin;          // least distance from every surface
    double walk_min_height = kDefaultWalkMinHeight;   // walkable: the band above the floor
    double walk_max_height = kDefaultWalkMaxHeight;
};

struct Candidates {
    std::vector<float> positions;  // 3 per candidate, world, in grid order (x fastest, then y, z)
    std::vector<float> held_out;   // 3 per held-out point
    size_t grid_points = 0;        // candidate grid points before the rules
};

// The number of candidate grid points the rules give for the scene (an upper bound of the
// candidates). Throws Error(Status::invalid_argument) for a spacing that is not positive, a negative
// margin, a margin larger than the scene, a bad height band or too many grid points, and
// Error(Status::scene) for a scene without meshes.
size_t candidate_bound(const Scene& scene, const CandidateRules& rules);

// The candidates and held-out points. Throws as candidate_bound, Error(Status::scene) when the inside
// test cannot decide (bake/inside_test.h) and Error(Status::cancelled) from the progress callback.
Candidates find_candidates(const Scene& scene, const CandidateRules& rules, uint32_t threads,
                           const ProgressRange& progress);

// Whether no surface lies closer than margin to the local point (margin 0: always).
bool clear_of_surfaces(const RayCaster& caster, const float local[3], double margin);

}  // namespace tetprobe
