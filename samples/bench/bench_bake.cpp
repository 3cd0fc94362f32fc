// The bake benchmark: rays per second of the bake next to raw Embree rtcIntersect1 rays per second
// on the same scene, then "what accuracy costs in time": SH error against a high-sample reference
// for several rays-per-probe and bounce settings, with bake time, and with emitter sampling off
// and on in scenes with emissive surfaces; then shadow-caster culling on and off at the same seed (the
// time it saves and the largest difference it makes). Prints markdown tables; with --out DIR also
// writes bake.json for the report (part 4).
//
// Scenes: samples/scenes/two_rooms.json and cornell_box.json relative to the working directory (the
// repository root under `make bench`), or those given with --scene PATH (repeatable); culling is also
// measured on race_track.json (a scene whose plan culls shadow casters). --quick shrinks the sweep for
// a smoke run.
#include "bench.h"

#include "part_output.h"

#include "bake/lighting_bake.h"
#include "bake/ray_caster.h"
#include "bake/sampling.h"
#include "bake/scene_file.h"
#include "core/error.h"
#include "core/sh.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace tetprobe;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

unsigned worker_count() { return std::max(1u, std::thread::hardware_concurrency()); }

// Closest-hit rays from the probes in uniformly distributed directions, straight through Embree,
// on all cores: the ceiling the bake's own ray rate is measured against.
double raw_embree_rays_per_second(const Scene& scene, const std::vector<float>& probes, uint64_t rays_total) {
    double origin[3] = {0, 0, 0};
    const size_t count = probes.size() / 3;
    for (size_t i = 0; i < probes.size(); ++i) origin[i % 3] += probes[i] / double(count);
    RayCaster caster(scene, origin);
    const unsigned threads = worker_count();
    std::atomic<uint64_t> hits{0};
    const Clock::time_point start = Clock::now();
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) {
        pool.emplace_back([&, t] {
            uint64_t local_hits = 0;
            for (uint64_t r = t; r < rays_total; r += threads) {
                const size_t probe = size_t(r % count);
                double w[3];
                stratified_sphere_direction(99, probe, uint32_t(r / count % 1024), 1024, w);
                const float o[3] = {float(probes[3 * probe] - origin[0]), float(probes[3 * probe + 1] - origin[1]),
                                    float(probes[3 * probe + 2] - origin[2])};
                const float d[3] = {float(w[0]), float(w[1]), float(w[2])};
                RayHit hit;
                local_hits += caster.intersect(o, d, 0.0f, INFINITY, &hit) ? 1 : 0;
            }
            hits += local_hits;
        });
    }
    for (std::thread& t : pool) t.join();
    const double elapsed = seconds_since(start);
    return elapsed > 0 ? double(rays_total) / elapsed : 0.0;
}

// Relative RMS difference of the SH coefficients and of the irradiance in the six axis directions.
void errors(const std::vector<float>& sh, const std::vector<float>& reference, double* sh_error,
            double* irradiance_error) {
    double diff = 0, norm = 0, e_diff = 0, e_norm = 0;
    for (size_t i = 0; i < sh.size(); ++i) {
        diff += double(sh[i] - reference[i]) * (sh[i] - reference[i]);
        norm += double(reference[i]) * reference[i];
    }
    static const float axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (size_t p = 0; p < sh.size() / 27; ++p)
        for (const auto& n : axes) {
            float a[3], b[3];
            sh_eval_irradiance(&sh[27 * p], n, a);
            sh_eval_irradiance(&reference[27 * p], n, b);
            for (int c = 0; c < 3; ++c) {
                e_diff += double(a[c] - b[c]) * (a[c] - b[c]);
                e_norm += double(b[c]) * b[c];
            }
        }
    *sh_error = norm > 0 ? std::sqrt(diff / norm) : 0.0;
    *irradiance_error = e_norm > 0 ? std::sqrt(e_diff / e_norm) : 0.0;
}

