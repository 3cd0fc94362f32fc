// Candidate probe positions for automatic placement, only where a probe is useful and safe, and the
// validation points placement measures its error at.
//
// Candidates stand on a lattice of `spacing`. The whole mode takes the lattice points over the scene's
// bounds; the walkable mode takes vertical columns of it, finds every upward-facing surface along each
// (up is the scene's up, Scene::up; a floor faces up within 45 degrees, a one-sided surface seen from
// behind is none), and
// stands points above each floor across the height band [walk_min_height, walk_max_height], a spacing
// apart, cut off `margin` below the next surface above the floor and at the scene's bounds. Kept points
// are outside geometry (bake/inside_test.h) and at least `margin` from every surface. When the scene
// has playable seeds (a level's spawn points), only candidates connected to them are kept: two
// candidates of neighbouring columns (or of one column) less than 1.5 spacings apart in height are
// connected when the segment between them crosses no surface, and a seed joins the nearest candidate
// within two spacings that it sees. Work runs column by column and memory grows with the candidates,
// never with the bounding box.
//
// Validation points: free points drawn uniformly over the volume the candidates stand for, up to the
// walls (a candidate, drawn in proportion to its box's volume, moved within half a spacing of it
// horizontally, a whole spacing toward a side without a neighbouring candidate, and within its share of
// the band vertically; kept when the move crosses no surface, the point is not inside geometry and, in
// the walkable mode, the point itself stands in the band above a floor, as candidates do: the first
// surface below it faces up and lies between the band's bottom and walk_max_height under it, so a box
// reaching past a ledge or onto a slope too steep to stand on measures no air where nothing walks), one
// for every four candidates (at least 1,024 when there are that many candidates, at most 16,384).
#pragma once

#include "bake/progress.h"
#include "bake/ray_caster.h"
#include "bake/scene.h"
#include "core/option_defaults.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tetprobe {

enum class PlacementMode : uint32_t { whole = 0, walkable = 1 };

// Candidates above this are refused (each costs about a hundred bytes through placement: position,
// signal, residual, weights). Points tested (lattice points of the whole mode, columns of the walkable
// mode) above kMaxPlacementTested are refused before any is tested.
constexpr size_t kMaxPlacementCandidates = size_t(1) << 22;
constexpr size_t kMaxPlacementTested = size_t(1) << 28;

struct CandidateRules {
    PlacementMode mode = PlacementMode::whole;
    double spacing = kDefaultPlacementSpacing;        // world units between lattice points
    double margin = kDefaultPlacementMargin;          // least distance from every surface
    double walk_min_height = kDefaultWalkMinHeight;   // walkable: the band above the floor
    double walk_max_height = kDefaultWalkMaxHeight;
};

struct Candidates {
    std::vector<float> positions;   // 3 per candidate, world, column by column (x, then z; y within)
    std::vector<float> extents;     // 2 per candidate: the heights of the volume it stands for (along up)
    std::vector<float> validation;  // 3 per validation point
    size_t tested = 0;              // points the inside and margin tests were applied to
    size_t unreached = 0;           // candidates left out because no playable seed reaches them
};

// The number of points the inside and margin tests are applied to (an upper bound of the candidates;
// the walkable mode casts a few rays per column to find the floors). Throws Error(Status::invalid_argument)
// for a spacing that is not positive, a negative margin, a margin larger than the scene, a bad height
// band or too many points, and Error(Status::scene) for a scene without meshes.
size_t candidate_bound(const Scene& scene, const CandidateRules& rules, uint32_t threads = 0);

// The candidates and validation points (`seed` draws the validation offsets). Throws as candidate_bound,
// Error(Status::invalid_argument) when more than kMaxPlacementCandidates pass, Error(Status::scene) when
// the inside test cannot decide (bake/inside_test.h) or no playable seed sees a candidate, and
// Error(Status::cancelled) from the progress callback.
Candidates find_candidates(const Scene& scene, const CandidateRules& rules, uint64_t seed, uint32_t threads,
                           const Progress& progress);

// Whether no surface lies closer than margin to the local point (margin 0: always).
bool clear_of_surfaces(const RayCaster& caster, const float local[3], double margin);

}  // namespace tetprobe
