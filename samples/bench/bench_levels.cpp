// tetprobe_bench levels ...: the real-level benchmark (Quake 3 levels of Debian's openarena-081-maps,
// extracted into the build tree by samples/bench/setup_levels.sh).
//
//   tetprobe_bench levels eval --level NAME --probes FILE.csv [--layout ID] [--json]
//       One probe set (x,y,z per line) on one level: baked with the level's probe settings, built with
//       the store layout (default: every layout), measured with the level's metric (level_metric.h).
//       Prints a table, or with --json one JSON object (the "results" rows of levels.json below).
//   tetprobe_bench levels prepare --level NAME...
//       Only prepares the levels' caches (playable space, evaluation points, reference, paths).
//
// Common options: --maps DIR (the .bsp files; default build/levels/maps), --cache DIR (the prepared
// levels; default build/levels/cache; "" for none), --threads N (0 = all cores). A level is a name in
// --maps or a path to a .bsp file. The first use of a level bakes its reference (about a minute on two
// cores); later uses read it from the cache, so an evaluation takes its own bake and queries only.
#include "bench.h"

#include "level_reference.h"
#include "level_tetprobe.h"
#include "store_layouts.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace {

using namespace bench;
using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

struct LevelArgs {
    std::string command;
    std::vector<std::string> levels;
    std::string maps = "build/levels/maps", cache = "build/levels/cache", out, probes, layout;
    bool json = false, quick = false;
    uint32_t threads = 0;
};

LevelArgs parse_level_args(int argc, char** argv) {
    LevelArgs a;
    int i = 2;
    if (i < argc && argv[i][0] != '-') a.command = argv[i++];
    for (; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--level") a.levels.push_back(value());
        else if (arg == "--levels") {
            std::stringstream list(value());
            std::string name;
            while (std::getline(list, name, ','))
                if (!name.empty()) a.levels.push_back(name);
        } else if (arg == "--maps") a.maps = value();
        else if (arg == "--cache") a.cache = value();
        else if (arg == "--out") a.out = value();
        else if (arg == "--probes") a.probes = value();
        else if (arg == "--layout") a.layout = value();
        else if (arg == "--threads") a.threads = uint32_t(std::stoul(value()));
        else if (arg == "--json") a.json = true;
        else if (arg == "--quick") a.quick = true;
        else throw std::invalid_argument("unknown option " + arg);
    }
    return a;
}

std::string level_path(const LevelArgs& a, const std::string& level) {
    if (level.size() > 4 && level.compare(level.size() - 4, 4, ".bsp") == 0) return level;
    return (fs::path(a.maps) / (level + ".bsp")).string();
}

std::vector<float> read_probe_csv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::vector<float> positions;
    std::string line;
    for (size_t number = 1; std::getline(in, line); ++number) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        float p[3];
        char comma1, comma2;
        std::stringstream fields(line);
        if (!(fields >> p[0] >> comma1 >> p[1] >> comma2 >> p[2]) || comma1 != ',' || comma2 != ',') {
            if (number == 1) continue;  // a header
            throw std::runtime_error(path + ": line " + std::to_string(number) + " is not x,y,z");
        }
        positions.insert(positions.end(), p, p + 3);
    }
    if (positions.empty()) throw std::runtime_error(path + ": no probes");
    return positions;
}

