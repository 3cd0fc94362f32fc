// One scene of the methods and precision benchmarks: its probes baked once, the query points, the moving
// object's path, the slice, and the references baked directly at all of them with tp_bake (the same rays,
// bounces and seed as the probes, so the reference is the same estimator as the probes).
#pragma once

#include "capi/tetprobe.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace bench {

struct MethodSettings {
    bool quick = false;
    uint32_t rays = 512;
    uint32_t bounces = 2;
    uint64_t seed = 1;
    size_t queries = 2000;
    size_t frames = 600;
    int slice_size = 64;
};

MethodSettings method_settings(bool quick);

// The 6 axis normals every error is measured on; the path trace and the slice use kUp.
extern const float kAxisNormals[6][3];
extern const float kUp[3];

// Rec. 709 luminance of the irradiance of sh for normal n (tp_sh_eval_irradiance).
float irradiance_luminance(const float sh[27], const float n[3]);

// Bakes positions with tp_bake and the settings; throws std::runtime_error with tp_last_error on failure.
std::vector<float> bake_at(const tp_scene* scene, const std::vector<float>& positions, const MethodSettings& settings,
                           uint64_t seed);

struct MethodScene {
    std::string name, file, probe_source;
    tp_scene* scene = nullptr;
    std::vector<float> probes, probe_sh;  // 3 and 27 floats per probe
    float probe_min[3], probe_max[3];
    float query_min[3], query_max[3];
    std::vector<float> queries, reference, second_reference;  // second: another seed (the noise)
    std::vector<float> path, path_reference;                  // path reference: common random numbers
    size_t path_bad_frames = 0;  // frames inside geometry or crossing a surface (0 unless no loop avoided them)
    float slice_height = 0;
    float slice_x[2], slice_z[2];
    std::vector<float> slice_points, slice_reference;
    double mean_irradiance = 0;  // of the reference over the queries and the 6 normals

    MethodScene() = default;
    MethodScene(const MethodScene&) = delete;
    MethodScene& operator=(const MethodScene&) = delete;
    ~MethodScene();
};

// Loads and bakes everything above. with_slice = false skips the slice (the precision benchmark).
void prepare_method_scene(const std::string& path, const MethodSettings& settings, bool with_slice, MethodScene* out);

}  // namespace bench

namespace bench {

// Command line of `tetprobe_bench methods|precision`: --out DIR (default build/bench), --quick, --scene PATH
// (repeatable; default: the sample scenes given, relative to the repository root).
struct MethodArgs {
    bool quick = false;
    std::string out = "build/bench";
    std::vector<std::string> scenes;
};

MethodArgs parse_method_args(int argc, char** argv, const std::vector<std::string>& default_scenes);

// Relative error statistics of luminance irradiance against a reference (see the schema in bench_methods.cpp).
struct ErrorStats {
    double sum_squares = 0, max = 0;
    size_t count = 0;
    void add(double relative_error) {
        sum_squares += relative_error * relative_error;
        max = std::max(max, std::fabs(relative_error));
        ++count;
    }
    double rms() const { return count ? std::sqrt(sum_squares / double(count)) : 0.0; }
};

}  // namespace bench

namespace bench {

// Repetitions of a timed loop so that one run takes about target_seconds (at least 1, at most
// max_repetitions): one untimed pass sets the scale, so a slow method is not run for minutes.
size_t repetitions_for(const std::function<void()>& one_pass, double target_seconds, size_t max_repetitions);

}  // namespace bench
