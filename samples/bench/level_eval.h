// Running one interpolation method on a level the same way for every method: its SH at the evaluation
// points (each query alone: no hint, no history), its SH along the walking paths (one moving object per
// path, keeping its hint or state from frame to frame) and the time of those path queries (ns per query,
// the median of kRepetitions runs over every frame). A method is a pair of callables: reset() starts a new
// object, query(position, out_sh) answers one frame; templates keep them inlined in the timed loop.
#pragma once

#include "bench_timing.h"
#include "level_metric.h"
#include "level_reference.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// One method on one level at one budget: what every table and plot of the real-level part reads.
struct LevelResult {
    std::string method;      // e.g. "tetprobe_placed", "grid_dilated_unorm8"
    std::string layout;      // the tetprobe store layout, or the peer's encoding
    std::string label;
    size_t probes = 0;
    uint64_t bytes = 0;           // what ships: the store blob, or the peer's run-time arrays
    uint64_t resident_bytes = 0;  // in memory after loading (tetprobe: the heap a loaded store holds)
    LevelError error;
    double ns_per_query = 0;
    double placement_seconds = 0, bake_seconds = 0, build_seconds = 0;
    std::string note;

    nlohmann::ordered_json json() const;
};

template <class Reset, class Query>
std::vector<float> sh_at_points(const Level& level, Reset reset, Query query) {
    const size_t count = level.points.size() / 3;
    std::vector<float> out(27 * count);
    for (size_t i = 0; i < count; ++i) {
        reset();
        query(&level.points[3 * i], &out[27 * i]);
    }
    return out;
}

template <class Reset, class Query>
std::vector<float> sh_on_paths(const Level& level, Reset reset, Query query) {
    std::vector<float> out(level.path_points.size() / 3 * 27);
    size_t frame = 0;
    for (uint32_t frames : level.path_frames) {
        reset();
        for (uint32_t f = 0; f < frames; ++f, ++frame) query(&level.path_points[3 * frame], &out[27 * frame]);
    }
    return out;
}

template <class Reset, class Query>
double ns_on_paths(const Level& level, Reset reset, Query query) {
    const size_t frames_total = level.path_points.size() / 3;
    if (frames_total == 0) return 0;
    float sink = 0;
    const double seconds = median_seconds([&] {
        float out[27], acc = 0;
        const Clock::time_point t0 = Clock::now();
        size_t frame = 0;
        for (uint32_t frames : level.path_frames) {
            reset();
            for (uint32_t f = 0; f < frames; ++f, ++frame) {
                query(&level.path_points[3 * frame], out);
                acc += out[0];
            }
        }
        const double s = seconds_since(t0);
        sink += acc;
        return s;
    });
    volatile float keep = sink;
    (void)keep;
    return 1e9 * seconds / double(frames_total);
}

// Error and time of a method: the three passes above.
template <class Reset, class Query>
void measure_method(const Level& level, Reset reset, Query query, LevelResult* result) {
    result->error = level_error(level, sh_at_points(level, reset, query), sh_on_paths(level, reset, query));
    result->ns_per_query = ns_on_paths(level, reset, query);
}

}  // namespace bench
