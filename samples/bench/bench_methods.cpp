// tetprobe_bench methods | precision [--out DIR] [--quick] [--scene PATH]...: parts 1 and 2 of issue 8.
// Every method answers the same query points and the same path, against a reference baked with tp_bake
// directly at each point (the same rays, bounces and seed as the probes: the same estimator). Writes
// DIR/methods.json and DIR/precision.json (DIR defaults to build/bench) for samples/bench/report.py.
//
// JSON schema (stable: fields may be added, none renamed or removed).
// Irradiance is a scalar: the Rec. 709 luminance 0.2126 R + 0.7152 G + 0.0722 B of E(n) (tp_sh_eval_irradiance).
// An error is |E_method(p, n) - E_reference(p, n)| over every query point p and each of the 6 axis normals n,
// divided by "mean_irradiance" (the mean of E_reference over the same points and normals): rms_error is the
// root mean square of that, max_error its maximum.
//
// methods.json
// {
//   "schema": "tetprobe-bench-methods/1", "quick": bool,
//   "bake": {"rays": int, "bounces": int, "seed": int, "why": str},      // one setting for probes, grids, references
//   "irradiance": str, "error": str, "popping": str, "timing": str,         // the definitions, in words
//   "damping": {"time_constant_frames": float, "frame_seconds": float, "alpha": float, "rule": str},
//   "scenes": [{
//     "name": str, "file": str,
//     "probes": int, "probe_source": "scene file" | "uniform",
//     "probe_bounds": {"min": [3], "max": [3]},
//     "query_box": {"min": [3], "max": [3]},   // probe bounds; an axis thinner than 1% of the diagonal widened to +-0.5
//     "queries": int,                          // uniform random points in query_box (seeded)
//     "query_rule": str,                       // points inside geometry or within 0.5 of a point/spot light are redrawn
//     "bake_seconds": float,                   // time to bake probes and references of this scene
//     "reference_noise": float,                // rms_error (as defined above) of a second reference with another
//                                              // seed against the first (the noise of both references)
//     "mean_irradiance": float,
//     "path": {"frames": int, "points": [[x, y, z], ...], "normal": [3],
//              "bad_frames": int,     // frames inside geometry or crossing a surface (0 unless no loop avoided them)
//              "reference_trace": [E per frame for "normal", relative to mean_irradiance],
//              "reference_worst_jump": float, // the reference's own worst frame-to-frame jump (see "popping")
//              "reference_note": str},
//     "methods": [{
//       "id": "tetrahedral_fast" | "tetrahedral_compact" | "grid_equal_count" | "grid_equal_memory"
//             | "knn4" | "knn4_damped",
//       "label": str,              // human-readable name for tables and legends
//       "note": str,               // only where a metric needs explaining (knn4_damped)
//       "probes": int,             // probes this method blends (grids: nx*ny*nz)
//       "grid": [nx, ny, nz] | null,
//       "bytes": int,              // bytes of the method's run-time data
//       "rms_error": float, "max_error": float,
//       "path_rms_error": float, "path_max_error": float,  // the same errors at the path's frames (damping included)
//       "worst_jump": float,       // popping along the path (same definition as reference_worst_jump)
//       "ns_per_query": float,     // single queries along the path, each with its hint/state, median of 5 runs
//       "at_probes_max_error": float | null,  // max error at the probe positions against the probes' own bake
//       "trace": [E per frame along the path for path.normal, relative to mean_irradiance]
//     }],
//     "slice": {"axis": "y", "height": float, "normal": [3],
//               "x": [min, max], "z": [min, max], "nx": int, "nz": int,   // row-major: row = z index, column = x index
//               "cells": str,       // values at the centres of nx x nz equal cells spanning x and z
//               "reference": [nx*nz floats, E relative to mean_irradiance],
//               "methods": {"<method id>": [nx*nz floats], ...}}
//   }]
// }
//
// precision.json (one scene, two rooms, unless --scene is given; the same queries, path and reference as methods.json)
// {
//   "schema": "tetprobe-bench-precision/1", "quick": bool, "bake": {...as above}, "error": str,
//   "sh_options": str,            // how the evaluation choices are applied (per query or per probe)
//   "sloan_strength_rule": str,   // how the fixed strength of Sloan's window is chosen
//   "rule": str,                  // how a winner is chosen: error first (ties within "tie_margin"), then ns, then bytes
//   "scenes": [{
//     "name": str, "file": str, "probes": int, "queries": int, "mean_irradiance": float,
//     "reference_noise": float, "tie_margin": float,   // tie_margin: that of the "overall" decision
//     "sloan_strength": float,
//     "rows": [{
//       "id": str,                 // e.g. "half_fast_L2_none"
//       "precision": "float32" | "half", "layout": "fast" | "compact",
//       "order": "L2" | "L1" | "ZH3", "window": "none" | "sloan" | "nonnegative",
//       "applied": "per query" | "per probe",  // the non-negative window is applied to each probe once
//       "rms_error": float, "max_error": float,
//       "negative_fraction": float, // fraction of query points whose tp_sh_min_irradiance (any channel) < 0
//       "ns_per_query": float,      // interpolate + evaluate one normal, along the path with hints, median of 5
//       "bytes_per_probe": float,   // the store's bytes per probe if its SH section held only what the order reads
//                                   // (L1, and ZH3 per query: 12 coefficients; L2 and ZH3 per probe: 27) at this
//                                   // precision
//       "store_bytes_per_probe": float, // the store as built today (27 coefficients)
//       "at_probes_max_error": float    // at the probe positions against their own bake evaluated with the same
//                                       // options (float32: exactly 0; half: the rounding to half)
//     }],
//     "decisions": [{
//       "question": "precision and layout" | "order and window" | "overall",
//       "candidates": [row ids],
//       "winner": row id,
//       "why": str,
//       "tied": [row ids],         // rows within the noise of the lowest-error row (paired test, see "rule")
//       "tie_margin": float        // the largest paired margin among the tied rows, on the RMS scale
//     }]
//   }]
// }
#include "bench.h"