json bench_scene(const std::string& path, bool quick) {
    Scene scene = load_scene_file(path);
    const std::vector<float>& probes = scene.probes();
    const size_t count = scene.probe_count();
    BakeSettings settings;
    EffectsPlan plan;
    std::printf("\n### %s\n\n%zu probes, %zu meshes, %zu lights; plan at 2 bounces: %s\n\n", path.c_str(), count,
                scene.meshes().size(), scene.lights().size(),
                derive_effects_plan(scene, probes, 2, true).summary().c_str());

    // Ray rates: a bake at 512 rays and 2 bounces against raw closest-hit rays on the same scene.
    settings.rays = quick ? 128 : 512;
    settings.bounces = 2;
    settings.seed = 1;
    BakeStats stats;
    bake_lighting(scene, probes, settings, &plan, &stats);
    const double bake_rate = stats.seconds > 0 ? double(stats.rays_cast) / stats.seconds : 0.0;
    const double raw_rate = raw_embree_rays_per_second(scene, probes, std::max<uint64_t>(stats.rays_cast, 200000));
    std::printf("| threads | bake rays (all kinds) | bake time | bake Mrays/s | raw rtcIntersect1 Mrays/s | bake / raw |\n");
    std::printf("| ---: | ---: | ---: | ---: | ---: | ---: |\n");
    std::printf("| %u | %llu | %.3f s | %.2f | %.2f | %.2f |\n\n", worker_count(),
                (unsigned long long)stats.rays_cast, stats.seconds, bake_rate / 1e6, raw_rate / 1e6,
                raw_rate > 0 ? bake_rate / raw_rate : 0.0);
    json result = {{"scene", path},
                   {"probes", count},
                   {"plan", derive_effects_plan(scene, probes, 2, true).summary()},
                   {"threads", worker_count()},
                   {"bake_mrays_per_second", bake_rate / 1e6},
                   {"raw_mrays_per_second", raw_rate / 1e6}};

    // What accuracy costs in time: every setting against one high-sample, many-bounce reference
    // (error: noise and the light of the bounces left out), and against a high-sample reference of
    // the same bounces (noise alone).
    const uint32_t reference_rays = quick ? 1024 : 8192, reference_bounces = 6;
    settings.rays = reference_rays;
    settings.bounces = reference_bounces;
    settings.seed = 12345;  // independent of the settings under test
    const Clock::time_point reference_start = Clock::now();
    const std::vector<float> reference = bake_lighting(scene, probes, settings);
    const std::vector<uint32_t> ray_counts = quick ? std::vector<uint32_t>{32, 128} : std::vector<uint32_t>{32, 128, 512, 2048};
    const std::vector<uint32_t> bounce_counts = quick ? std::vector<uint32_t>{0, 2} : std::vector<uint32_t>{0, 1, 2, 4};
    std::vector<std::vector<float>> same_bounce_references;
    for (uint32_t bounces : bounce_counts) {
        settings.bounces = bounces;
        same_bounce_references.push_back(bake_lighting(scene, probes, settings));
    }
    // Emitter sampling only matters with emissive surfaces: then each setting is also run without
    // it (emission found only by rays that hit it), to show what it saves.
    const bool emissive = !plan.emissive_meshes.empty();
    std::printf("References: %u rays per probe, %u bounces (and each bounce count of the table), %.2f s. Errors are "
                "relative RMS over all probes; noise is the SH error against the reference of the same bounces.\n\n",
                reference_rays, reference_bounces, seconds_since(reference_start));
    result["reference"] = {{"rays", reference_rays}, {"bounces", reference_bounces}};
    result["rows"] = json::array();
    std::printf("| rays per probe | bounces | emitter sampling | bake time | ms per probe | SH error | irradiance error | SH noise |\n");
    std::printf("| ---: | ---: | :---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (uint32_t rays : ray_counts)
        for (size_t b = 0; b < bounce_counts.size(); ++b)
            for (bool sampled : emissive ? std::vector<bool>{false, true} : std::vector<bool>{true}) {
                settings.rays = rays;
                settings.bounces = bounce_counts[b];
                settings.seed = 7;
                settings.emitter_sampling = sampled;
                // Wall time, median of 3 (the bake is deterministic: the same SH every time).
                std::vector<float> sh;
                double times[3];
                for (double& t : times) {
                    const Clock::time_point start = Clock::now();
                    sh = bake_lighting(scene, probes, settings);
                    t = seconds_since(start);
                }
                std::sort(times, times + 3);
                const double elapsed = times[1];
                double sh_error, irradiance_error, noise, unused;
                errors(sh, reference, &sh_error, &irradiance_error);
                errors(sh, same_bounce_references[b], &noise, &unused);
                std::printf("| %u | %u | %s | %.3f s | %.3f | %.4f | %.4f | %.4f |\n", rays, bounce_counts[b],
                            !emissive ? "-" : sampled ? "on" : "off", elapsed, 1e3 * elapsed / double(count), sh_error,
                            irradiance_error, noise);
                result["rows"].push_back({{"rays", rays},
                                          {"bounces", bounce_counts[b]},
                                          {"emitter_sampling", emissive ? json(sampled) : json(nullptr)},
                                          {"seconds", elapsed},
                                          {"sh_error", sh_error},
                                          {"irradiance_error", irradiance_error},
                                          {"noise", noise}});
            }
    return result;
}

// Shadow-caster culling on and off at the same settings and seed: wall time of the whole bake (median of
// 5, on and off interleaved so that a change in the machine's load hits both), the plan's shadow casters
// both ways, and the largest difference of any SH coefficient.
json bench_culling(const std::string& path, bool quick) {
    const Scene scene = load_scene_file(path);
    const std::vector<float>& probes = scene.probes();
    BakeSettings settings;
    settings.rays = quick ? 64 : 2048;  // enough work that the machine's noise does not decide
    settings.bounces = 2;
    settings.seed = 7;
    json result = {{"scene", path}, {"probes", scene.probe_count()}, {"rays", settings.rays},
                   {"bounces", settings.bounces}, {"repetitions", 5}};
    std::vector<float> baked[2];
    std::vector<double> seconds[2];
    for (int repetition = 0; repetition < 5; ++repetition)
        for (const bool culling : {true, false}) {
            settings.culling = culling;
            const Clock::time_point start = Clock::now();
            baked[culling ? 0 : 1] = bake_lighting(scene, probes, settings);
            seconds[culling ? 0 : 1].push_back(seconds_since(start));
        }
    for (const bool culling : {true, false}) {
        std::vector<double>& s = seconds[culling ? 0 : 1];
        std::sort(s.begin(), s.end());
        const EffectsPlan plan = derive_effects_plan(scene, probes, settings.bounces, culling);
        result[culling ? "on" : "off"] = {{"seconds", s[s.size() / 2]},
                                          {"shadow_casters", plan.shadow_casters},
                                          {"shadow_caster_candidates", plan.shadow_caster_candidates}};
    }
    double max_difference = 0;
    for (size_t i = 0; i < baked[0].size(); ++i)
        max_difference = std::max(max_difference, std::fabs(double(baked[0][i]) - baked[1][i]));
    result["max_abs_difference"] = max_difference;
    result["identical_bytes"] = baked[0].size() == baked[1].size() &&
                                !std::memcmp(baked[0].data(), baked[1].data(), baked[0].size() * sizeof(float));
    return result;
}

}  // namespace

