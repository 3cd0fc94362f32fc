// tetprobe_bench leak [--out DIR] [--scene FILE] [--rays N]: leak control on the two-rooms scene, before
// and after, through the C ABI. The scene's probes are baked, a store is built without and with the
// scene (leak control), and irradiance is compared along paths across the dividing wall (x 4 to 4.2) with a
// bake at the path points themselves (the reference). Writes DIR/leak.json (default DIR: build/bench)
// and prints a summary.
//
// leak.json schema (every irradiance is the mean over directions, pi * Y00 * L00, averaged over r, g, b):
// {
//   "scene": "samples/scenes/two_rooms.json", "probes": 94, "leak_edges": 30, "rays": 256, "bounces": 2,
//   "store_bytes": {"without": int, "with": int},
//   "paths": [ { "name": "z=3.3 y=1.2", "from": [x,y,z], "to": [x,y,z],
//                "samples": [ {"x": float, "reference": float, "without": float, "with": float}, ... ],
//                "inside_left_out": int,           // path points inside geometry (the wall), not sampled
//                "leak_error": {"without": float, "with": float} } ],   // sum |store - reference| / sum reference
//   "cost_ns_per_query": { "rooms": {"without": float, "with": float},            // uniform in the probes' bounds
//                          "wall": {"without": float, "with": float} }            // within 0.6 of the wall
// }
#include "bench.h"
#include "bench_timing.h"

#include "capi/tetprobe.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

bool ok(tp_status status, const char* what) {
    if (status == TP_OK) return true;
    std::fprintf(stderr, "leak bench: %s: %s\n", what, tp_last_error());
    return false;
}

double mean_irradiance(const float* sh) {
    return 3.14159265358979 * 0.282095 * (double(sh[0]) + sh[9] + sh[18]) / 3.0;
}

// Median nanoseconds per query of one batch over points (hint-less: each query starts from the grid).
double ns_per_query(const tp_store* store, const std::vector<float>& points) {
    const size_t count = points.size() / 3;
    std::vector<float> sh(27 * count);
    std::vector<int32_t> hints(count, -1);
    const double seconds = bench::median_seconds([&] {
        std::fill(hints.begin(), hints.end(), -1);
        const auto start = bench::Clock::now();
        tp_store_interpolate_batch(store, count, points.data(), 0, hints.data(), 0, sh.data(), 0, nullptr);
        return bench::seconds_since(start);
    });
    return seconds * 1e9 / double(count);
}

}  // namespace