#include "bench_timing.h"
#include "grid_peer.h"
#include "knn_peer.h"
#include "method_json.h"
#include "method_scene.h"

#include "capi/tetprobe.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>

namespace {

using namespace bench;
using Json = nlohmann::ordered_json;

// Exponential smoothing of the KNN blend: a time constant of 6 frames (0.1 s at 60 frames per second).
constexpr double kDampingFrames = 6.0;
constexpr double kFrameSeconds = 1.0 / 60.0;
// Single queries timed per repetition (the path, repeated).
// A timed run lasts about this long (medians of 5 runs), at most kMaxTimedQueries queries.
constexpr double kTimedSeconds = 0.05;
constexpr size_t kMaxTimedQueries = 200000;

// A method answers a point with 27 SH floats. point_query answers independent points (a still object);
// path_query follows one moving object frame after frame (hint, damping state) and is reset at the path's start.
struct Method {
    std::string id, label, note;
    size_t probes = 0;
    const int* grid = nullptr;
    size_t bytes = 0;
    std::function<void(const float*, float*)> point_query;
    std::function<void(const float*, float*)> path_query;
    std::function<void()> reset_path;
};

void check(tp_status status, const char* what) {
    if (status != TP_OK) throw std::runtime_error(std::string(what) + ": " + tp_last_error());
}

// Every frame's 6 luminances along the path, relative to the mean irradiance.
std::vector<float> path_luminances(const MethodScene& s, const std::vector<float>& sh) {
    std::vector<float> e;
    for (size_t f = 0; f < sh.size() / 27; ++f)
        for (const auto& n : kAxisNormals) e.push_back(float(irradiance_luminance(&sh[27 * f], n) / s.mean_irradiance));
    return e;
}

// Worst frame-to-frame change over the 6 normals of luminances laid out as path_luminances.
double worst_jump(const std::vector<float>& e) {
    double worst = 0;
    for (size_t i = 6; i < e.size(); ++i) worst = std::max(worst, double(std::fabs(e[i] - e[i - 6])));
    return worst;
}

std::vector<float> up_trace(const std::vector<float>& e) {
    std::vector<float> trace;
    for (size_t i = 2; i < e.size(); i += 6) trace.push_back(e[i]);  // normal 2 of kAxisNormals is +Y
    return trace;
}

// Errors of sh (27 floats per point) against reference at the same points, over the 6 normals.
ErrorStats errors(const MethodScene& s, const std::vector<float>& sh, const std::vector<float>& reference) {
    ErrorStats stats;
    for (size_t i = 0; i < sh.size() / 27; ++i)
        for (const auto& n : kAxisNormals)
            stats.add((irradiance_luminance(&sh[27 * i], n) - irradiance_luminance(&reference[27 * i], n)) /
                      s.mean_irradiance);
    return stats;
}

std::vector<float> answer_points(const std::function<void(const float*, float*)>& query, const std::vector<float>& points) {
    std::vector<float> sh(points.size() / 3 * 27);
    for (size_t i = 0; i < points.size() / 3; ++i) query(&points[3 * i], &sh[27 * i]);
    return sh;
}

Json json_vec3(const float v[3]) { return Json::array({v[0], v[1], v[2]}); }

Json evaluate_method(const MethodScene& s, const MethodSettings& settings, Method& m, Json* slices) {
    const ErrorStats query_errors = errors(s, answer_points(m.point_query, s.queries), s.reference);
    const ErrorStats probe_errors = errors(s, answer_points(m.point_query, s.probes), s.probe_sh);

    m.reset_path();
    const std::vector<float> path_sh = answer_points(m.path_query, s.path);
    const std::vector<float> e = path_luminances(s, path_sh);
    const ErrorStats path_errors = errors(s, path_sh, s.path_reference);

    // Single queries along the path, repeated; the state (hint, damping) runs on across repetitions.
    const size_t frames = s.path.size() / 3;
    float sh[27], sink = 0;
    m.reset_path();
    const size_t repetitions = repetitions_for(
        [&] {
            for (size_t f = 0; f < frames; ++f) m.path_query(&s.path[3 * f], sh);
        },
        settings.quick ? kTimedSeconds / 50 : kTimedSeconds, kMaxTimedQueries / frames + 1);
    const double seconds = median_seconds([&] {
        const Clock::time_point start = Clock::now();
        for (size_t r = 0; r < repetitions; ++r)
            for (size_t f = 0; f < frames; ++f) {
                m.path_query(&s.path[3 * f], sh);
                sink += sh[0];
            }
        return seconds_since(start);
    });
    if (sink == 12345.678f) std::printf(" ");  // keeps the loop's results alive

    if (!s.slice_points.empty()) {
        const std::vector<float> slice_sh = answer_points(m.point_query, s.slice_points);
        Json values = Json::array();
        for (size_t i = 0; i < slice_sh.size() / 27; ++i)
            values.push_back(irradiance_luminance(&slice_sh[27 * i], kUp) / s.mean_irradiance);
        (*slices)[m.id] = values;
    }

    Json j;
    j["id"] = m.id;
    j["label"] = m.label;
    if (!m.note.empty()) j["note"] = m.note;
    j["probes"] = m.probes;
    j["grid"] = m.grid ? Json::array({m.grid[0], m.grid[1], m.grid[2]}) : Json(nullptr);
    j["bytes"] = m.bytes;
    j["rms_error"] = query_errors.rms();
    j["max_error"] = query_errors.max;
    j["path_rms_error"] = path_errors.rms();
    j["path_max_error"] = path_errors.max;
    j["worst_jump"] = worst_jump(e);
    j["ns_per_query"] = 1e9 * seconds / double(repetitions * frames);
    j["at_probes_max_error"] = m.id == "knn4_damped" ? Json(nullptr) : Json(probe_errors.max);
    j["trace"] = up_trace(e);
    return j;
}

tp_store* build_store(const MethodScene& s, uint32_t flags) {
    tp_build_options options;
    tp_build_options_init(&options);
    options.flags = flags;
    tp_store* store = nullptr;
    check(tp_store_build(s.probes.data(), 0, s.probe_sh.data(), 0, s.probes.size() / 3, &options, &store),
          "tp_store_build");
    return store;
}

uint64_t store_bytes(const tp_store* store) {
    tp_store_info info;
    info.struct_size = sizeof(info);
    check(tp_store_get_info(store, &info), "tp_store_get_info");
    return info.bytes;
}

Json bench_scene(const std::string& path, const MethodSettings& settings) {
    MethodScene s;
    const Clock::time_point start = Clock::now();
    prepare_method_scene(path, settings, true, &s);
    const double bake_seconds = seconds_since(start);
    const size_t probe_count = s.probes.size() / 3;

    std::vector<Method> methods;
    tp_store* fast = build_store(s, 0);
    tp_store* compact = build_store(s, TP_BUILD_COMPACT);
    int32_t fast_hint = -1, compact_hint = -1;
    for (tp_store* store : {fast, compact}) {
        const bool is_fast = store == fast;
        int32_t* hint = is_fast ? &fast_hint : &compact_hint;
        Method m;
        m.id = is_fast ? "tetrahedral_fast" : "tetrahedral_compact";
        m.label = is_fast ? "tetrahedral (tetprobe), fast layout" : "tetrahedral (tetprobe), compact layout";
        m.probes = probe_count;
        m.bytes = store_bytes(store);
        m.point_query = [store](const float* p, float* sh) { check(tp_store_interpolate(store, p, nullptr, sh), "interpolate"); };
        m.path_query = [store, hint](const float* p, float* sh) { tp_store_interpolate(store, p, hint, sh); };
        m.reset_path = [hint] { *hint = -1; };
        methods.push_back(std::move(m));
    }
    const uint64_t fast_bytes = store_bytes(fast);

    int count_dims[3], memory_dims[3];
    grid_dims_for_count(s.probe_min, s.probe_max, probe_count, count_dims);
    grid_dims_for_count(s.probe_min, s.probe_max, std::max<size_t>(1, (fast_bytes - GridPeer::kHeaderBytes) / 54), memory_dims);
    GridPeer count_grid(s.probe_min, s.probe_max, count_dims), memory_grid(s.probe_min, s.probe_max, memory_dims);
    for (GridPeer* grid : {&count_grid, &memory_grid}) {
        grid->set_sh(bake_at(s.scene, grid->positions(), settings, settings.seed));
        const bool equal_count = grid == &count_grid;
        Method m;
        m.id = equal_count ? "grid_equal_count" : "grid_equal_memory";
        m.label = equal_count ? "uniform grid, trilinear, equal probe count" : "uniform grid, trilinear, equal memory";
        m.probes = grid->probe_count();
        m.grid = grid->dims();
        m.bytes = grid->bytes();
        m.point_query = [grid](const float* p, float* sh) { grid->interpolate(p, sh); };
        m.path_query = m.point_query;
        m.reset_path = [] {};
        methods.push_back(std::move(m));
    }

    KnnPeer knn(s.probes, s.probe_sh);
    TemporalDamping damping(kDampingFrames);
    for (bool damped : {false, true}) {
        Method m;
        m.id = damped ? "knn4_damped" : "knn4";
        m.label = damped ? "4 nearest probes, inverse distance, temporal damping" : "4 nearest probes, inverse distance";
        if (damped)
            m.note = "rms_error and max_error at the query points are a still object's (damping converged: those of knn4); "
                     "path_rms_error and worst_jump show the damping along the path";
        m.probes = probe_count;
        m.bytes = knn.bytes() + (damped ? 27 * sizeof(float) : 0);  // plus one object's damping state
        m.point_query = [&knn](const float* p, float* sh) { knn.interpolate(p, sh); };
        if (damped) {
            m.path_query = [&knn, &damping](const float* p, float* sh) {
                float blended[27];
                knn.interpolate(p, blended);
                damping.update(blended, sh);
            };
            m.reset_path = [&damping] { damping.reset(); };
        } else {
            m.path_query = m.point_query;
            m.reset_path = [] {};
        }
        methods.push_back(std::move(m));
    }

    Json slices = Json::object();
    Json method_results = Json::array();
    for (Method& m : methods) method_results.push_back(evaluate_method(s, settings, m, &slices));
    tp_store_release(fast);
    tp_store_release(compact);

    const std::vector<float> reference_e = path_luminances(s, s.path_reference);
    Json j;
    j["name"] = s.name;
    j["file"] = s.file;
    j["probes"] = probe_count;
    j["probe_source"] = s.probe_source;
    j["probe_bounds"] = {{"min", json_vec3(s.probe_min)}, {"max", json_vec3(s.probe_max)}};
    j["query_box"] = {{"min", json_vec3(s.query_min)}, {"max", json_vec3(s.query_max)}};
    j["queries"] = s.queries.size() / 3;
    j["query_rule"] = "uniform in query_box, redrawn when inside geometry (at least 7 of 14 rays along the axes and "
                      "diagonals first hit the back of a triangle) or closer than 0.5 to a point or spot light";
    j["reference_noise"] = errors(s, s.second_reference, s.reference).rms();
    j["mean_irradiance"] = s.mean_irradiance;
    j["bake_seconds"] = bake_seconds;
    Json points = Json::array();
    for (size_t f = 0; f < s.path.size() / 3; ++f) points.push_back(json_vec3(&s.path[3 * f]));
    j["path"] = {{"frames", s.path.size() / 3},
                 {"points", points},
                 {"normal", json_vec3(kUp)},
                 {"reference_trace", up_trace(reference_e)},
                 {"reference_worst_jump", worst_jump(reference_e)},
                 {"bad_frames", s.path_bad_frames},
                 {"reference_note",
                  "each frame baked alone with the same seed and stream (common random numbers), so its jumps are "
                  "the light's own changes, not sampling noise"}};
    j["methods"] = method_results;
    Json reference_slice = Json::array();
    for (size_t i = 0; i < s.slice_reference.size() / 27; ++i)
        reference_slice.push_back(irradiance_luminance(&s.slice_reference[27 * i], kUp) / s.mean_irradiance);
    j["slice"] = {{"axis", "y"},
                  {"height", s.slice_height},
                  {"normal", json_vec3(kUp)},
                  {"x", {s.slice_x[0], s.slice_x[1]}},
                  {"z", {s.slice_z[0], s.slice_z[1]}},
                  {"nx", settings.slice_size},
                  {"nz", settings.slice_size},
                  {"cells", "values at the centres of nx by nz equal cells spanning x and z"},
                  {"reference", reference_slice},
                  {"methods", slices}};

    std::printf("\n### %s (%zu probes, %zu queries, reference noise %.4f)\n\n", s.name.c_str(), probe_count,
                s.queries.size() / 3, j["reference_noise"].get<double>());
    std::printf("| method | probes | bytes | RMS error | max error | worst jump | ns/query |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Json& m : method_results)
        std::printf("| %s | %zu | %zu | %.4f | %.4f | %.4f | %.1f |\n", m["label"].get<std::string>().c_str(),
                    m["probes"].get<size_t>(), m["bytes"].get<size_t>(), m["rms_error"].get<double>(),
                    m["max_error"].get<double>(), m["worst_jump"].get<double>(), m["ns_per_query"].get<double>());
    std::printf("| reference (baked at each point) | - | - | - | - | %.4f | - |\n", worst_jump(reference_e));
    return j;
}

}  // namespace

namespace bench {

Json method_bake_json(const MethodSettings& settings) {
    return {{"rays", settings.rays},
            {"bounces", settings.bounces},
            {"seed", settings.seed},
            {"why", settings.quick ? "quick smoke run"
                                   : "512 rays and 2 bounces (the library's default bounces): the references at "
                                     "every query, path and slice point of three scenes fit the benchmark's time budget"}};
}

int write_json(const std::string& dir, const char* name, const Json& j) {
    const std::string path = dir + "/" + name, temporary = path + ".tmp";
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    {
        std::ofstream out(temporary);
        out << j.dump(1) << "\n";
        if (!out) {
            std::fprintf(stderr, "cannot write %s\n", temporary.c_str());
            return 1;
        }
    }
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::fprintf(stderr, "cannot rename %s to %s: %s\n", temporary.c_str(), path.c_str(), error.message().c_str());
        return 1;
    }
    std::printf("\nwrote %s\n", path.c_str());
    return 0;
}

}  // namespace bench

