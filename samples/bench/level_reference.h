// One real level of the benchmark, prepared once and cached in the build tree: the imported scene, its
// playable space (level_space.h), the evaluation points drawn from it, the reference baked there with
// many rays (and a second seed on some of them: the reference's own noise), and walking paths between
// spawn points. Every method of the real-level benchmark is judged against this (level_metric.h), so a
// probe set's evaluation costs its own bake and queries only.
#pragma once

#include "level_space.h"

#include "bake/quake3_bsp.h"
#include "bake/scene.h"
#include "capi/tetprobe.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bench {

struct LevelSettings {
    uint32_t reference_rays = 1024;   // the reference at the evaluation points
    uint32_t probe_rays = 256;        // every method's probes (the same for all)
    uint32_t bounces = 2;             // both
    uint64_t reference_seed = 7, noise_seed = 1007, probe_seed = 1;
    size_t points = 1000;             // evaluation points
    size_t noise_points = 250;        // of those, baked again with noise_seed
    double light_clearance = 1.0;     // evaluation points keep this far from a point light (its 1/d^2 peak)
    size_t paths = 4;                 // walking paths: each from a spawn point to the farthest one it can reach
    double frame_step = 10.0 / 60.0;  // metres a frame: Q3's run speed (320 units/s) at 60 frames a second
    PlayableSpaceSettings space;

    // Everything above as text: a cache made with other settings is not used.
    std::string key() const;
};

struct Level {
    std::string name, file;
    tetprobe::Quake3Level import;       // vertices and indices dropped after the scene is made
    tetprobe::Scene scene;
    std::unique_ptr<tp_scene, tp_status (*)(tp_scene*)> handle{nullptr, tp_scene_release};  // the C ABI's copy
    size_t triangles = 0, lights = 0;   // of the scene (lights: the entities baked, sun included)
    size_t band_points = 0, free_points = 0, spawns_used = 0, spawns_given = 0;
    std::vector<float> playable;        // 3 per reachable point of the playable space (its grid), world
    float playable_lo[3] = {0, 0, 0}, playable_hi[3] = {0, 0, 0};
    std::vector<float> points;          // 3 per evaluation point
    std::vector<float> reference;       // 27 per evaluation point
    double mean = 0;                    // mean luminance irradiance of the reference over points and 6 normals
    double noise_rms = 0, noise_p95 = 0;  // the second seed against the first, on the first noise_points
    std::vector<float> path_points;     // 3 per frame, the paths one after another
    std::vector<uint32_t> path_frames;  // frames of each path
    double space_seconds = 0, reference_seconds = 0;  // when computed (not when read from the cache)
    bool from_cache = false;
};

// Prepares the level in `bsp` (a .bsp file) with the settings, reading what cache_dir/<name>/ holds for
// the same settings and writing it there otherwise (cache_dir empty: no cache). Throws
// std::runtime_error (or tetprobe::Error from the importer) with a message naming the level.
void prepare_level(const std::string& bsp, const std::string& cache_dir, const LevelSettings& settings,
                   uint32_t threads, Level* out);

// Bakes positions (3 floats each) in the level with the probes' settings; throws with tp_last_error.
std::vector<float> bake_probes(const Level& level, const std::vector<float>& positions, const LevelSettings& settings,
                               uint32_t rays = 0);

}  // namespace bench