Json level_json(const Level& level, const LevelSettings& settings) {
    const tetprobe::Quake3Counts& c = level.import.counts;
    size_t frames = 0;
    for (uint32_t f : level.path_frames) frames += f;
    return Json{{"name", level.name}, {"file", level.file}, {"title", level.import.worldspawn_message},
                {"triangles", level.triangles}, {"lights", level.lights},
                {"light_entities", level.import.lights.size()},
                {"faces", {{"total", c.faces}, {"polygons", c.polygons}, {"meshes", c.meshes}, {"patches", c.patches},
                           {"brush_model", c.brush_model_faces}, {"billboards_left_out", c.billboards},
                           {"sky_left_out", c.sky}, {"nodraw_left_out", c.nodraw},
                           {"liquid_or_fog_left_out", c.liquid_or_fog}, {"nonsolid_left_out", c.nonsolid}}},
                {"playable", {{"band_points", level.band_points}, {"free_points", level.free_points},
                              {"reachable_points", level.playable.size() / 3},
                              {"spawns_used", level.spawns_used}, {"spawns_given", level.spawns_given},
                              {"box_min", {level.playable_lo[0], level.playable_lo[1], level.playable_lo[2]}},
                              {"box_max", {level.playable_hi[0], level.playable_hi[1], level.playable_hi[2]}}}},
                {"points", level.points.size() / 3}, {"mean_irradiance", level.mean},
                {"reference_noise", {{"points", std::min(settings.noise_points, level.points.size() / 3)},
                                     {"rms", level.noise_rms}, {"p95", level.noise_p95}}},
                {"paths", level.path_frames.size()}, {"path_frames", frames},
                {"prepare_seconds", {{"space", level.space_seconds}, {"reference", level.reference_seconds},
                                     {"from_cache", level.from_cache}}}};
}

int run_eval(const LevelArgs& a, const LevelSettings& settings) {
    if (a.levels.size() != 1 || a.probes.empty()) throw std::invalid_argument("levels eval needs --level NAME and --probes FILE.csv");
    std::vector<const StoreLayout*> layouts;
    if (a.layout.empty()) {
        for (const StoreLayout& l : store_layouts()) layouts.push_back(&l);
    } else {
        const StoreLayout* l = find_store_layout(a.layout);
        if (!l) throw std::invalid_argument("unknown layout " + a.layout);
        layouts.push_back(l);
    }
    Level level;
    prepare_level(level_path(a, a.levels[0]), a.cache, settings, a.threads, &level);
    const std::vector<float> positions = read_probe_csv(a.probes);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<float> sh = bake_probes(level, positions, settings);
    const double bake_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    Json results = Json::array();
    for (const StoreLayout* layout : layouts) {
        LevelResult r = evaluate_tetprobe(level, positions, sh, *layout);
        r.method = "tetprobe_given";
        r.bake_seconds = bake_seconds;
        results.push_back(r.json());
    }
    if (a.json) {
        Json out = {{"level", level_json(level, settings)}, {"probe_file", a.probes}, {"results", results}};
        std::printf("%s\n", out.dump(1).c_str());
        return 0;
    }
    std::printf("%s: %zu evaluation points, mean irradiance %.4g, reference noise %.3g RMS (%.3g p95)\n",
                level.name.c_str(), level.points.size() / 3, level.mean, level.noise_rms, level.noise_p95);
    std::printf("| layout | probes | bytes | resident bytes | RMS | p95 | worst jump | ns/query | bake s |\n");
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Json& r : results)
        std::printf("| %s | %zu | %llu | %llu | %.4f | %.4f | %.4f | %.1f | %.2f |\n", r["layout"].get<std::string>().c_str(),
                    r["probes"].get<size_t>(), (unsigned long long)r["bytes"].get<uint64_t>(),
                    (unsigned long long)r["resident_bytes"].get<uint64_t>(), r["rms_error"].get<double>(),
                    r["p95_error"].get<double>(), r["worst_jump"].get<double>(), r["ns_per_query"].get<double>(),
                    r["bake_seconds"].get<double>());
    return 0;
}

int run_prepare(const LevelArgs& a, const LevelSettings& settings) {
    for (const std::string& name : a.levels) {
        Level level;
        prepare_level(level_path(a, name), a.cache, settings, a.threads, &level);
        std::printf("%s\n", level_json(level, settings).dump().c_str());
    }
    return 0;
}

}  // namespace

int run_levels_bench(int argc, char** argv) {
    try {
        const LevelArgs a = parse_level_args(argc, argv);
        LevelSettings settings;
        if (a.command == "eval") return run_eval(a, settings);
        if (a.command == "prepare") return run_prepare(a, settings);
        std::fprintf(stderr, "usage: tetprobe_bench levels eval|prepare ... (see samples/bench/bench_levels.cpp)\n");
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetprobe_bench levels: %s\n", e.what());
        return 1;
    }
}