int run_methods_bench(int argc, char** argv) {
    const MethodArgs args = parse_method_args(
        argc, argv, {"samples/scenes/two_rooms.json", "samples/scenes/cornell_box.json", "samples/scenes/race_track.json"});
    const MethodSettings settings = method_settings(args.quick);
    std::printf("## Interpolation methods\n");
    if (args.scenes.empty()) {
        std::fprintf(stderr, "No scene found: run from the repository root or pass --scene PATH.\n");
        return 1;
    }
    Json j;
    j["schema"] = "tetprobe-bench-methods/1";
    j["quick"] = settings.quick;
    j["bake"] = method_bake_json(settings);
    j["irradiance"] = "Rec. 709 luminance (0.2126 R + 0.7152 G + 0.0722 B) of tp_sh_eval_irradiance";
    j["error"] = "|E_method - E_reference| over every query point and the 6 axis normals, divided by the scene's "
                 "mean_irradiance (the reference's mean over the same points and normals); rms_error is its root mean "
                 "square, max_error its maximum";
    j["popping"] = "worst_jump: the largest |E(frame) - E(frame - 1)| over the path's frames and the 6 axis normals, "
                   "divided by mean_irradiance";
    j["timing"] = "ns_per_query: single queries along the path (one object, its hint or damping state carried), "
                  "the path repeated for about 0.05 s (at most 200,000 queries), median of 5 runs; "
                  "every method is called through the same std::function wrapper";
    j["damping"] = {{"time_constant_frames", kDampingFrames},
                    {"frame_seconds", kFrameSeconds},
                    {"alpha", TemporalDamping(kDampingFrames).alpha()},
                    {"rule", "sh = sh + alpha (blend - sh) each frame, alpha = 1 - exp(-1 / time_constant_frames); "
                             "the first frame takes the blend"}};
    j["scenes"] = Json::array();
    try {
        for (const std::string& path : args.scenes) j["scenes"].push_back(bench_scene(path, settings));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "methods benchmark failed: %s\n", e.what());
        return 1;
    }
    return write_json(args.out, "methods.json", j);
}
