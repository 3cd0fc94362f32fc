// The probes and the query points of the store benchmark: every method (floor, plain walk, CGAL,
// tetprobe) is timed on these same sets, generated from fixed seeds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bench {

// Side of the box the probes fill: [0, kBox]^3.
constexpr float kBox = 10.0f;

// n probes uniformly at random in the box, the 8 corners first (so the hull is the box).
std::vector<float> random_probes(size_t n, uint32_t seed);

// 27 SH floats per probe, uniform in [-1, 1].
std::vector<float> random_sh(size_t n, uint32_t seed);

// n points uniformly at random in [lo, hi]^3.
std::vector<float> random_points(size_t n, float lo, float hi, uint32_t seed);

// n points on a shell at 1.2x the box's half-diagonal around its centre (outside the hull): along a
// smooth closed path when coherent, else independent random directions.
std::vector<float> outside_points(size_t n, bool coherent, uint32_t seed);

// Objects moving through the box: each starts at a random point of [lo, hi]^3 and moves 0.2% of the
// box per frame, turning slowly, reflected at the walls. Kept in both orders: one object's whole
// path contiguous (the single-query loops, each object carrying its own hint) and one frame's
// objects contiguous (the batch calls, one per frame).
struct ObjectPaths {
    size_t objects = 0;
    size_t frames = 0;
    std::vector<float> by_object;  // [object][frame][3]
    std::vector<float> by_frame;   // [frame][object][3]

    const float* at(size_t object, size_t frame) const { return &by_object[3 * (object * frames + frame)]; }
    const float* frame(size_t f) const { return &by_frame[3 * f * objects]; }
    // Frame 0 locates each object once, untimed, to give every method its first hint; frames
    // 1..frames-1 are timed.
    size_t timed_queries() const { return objects * (frames - 1); }
};

ObjectPaths moving_objects(size_t objects, size_t frames, float lo, float hi, uint32_t seed);

}  // namespace bench
