// Part 5 of the report, probe count: on the two-rooms scene, a grid of probes over the bounds of the
// scene's own probes, its spacing halved level by level, each level baked, built into a tetrahedral
// store and interpolated at fixed query points; error against a reference baked directly at those
// points (same rays and bounces), and the store's bytes. The noise floor is the error of a second
// direct bake at the query points with another seed: no probe count can go below it. Writes
// probes.json with --out DIR; --quick: two coarse levels and few rays.
#include "bench.h"

#include "part_output.h"

#include "bake/lighting_bake.h"
#include "bake/scene_file.h"
#include "capi/tetprobe.h"
#include "core/error.h"
#include "core/sh.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace tetprobe;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

const float kAxes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// Irradiance error over the six axis normals and three channels: RMS relative to the reference's RMS,
// and the largest absolute difference relative to the same RMS.
void irradiance_error(const std::vector<float>& sh, const std::vector<float>& reference, double* rms, double* max) {
    double diff = 0, norm = 0, worst = 0;
    for (size_t p = 0; p < sh.size() / 27; ++p)
        for (const auto& n : kAxes) {
            float a[3], b[3];
            sh_eval_irradiance(&sh[27 * p], n, a);
            sh_eval_irradiance(&reference[27 * p], n, b);
            for (int c = 0; c < 3; ++c) {
                diff += double(a[c] - b[c]) * (a[c] - b[c]);
                norm += double(b[c]) * b[c];
                worst = std::max(worst, std::fabs(double(a[c]) - b[c]));
            }
        }
    const double reference_rms = std::sqrt(norm / double(sh.size() / 27 * 18));
    *rms = norm > 0 ? std::sqrt(diff / norm) : 0.0;
    *max = reference_rms > 0 ? worst / reference_rms : 0.0;
}

struct StoreDeleter {
    void operator()(tp_store* s) const { tp_store_release(s); }
};

json run_level(const Scene& scene, uint32_t per_axis, const float lo[3], const float hi[3],
               const std::vector<float>& queries, const std::vector<float>& reference, BakeSettings settings) {
    std::vector<float> probes;
    for (uint32_t i = 0; i < per_axis; ++i)
        for (uint32_t j = 0; j < per_axis; ++j)
            for (uint32_t k = 0; k < per_axis; ++k) {
                const uint32_t index[3] = {i, j, k};
                for (int a = 0; a < 3; ++a)
                    probes.push_back(lo[a] + (hi[a] - lo[a]) * float(index[a]) / float(per_axis - 1));
            }
    const size_t count = probes.size() / 3;
    settings.seed = 3;
    const Clock::time_point t0 = Clock::now();
    const std::vector<float> sh = bake_lighting(scene, probes, settings);
    const double bake_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

    json level = {{"probes_per_axis", per_axis}, {"probes", count}, {"bake_seconds", bake_seconds}};
    level["spacing"] = {(hi[0] - lo[0]) / float(per_axis - 1), (hi[1] - lo[1]) / float(per_axis - 1),
                        (hi[2] - lo[2]) / float(per_axis - 1)};
    for (const bool compact : {false, true}) {
        tp_build_options options;
        tp_build_options_init(&options);
        options.flags = compact ? TP_BUILD_COMPACT : 0;
        tp_store* raw = nullptr;
        if (tp_store_build(probes.data(), 0, sh.data(), 0, count, &options, &raw) != TP_OK)
            throw std::runtime_error(std::string("tp_store_build: ") + tp_last_error());
        std::unique_ptr<tp_store, StoreDeleter> store(raw);
        tp_store_info info;
        std::memset(&info, 0, sizeof info);
        info.struct_size = sizeof info;
        tp_store_get_info(store.get(), &info);
        level[compact ? "compact_bytes" : "fast_bytes"] = info.bytes;
        if (compact) continue;
        std::vector<float> interpolated(27 * (queries.size() / 3));
        int32_t hint = -1;
        for (size_t q = 0; q < queries.size() / 3; ++q)
            tp_store_interpolate(store.get(), &queries[3 * q], &hint, &interpolated[27 * q]);
        double rms, max;
        irradiance_error(interpolated, reference, &rms, &max);
        level["rms_error"] = rms;
        level["max_error"] = max;
    }
    return level;
}

}  // namespace

int run_probe_count_bench(int argc, char** argv) {
    const bench::PartOptions options = bench::part_options(argc, argv);
    std::string scene_path = "samples/scenes/two_rooms.json";
    for (int i = 1; i + 1 < argc; ++i)
        if (!std::strcmp(argv[i], "--probe-scene")) scene_path = argv[i + 1];
    json result = {{"part", "probes"}, {"machine", bench::machine_json(options.quick)}, {"scene", scene_path}};
    try {
        const Scene scene = load_scene_file(scene_path);
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t i = 0; i < scene.probes().size(); ++i) {
            lo[i % 3] = std::min(lo[i % 3], scene.probes()[i]);
            hi[i % 3] = std::max(hi[i % 3], scene.probes()[i]);
        }
        const size_t query_count = options.quick ? 100 : 2000;
        std::mt19937 rng(21);
        std::vector<float> queries;
        for (size_t q = 0; q < query_count; ++q)
            for (int a = 0; a < 3; ++a) queries.push_back(std::uniform_real_distribution<float>(lo[a], hi[a])(rng));
        BakeSettings settings;
        settings.rays = options.quick ? 64 : 512;
        settings.bounces = 2;
        settings.seed = 1;
        const std::vector<float> reference = bake_lighting(scene, queries, settings);
        settings.seed = 2;
        double noise_rms, noise_max;
        irradiance_error(bake_lighting(scene, queries, settings), reference, &noise_rms, &noise_max);
        result["rays"] = settings.rays;
        result["bounces"] = settings.bounces;
        result["query_points"] = query_count;
        result["bounds"] = {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
        result["noise_floor"] = {{"rms_error", noise_rms}, {"max_error", noise_max}};
        result["levels"] = json::array();
        for (uint32_t per_axis : options.quick ? std::vector<uint32_t>{2, 3} : std::vector<uint32_t>{3, 5, 9, 17}) {
            std::fprintf(stderr, "probe-count benchmark: %u^3 probes...\n", per_axis);
            result["levels"].push_back(run_level(scene, per_axis, lo, hi, queries, reference, settings));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "probe-count benchmark failed: %s\n", e.what());
        return 1;
    }
    std::printf("## Probe count (%s)\n\n| probes | spacing x | RMS error | max error | fast bytes | compact bytes |\n",
                scene_path.c_str());
    std::printf("| ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const json& l : result["levels"])
        std::printf("| %zu | %.3f | %.4f | %.4f | %zu | %zu |\n", l["probes"].get<size_t>(),
                    l["spacing"][0].get<double>(), l["rms_error"].get<double>(), l["max_error"].get<double>(),
                    l["fast_bytes"].get<size_t>(), l["compact_bytes"].get<size_t>());
    std::printf("\nnoise floor (a second direct bake): RMS %.4f\n", result["noise_floor"]["rms_error"].get<double>());
    if (!options.out_dir.empty()) bench::write_json_file(options.out_dir, "probes.json", result);
    return 0;
}
