#include "level_reference.h"

#include "level_metric.h"
#include "part_output.h"

#include "bake/quake3_scene.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace bench {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<float> bake(const tp_scene* scene, const float* positions, size_t count, uint32_t rays, uint32_t bounces,
                        uint64_t seed, const std::string& what) {
    tp_bake_options options;
    tp_bake_options_init(&options);
    options.rays = rays;
    options.bounces = bounces;
    options.seed = seed;
    std::vector<float> sh(27 * count);
    if (count && tp_bake(scene, positions, 0, count, &options, sh.data(), 0) != TP_OK)
        throw std::runtime_error(what + ": tp_bake: " + tp_last_error());
    return sh;
}

// Bumped whenever what the cache holds changes meaning.
constexpr int kCacheVersion = 3;

}  // namespace

std::string LevelSettings::key() const {
    char text[512];
    std::snprintf(text, sizeof text,
                  "v%d rays %u probe_rays %u bounces %u seeds %llu %llu %llu points %zu noise %zu clearance %g paths %zu "
                  "step %g space %g %g %g %g %g %g",
                  kCacheVersion, reference_rays, probe_rays, bounces, (unsigned long long)reference_seed,
                  (unsigned long long)noise_seed, (unsigned long long)probe_seed, points, noise_points, light_clearance,
                  paths, frame_step, space.spacing, space.layer, space.band_min, space.band_max, space.floor_cosine,
                  space.clearance);
    return text;
}

std::vector<float> bake_probes(const Level& level, const std::vector<float>& positions, const LevelSettings& settings,
                               uint32_t rays) {
    return bake(level.handle.get(), positions.data(), positions.size() / 3, rays ? rays : settings.probe_rays,
                settings.bounces, settings.probe_seed, level.name);
}

