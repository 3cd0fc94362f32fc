// The playable space of a level, as the real-level benchmark defines it once for every method: the
// points of a grid (spacing horizontally, layer vertically) that stand in the walkable band above an
// upward-facing surface (band_min to band_max above it, and clear of the next surface above), that are
// not inside geometry (bake/inside_test.h), and that a flood fill from the level's spawn points reaches,
// two grid neighbours (26-connected) being connected when the straight segment between them crosses no
// surface. The void outside a sealed level, and closed-off pockets, never count.
#pragma once

#include "bake/scene.h"

#include <cstddef>
#include <cstdint>
#include <vector>


namespace bench {

struct PlayableSpaceSettings {
    double spacing = 0.5;          // metres between grid columns
    double layer = 0.45;           // metres between grid layers
    double band_min = 0.2, band_max = 2.0;  // the walkable band above a floor, metres
    double floor_cosine = 0.7071;  // a floor faces up within 45 degrees (its front side)
    double clearance = 0.1;        // a point stays this far below the next surface above it
};

struct PlayableSpace {
    PlayableSpaceSettings settings;
    double grid_origin[3] = {0, 0, 0};  // world position of grid point (0, 0, 0)
    int64_t dims[3] = {0, 0, 0};
    std::vector<float> points;              // 3 per reachable point (world), in grid order
    std::vector<int64_t> cells;             // grid index of each reachable point (x fastest, then y, z)
    std::vector<uint32_t> neighbour_start;  // CSR of the connections among reachable points
    std::vector<uint32_t> neighbours;
    std::vector<uint32_t> seeds;            // the reachable point each spawn point starts from
    size_t band_points = 0, free_points = 0;  // points of the band; of those, not inside geometry
    size_t spawns_used = 0, spawns_given = 0;
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  // bounds of the reachable points

    size_t count() const { return points.size() / 3; }
};

// Finds the playable space. spawn_points: 3 floats each (world). Throws std::runtime_error when no
// spawn point reaches the space.
PlayableSpace find_playable_space(const tetprobe::Scene& scene, const std::vector<float>& spawn_points,
                                  const PlayableSpaceSettings& settings, uint32_t threads);

// The shortest path (fewest grid steps) between two reachable points along the connections, as the
// points' indices from `from` to `to`; empty when they are not connected.
std::vector<uint32_t> grid_path(const PlayableSpace& space, uint32_t from, uint32_t to);

// `count` free points of the playable space: a reachable grid point drawn at random (seeded), moved by
// a uniform offset within half a grid step on each axis, kept when the straight move from the grid
// point crosses no surface and the point keeps `clearance` from every position in `avoid` (3 floats
// each: point lights, whose 1/d^2 peak would dominate every method's error alike).
std::vector<float> draw_free_points(const tetprobe::Scene& scene, const PlayableSpace& space, size_t count,
                                    uint64_t seed, const std::vector<float>& avoid, double clearance);

// The connected component of each reachable point (0, 1, ...: jump pads and teleporters can split a level's
// walkable space into parts that spawn points reach separately).
std::vector<uint32_t> component_labels(const PlayableSpace& space);

// A walk along grid_path from `from` to `to`, one frame every `step` metres along its segments (3 floats
// per frame); empty when they are not connected.
std::vector<float> walking_path(const PlayableSpace& space, uint32_t from, uint32_t to, double step);

}  // namespace bench
