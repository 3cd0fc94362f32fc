// Candidate probe positions for automatic placement, kept where a probe is useful and safe. The whole
// mode takes a grid over the scene's bounds; the walkable mode takes columns of that grid, finds
// every upward-facing surface along each (up is the scene's up, Scene::up; a floor faces up within 45 degrees, a one-sided
// surface seen from behind is none), and stands points above each floor across the height band
// [walk_min_height, walk_max_height], a spacing apart, cut off `margin` below the next surface above
// the floor and at the scene's bounds. Kept points are outside geometry
// (bake/inside_test.h) and at least `margin` from every surface. The same rules pick held-out points
// on the grid shifted by half a spacing (the cells' centres), where pruning measures its error.
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

// Points (candidates and held-out points together) above this are refused: each is tested with
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
    size_t grid_points = 0;        // candidate points before the inside and margin tests
};

// The number of candidate points before the inside and margin tests (an upper bound of the
// candidates; the walkable mode casts a few rays per column to find the floors). Throws Error(Status::invalid_argument) for a spacing that is not positive, a negative
// margin, a margin larger than the scene, a bad height band or too many grid points, and
// Error(Status::scene) for a scene without meshes.
size_t candidate_bound(const Scene& scene, const CandidateRules& rules);

// The candidates and held-out points. Throws as candidate_bound, Error(Status::scene) when the inside
// test cannot decide (bake/inside_test.h) and Error(Status::cancelled) from the progress callback.
Candidates find_candidates(const Scene& scene, const CandidateRules& rules, uint32_t threads,
                           const Progress& progress);

// Whether no surface lies closer than margin to the local point (margin 0: always).
bool clear_of_surfaces(const RayCaster& caster, const float local[3], double margin);

}  // namespace tetprobe