int run_leak_bench(int argc, char** argv) {
    std::string out_dir = "build/bench", scene_path = "samples/scenes/two_rooms.json";
    uint32_t rays = 256;
    for (int i = 2; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_dir = argv[++i];
        else if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) scene_path = argv[++i];
        else if (!std::strcmp(argv[i], "--rays") && i + 1 < argc) rays = uint32_t(std::atoi(argv[++i]));
    }
    tp_scene* scene = nullptr;
    if (!ok(tp_scene_load_file(scene_path.c_str(), &scene), scene_path.c_str())) return 1;
    const float* scene_probes = nullptr;
    size_t count = 0;
    tp_scene_probes(scene, &scene_probes, &count);
    const std::vector<float> probes(scene_probes, scene_probes + 3 * count);
    tp_bake_options bake;
    tp_bake_options_init(&bake);
    bake.rays = rays;
    bake.seed = 4;
    std::vector<float> sh(27 * count);
    if (!ok(tp_bake(scene, probes.data(), 0, count, &bake, sh.data(), 0), "baking the probes")) return 1;

    tp_build_options with_scene;
    tp_build_options_init(&with_scene);
    with_scene.scene = scene;
    tp_store *plain = nullptr, *leak = nullptr;
    if (!ok(tp_store_build(probes.data(), 0, sh.data(), 0, count, nullptr, &plain), "building without the scene") ||
        !ok(tp_store_build(probes.data(), 0, sh.data(), 0, count, &with_scene, &leak), "building with the scene"))
        return 1;
    tp_store_info info_plain{}, info_leak{};
    info_plain.struct_size = info_leak.struct_size = sizeof(tp_store_info);
    tp_store_get_info(plain, &info_plain);
    tp_store_get_info(leak, &info_leak);

    nlohmann::json report;
    report["scene"] = scene_path;
    report["probes"] = count;
    report["leak_edges"] = info_leak.leak_edges;
    report["rays"] = bake.rays;
    report["bounces"] = bake.bounces;
    report["store_bytes"] = {{"without", info_plain.bytes}, {"with", info_leak.bytes}};
    std::printf("leak control on %s: %zu probes, %u blocked pairs, store %llu -> %llu bytes\n", scene_path.c_str(),
                count, info_leak.leak_edges, (unsigned long long)info_plain.bytes, (unsigned long long)info_leak.bytes);

    // Paths across the wall between the probe columns either side of it, away from the door (z 1.5 to 2.5).
    const float paths[][2] = {{1.2f, 3.3f}, {2.0f, 0.7f}, {0.8f, 0.4f}};
    for (const auto& yz : paths) {
        std::vector<float> line;
        for (int i = 0; i <= 60; ++i) line.insert(line.end(), {3.5f + 0.02f * float(i), yz[0], yz[1]});
        // Points inside the wall (x 4 to 4.2) are left out: no object is there, and the bake there is black.
        std::vector<uint32_t> inside(line.size() / 3);
        size_t inside_count = 0;
        if (!ok(tp_find_inside_probes(scene, line.data(), 0, line.size() / 3, inside.data(), inside.size(), &inside_count),
                "finding path points inside geometry"))
            return 1;
        std::vector<float> points;
        for (size_t i = 0, next = 0; i < line.size() / 3; ++i) {
            if (next < inside_count && inside[next] == i) { ++next; continue; }
            points.insert(points.end(), {line[3 * i], line[3 * i + 1], line[3 * i + 2]});
        }
        const size_t n = points.size() / 3;
        std::vector<float> reference(27 * n), without(27 * n), with(27 * n);
        if (!ok(tp_bake(scene, points.data(), 0, n, &bake, reference.data(), 0), "baking the path") ||
            !ok(tp_store_interpolate_batch(plain, n, points.data(), 0, nullptr, 0, without.data(), 0, nullptr), "query") ||
            !ok(tp_store_interpolate_batch(leak, n, points.data(), 0, nullptr, 0, with.data(), 0, nullptr), "query"))
            return 1;
        nlohmann::json path, samples = nlohmann::json::array();
        double error_without = 0, error_with = 0, level = 0;
        for (size_t i = 0; i < n; ++i) {
            const double r = mean_irradiance(&reference[27 * i]), a = mean_irradiance(&without[27 * i]),
                         b = mean_irradiance(&with[27 * i]);
            samples.push_back({{"x", points[3 * i]}, {"reference", r}, {"without", a}, {"with", b}});
            error_without += std::fabs(a - r);
            error_with += std::fabs(b - r);
            level += std::fabs(r);
        }
        char name[64];
        std::snprintf(name, sizeof name, "z=%.1f y=%.1f", yz[1], yz[0]);
        path["name"] = name;
        path["from"] = {points[0], points[1], points[2]};
        path["to"] = {points[3 * n - 3], points[3 * n - 2], points[3 * n - 1]};
        path["samples"] = samples;
        path["inside_left_out"] = inside_count;
        path["leak_error"] = {{"without", error_without / level}, {"with", error_with / level}};
        report["paths"].push_back(path);
        std::printf("  path %-12s leak error %.3f without, %.3f with leak control\n", name, error_without / level,
                    error_with / level);
    }

    // Cost per query: uniform over the probes' bounds, and within 0.6 of the wall (where cells are blocked).
    std::mt19937 random(9);
    std::vector<float> rooms, wall;
    std::uniform_real_distribution<float> ux(info_plain.bounds_min[0], info_plain.bounds_max[0]),
        uy(info_plain.bounds_min[1], info_plain.bounds_max[1]), uz(info_plain.bounds_min[2], info_plain.bounds_max[2]),
        near_wall(3.4f, 4.6f);
    for (int i = 0; i < 200000; ++i) {
        rooms.insert(rooms.end(), {ux(random), uy(random), uz(random)});
        wall.insert(wall.end(), {near_wall(random), uy(random), uz(random)});
    }
    // Alternated, the least of three medians each (the machine is shared; noise only adds time).
    double rooms_plain = 1e30, rooms_leak = 1e30, wall_plain = 1e30, wall_leak = 1e30;
    for (int round = 0; round < 3; ++round) {
        rooms_plain = std::min(rooms_plain, ns_per_query(plain, rooms));
        rooms_leak = std::min(rooms_leak, ns_per_query(leak, rooms));
        wall_plain = std::min(wall_plain, ns_per_query(plain, wall));
        wall_leak = std::min(wall_leak, ns_per_query(leak, wall));
    }
    report["cost_ns_per_query"] = {{"rooms", {{"without", rooms_plain}, {"with", rooms_leak}}},
                                   {"wall", {{"without", wall_plain}, {"with", wall_leak}}}};
    std::printf("  cost per query (cold, no hint): rooms %.1f -> %.1f ns, near the wall %.1f -> %.1f ns\n",
                rooms_plain, rooms_leak, wall_plain, wall_leak);

    std::filesystem::create_directories(out_dir);
    const std::string path = out_dir + "/leak.json";
    std::ofstream(path) << report.dump(1) << "\n";
    std::printf("wrote %s\n", path.c_str());
    tp_store_release(plain);
    tp_store_release(leak);
    tp_scene_release(scene);
    return 0;
}