int run_bake_bench(int argc, char** argv) {
    const bench::PartOptions options = bench::part_options(argc, argv);
    const bool quick = options.quick;
    std::vector<std::string> scenes, culling_scenes;
    for (int i = 1; i < argc; ++i)
        if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) scenes.push_back(argv[++i]);
    if (scenes.empty())
        for (const char* name : {"samples/scenes/two_rooms.json", "samples/scenes/cornell_box.json"})
            if (std::ifstream(name)) scenes.push_back(name);
    culling_scenes = scenes;
    if (std::ifstream("samples/scenes/race_track.json")) culling_scenes.push_back("samples/scenes/race_track.json");
    std::printf("## Lighting bake\n");
    if (scenes.empty()) {
        std::printf("\nNo scene found: run from the repository root or pass --scene PATH.\n");
        return 1;
    }
    json result = {{"part", "bake"}, {"machine", bench::machine_json(quick)}};
    result["scenes"] = json::array();
    result["culling"] = json::array();
    try {
        for (const std::string& path : scenes) result["scenes"].push_back(bench_scene(path, quick));
        std::printf("\n### Shadow-caster culling (same seed)\n\n| scene | shadow casters on / off | bake on | "
                    "bake off | "
                    "max |difference| | same bytes |\n| --- | ---: | ---: | ---: | ---: | :---: |\n");
        for (const std::string& path : culling_scenes) {
            const json c = bench_culling(path, quick);
            std::printf("| %s | %u / %u | %.3f s | %.3f s | %.3g | %s |\n", path.c_str(),
                        c["on"]["shadow_casters"].get<uint32_t>(), c["off"]["shadow_casters"].get<uint32_t>(),
                        c["on"]["seconds"].get<double>(), c["off"]["seconds"].get<double>(),
                        c["max_abs_difference"].get<double>(), c["identical_bytes"].get<bool>() ? "yes" : "no");
            result["culling"].push_back(c);
        }
        if (!options.out_dir.empty()) bench::write_json_file(options.out_dir, "bake.json", result);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bake benchmark failed: %s\n", e.what());
        return 1;
    }
    return 0;
}