void prepare_level(const std::string& bsp, const std::string& cache_dir, const LevelSettings& settings,
                   uint32_t threads, Level* out) {
    Level& level = *out;
    level.file = bsp;
    level.name = fs::path(bsp).stem().string();
    level.import = tetprobe::read_quake3_bsp(bsp);
    tetprobe::add_quake3_level(level.scene, level.import);
    level.import.vertices.clear(), level.import.indices.clear();
    level.import.vertices.shrink_to_fit(), level.import.indices.shrink_to_fit();
    for (const tetprobe::Mesh& mesh : level.scene.meshes()) level.triangles += mesh.triangle_count();
    level.lights = level.scene.lights().size();
    tp_scene* handle = nullptr;
    if (tp_scene_load_file(bsp.c_str(), &handle) != TP_OK)
        throw std::runtime_error(bsp + ": tp_scene_load_file: " + tp_last_error());
    level.handle.reset(handle);

    const std::string dir = cache_dir.empty() ? std::string() : (fs::path(cache_dir) / level.name).string();
    const uint64_t file_size = fs::file_size(bsp);
    if (!dir.empty()) {
        std::ifstream in(fs::path(dir) / "meta.json");
        const nlohmann::json meta = nlohmann::json::parse(in, nullptr, false);
        if (meta.is_object() && meta.value("key", "") == settings.key() && meta.value("file_size", uint64_t(0)) == file_size &&
            read_npy_f32((fs::path(dir) / "playable.npy").string(), 3, &level.playable) &&
            read_npy_f32((fs::path(dir) / "points.npy").string(), 3, &level.points) &&
            read_npy_f32((fs::path(dir) / "reference.npy").string(), 27, &level.reference) &&
            read_npy_f32((fs::path(dir) / "paths.npy").string(), 3, &level.path_points)) {
            level.band_points = meta["band_points"], level.free_points = meta["free_points"];
            level.spawns_used = meta["spawns_used"], level.spawns_given = meta["spawns_given"];
            level.mean = meta["mean"], level.noise_rms = meta["noise_rms"], level.noise_p95 = meta["noise_p95"];
            level.path_frames = meta["path_frames"].get<std::vector<uint32_t>>();
            level.space_seconds = meta["space_seconds"], level.reference_seconds = meta["reference_seconds"];
            for (int k = 0; k < 3; ++k) level.playable_lo[k] = meta["playable_lo"][k], level.playable_hi[k] = meta["playable_hi"][k];
            level.from_cache = true;
            return;
        }
    }

    auto start = std::chrono::steady_clock::now();
    const PlayableSpace space = find_playable_space(level.scene, level.import.spawn_points, settings.space, threads);
    level.playable = space.points;
    level.band_points = space.band_points, level.free_points = space.free_points;
    level.spawns_used = space.spawns_used, level.spawns_given = space.spawns_given;
    for (int k = 0; k < 3; ++k) level.playable_lo[k] = space.lo[k], level.playable_hi[k] = space.hi[k];
    std::vector<float> lights;
    for (const tetprobe::Light& light : level.scene.lights())
        if (light.positional())
            for (double c : light.position) lights.push_back(float(c));
    level.points = draw_free_points(level.scene, space, settings.points, settings.reference_seed, lights,
                                    settings.light_clearance);
    // Paths: from spawn point k (in the level's order) to the spawn point farthest from it that the same
    // connected part of the playable space holds, for the first spawn points that have one, each pair once.
    const std::vector<uint32_t> component = component_labels(space);
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    for (size_t k = 0; k < space.seeds.size() && level.path_frames.size() < settings.paths; ++k) {
        const uint32_t from = space.seeds[k];
        uint32_t to = from;
        double farthest = 0;
        for (uint32_t other : space.seeds) {
            if (component[other] != component[from]) continue;
            double d2 = 0;
            for (int a = 0; a < 3; ++a) d2 += double(space.points[3 * other + a] - space.points[3 * from + a]) * (space.points[3 * other + a] - space.points[3 * from + a]);
            if (d2 > farthest) farthest = d2, to = other;
        }
        if (to == from || std::find(pairs.begin(), pairs.end(), std::make_pair(to, from)) != pairs.end()) continue;
        pairs.push_back({from, to});
        const std::vector<float> frames = walking_path(space, from, to, settings.frame_step);
        if (frames.size() < 6) continue;
        level.path_points.insert(level.path_points.end(), frames.begin(), frames.end());
        level.path_frames.push_back(uint32_t(frames.size() / 3));
    }
    level.space_seconds = seconds_since(start);

    start = std::chrono::steady_clock::now();
    const size_t count = level.points.size() / 3, noise_count = std::min(settings.noise_points, count);
    level.reference = bake(level.handle.get(), level.points.data(), count, settings.reference_rays, settings.bounces,
                           settings.reference_seed, level.name + " reference");
    const std::vector<float> second = bake(level.handle.get(), level.points.data(), noise_count, settings.reference_rays,
                                           settings.bounces, settings.noise_seed, level.name + " reference, second seed");
    level.reference_seconds = seconds_since(start);
    const std::vector<float> e = luminance6(level.reference.data(), count);
    double sum = 0;
    for (float v : e) sum += v;
    level.mean = sum / double(e.size());
    if (!(level.mean > 0)) throw std::runtime_error(level.name + ": the reference irradiance is not positive (no light reaches the playable space)");
    std::vector<float> first(e.begin(), e.begin() + std::ptrdiff_t(6 * noise_count));
    relative_error(luminance6(second.data(), noise_count), first, level.mean, &level.noise_rms, &level.noise_p95);

    if (!dir.empty()) {
        write_npy_f32(dir, "playable.npy", level.playable.data(), level.playable.size() / 3, 3);
        write_npy_f32(dir, "points.npy", level.points.data(), count, 3);
        write_npy_f32(dir, "reference.npy", level.reference.data(), count, 27);
        write_npy_f32(dir, "paths.npy", level.path_points.data(), level.path_points.size() / 3, 3);
        nlohmann::json meta = {{"key", settings.key()}, {"file", bsp}, {"file_size", file_size},
                               {"band_points", level.band_points}, {"free_points", level.free_points},
                               {"spawns_used", level.spawns_used}, {"spawns_given", level.spawns_given},
                               {"mean", level.mean}, {"noise_rms", level.noise_rms}, {"noise_p95", level.noise_p95},
                               {"path_frames", level.path_frames}, {"space_seconds", level.space_seconds},
                               {"reference_seconds", level.reference_seconds},
                               {"playable_lo", {level.playable_lo[0], level.playable_lo[1], level.playable_lo[2]}},
                               {"playable_hi", {level.playable_hi[0], level.playable_hi[1], level.playable_hi[2]}}};
        write_json_file(dir, "meta.json", meta);  // last: a cache without it is not used
    }
}

}  // namespace bench
