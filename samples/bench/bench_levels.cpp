// tetprobe_bench levels ...: the real-level benchmark (Quake 3 levels of Debian's openarena-081-maps,
// extracted into the build tree by samples/bench/setup_levels.sh; `make bench` runs it through run_levels.sh).
//
//   tetprobe_bench levels [run] [--levels default|all|A,B,...] [--out DIR] [--quick]
//       The part of the report: on each level, tetprobe's probe choices (probe_choices.h) in every store
//       layout (store_layouts.h) at each probe count, the peers (level_peers.h) at the bytes of each
//       tetprobe layout's placed store, and at the bytes of each compact placed store every layout with as
//       many probes of one placement order as fit, all measured with the one metric (level_metric.h). Writes
//       DIR/levels.json (after every level) and prints a table per level.
//   tetprobe_bench levels eval --level NAME --probes FILE.csv [--layout ID] [--json]
//       One probe set (x,y,z per line) on one level: baked with the level's probe settings, built with
//       the store layout (default: every layout of store_layouts.h; --layout also takes fast_leak and
//       compact_leak, leak control), measured with the level's metric. Prints a table, or with
//       --json {"level": <level fields below, without results>, "probe_file": str, "results": [<result>]}.
//   tetprobe_bench levels placement [--levels default|all|A,B,...] [--out DIR]
//       Placement against the simpler choices among the same candidates, compact layout, at the counts
//       kPlacementCounts (50 to 4,000): placed (one tp_place_probes per count with that target, threads
//       --threads, as a user asks for N probes: the set is exchanged at its target, so a count need not
//       be a prefix of a larger count's placement), placed with leak control, random subsamples (mean of 3), the uniform
//       lattice pick, all candidates (with and without leak control), and the error placement reports for
//       each count (its curve) beside the one measured. Writes DIR/levels_placement.json:
//       {"schema": "tetprobe-bench-levels-placement/1", "machine", "settings": {"counts", "random_seeds",
//        "placement": {...as levels.json}, "threads": int}, "metric": str,
//        "levels": [{<level fields of levels.json>, "candidates": int, "placement_seconds": float,
//                    "placement_progress_calls": int, "curve": [[probes, error]] (the largest count's run),
//                    "all": {"rms", "rms_leak": float},
//                    "counts": [{"probes": int, "placed", "placed_leak", "random", "lattice", "reported": float,
//                                "placement_seconds": float, "p95": {"placed", "random", "lattice": float}}]}]}
//       (errors: RMS of the metric, p95 its 95th percentile; reported: the last point of that count's own
//       placement curve, the error it reports for its result, NaN written as null; "placement": "per count").
//   tetprobe_bench levels leakpoints --level NAME [--count N] --out DIR
//       Leak control point by point: the placed set of N probes (default: all candidates), compact layout,
//       with and without leak control, at each evaluation point. Writes DIR/leak_points_NAME_N|all.csv: per
//       point its position, the reference and both answers (mean luminance irradiance over the 6 normals over
//       the level's mean), both squared errors (summed over the 6 normals, the rms is the root of their mean
//       over points x 6), and for each of the cell's 4 probes (as the store without leak control locates
//       them) its index, weight without and with leak control, its light (as the answers), whether it sees
//       the point (an Embree ray) and its distance.
//   tetprobe_bench levels prepare --level NAME...   only prepares (and caches) the levels
//   tetprobe_bench levels survey                    every level of --maps: triangles, lights, spawns, size
//
// Common options: --maps DIR (the .bsp files; default build/levels/maps), --cache DIR (the prepared
// levels; default build/levels/cache; "" for none), --threads N (0 = all cores). A level is a name in
// --maps or a path to a .bsp file. The first use of a level bakes its reference (tens of seconds on two
// cores); later uses read it from the cache, so an evaluation takes its own bake and queries only.
//
// levels.json (stable: fields may be added, none renamed or removed)
// {
//   "schema": "tetprobe-bench-levels/1", "machine": {...as every part},
//   "settings": {"reference_rays", "probe_rays", "bounces": int, "points", "noise_points": int,
//                "light_clearance", "frame_step": float, "paths": int, "counts": [int], "random_seeds": int,
//                "space": {"spacing", "layer": float, "band": [min, max], "floor_cosine", "clearance": float},
//                "placement": {"mode": str, "spacing": float, "band": [min, max], "rays": int, "error_bound": 0},
//                "layouts": [{"id": str, "label": str}]},
//   "metric": str, "import": str,           // the definitions, in words
//   "all_levels": [str], "default_levels": [str],
//   "levels": [{
//     "name": str, "not_run": str,          // only "name" and "not_run" when the level failed
//     "file": str, "title": str, "triangles": int, "lights": int, "light_entities": int,
//     "faces": {"total", "polygons", "meshes", "patches", "brush_model", "billboards_left_out", "sky_left_out",
//               "nodraw_left_out", "liquid_or_fog_left_out", "nonsolid_left_out": int},
//     "playable": {"band_points", "free_points", "reachable_points", "spawns_used", "spawns_given": int,
//                  "box_min": [3], "box_max": [3]},
//     "points": int, "mean_irradiance": float,
//     "reference_noise": {"points": int, "rms": float, "p95": float},
//     "paths": int, "path_frames": int,
//     "prepare_seconds": {"space": float, "reference": float, "from_cache": bool},
//     "candidates": {"count": int, "spacing": float, "find_seconds": float, "bake_seconds": float},
//     "results": [{                          // <result>
//       "method": "tetprobe_placed" | "tetprobe_random" | "tetprobe_lattice" | "tetprobe_all" | "tetprobe_given"
//               | "tetprobe_placed_at_bytes"   // as many of one placement order as fit in a compact budget
//               | "grid_half" | "grid_apv8" | "bricks_apv8" | "knn4" | "knn4_damped",
//       "layout": str,                       // tetprobe: a store layout id; peers: "half" | "apv8"
//       "label": str, "probes": int,         // bricks: samples baked
//       "bytes": int, "resident_bytes": int, // what ships; what the loaded method holds
//       "rms_error", "p95_error", "max_error", "worst_jump", "ns_per_query": float,
//       "placement_seconds", "bake_seconds", "build_seconds": float,  // tetprobe choices: bake_seconds is the
//                                            // candidates' bake time per probe times the probes
//       "target": int | null,                // tetprobe and knn: the probe count asked for (null: all candidates)
//       "seeds": int,                        // tetprobe_random: the results are means over this many subsamples
//       "probe_set": "placed",               // knn: the probes it blends
//       "budget_bytes": int, "budget_of": str,  // peers and tetprobe_placed_at_bytes: the budget and whose bytes
//                                            // it is ("tetprobe placed compact 400")
//       "note": str}],
//     "skipped": [{"method": str, "budget_bytes" | "target": int, "why": str}]
//   }]
// }
#include "bench.h"

#include "level_metric.h"
#include "level_peers.h"
#include "level_reference.h"
#include "level_tetprobe.h"
#include "part_output.h"
#include "probe_choices.h"
#include "store_layouts.h"

#include "bake/ray_caster.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
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
    uint32_t count = 0;  // leakpoints: the placed count (0: all candidates)
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
        else if (arg == "--count") a.count = uint32_t(std::stoul(value()));
        else if (arg == "--layout") a.layout = value();
        else if (arg == "--threads") a.threads = uint32_t(std::stoul(value()));
        else if (arg == "--json") a.json = true;
        else if (arg == "--quick") a.quick = true;
        else throw std::invalid_argument("unknown option " + arg);
    }
    return a;
}

const char* const kMetricText =
    "Irradiance: Rec. 709 luminance of E(n) for the 6 axis normals. Error at each evaluation point and normal: "
    "|E_method - E_reference| / the level's mean (of the reference over the same points and normals); rms_error and "
    "p95_error: RMS and 95th percentile over points x normals. Evaluation points: random free points of the playable "
    "space (grid points of the walkable band 0.2-2 m above floors, not inside geometry, flood-filled from the spawn "
    "points; each moved by up to half a grid step), at least light_clearance from every point light. Reference: a bake "
    "at each point with reference_rays; reference_noise: a second seed against it. worst_jump: the largest change of E "
    "(any axis normal) between consecutive frames along walking paths, each the shortest way along the flood fill from a "
    "spawn point to the farthest spawn point it reaches (frame_step metres a frame), "
    "over the mean. ns_per_query: single queries along the paths, each object keeping its hint or state, median of 5 runs. "
    "bytes: what ships (a store's blob; a peer's run-time arrays); resident_bytes: what the loaded method holds.";
const char* const kImportText =
    "Quake 3 levels (IBSP 46) from Debian's openarena-081-maps, imported by bake/quake3_bsp: 32 units a metre, y up; "
    "polygons, meshes and Bezier patches (8 x 8 quads per 3 x 3 piece) of the world and brush models, one-sided, "
    "albedo 0.5; sky, nodraw, liquid, fog and nonsolid faces left out; light entities as inverse-square point (or spot) "
    "lights of q3map's scale, held at their value at 16 units (0.5 m) closer in as q3map2 does, plus a sun (irradiance 3) and a sky (radiance 0.25, 0.32, 0.45): bake/quake3_scene.h.";

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

// The levels of the benchmark, chosen by measuring all 50 (tetprobe_bench levels survey): q3map2 drops light
// entities unless told to keep them, so four levels have their lights; the others are lit by the stated sun
// and sky through their sky faces.
const std::vector<std::string> kAllLevels = {
    "aggressor",  // small indoor, 84 lights, 3 sky faces
    "q3dm6ish",   // indoor, 30 lights, no sky
    "kaos",       // indoor and outdoor, 30 lights, 193 curved patches (48k triangles)
    "oa_bases3",  // large outdoor base level, 22 lights
    "islanddm",   // large outdoor island, sun and sky only
    "wrackdm17",  // large, open to the sky, sun and sky only
};
const std::vector<std::string> kDefaultLevels = {"aggressor", "islanddm"};

// Probe counts of tetprobe's sets; the peers are built at the bytes each tetprobe layout takes at each.
const std::vector<uint32_t> kCounts = {100, 200, 400, 800};
const std::vector<uint32_t> kQuickCounts = {50, 100};
constexpr int kRandomSeeds = 3;
const std::vector<uint32_t> kPlacementCounts = {50, 100, 200, 400, 800, 1600, 3200, 4000};

// Means over the random subsamples' results (error, time and bytes).
LevelResult mean_of(const std::vector<LevelResult>& rs) {
    LevelResult m = rs.front();
    m.error = LevelError();
    m.ns_per_query = 0, m.bytes = 0, m.resident_bytes = 0, m.build_seconds = 0;
    for (const LevelResult& r : rs) {
        m.error.rms += r.error.rms / double(rs.size());
        m.error.p95 += r.error.p95 / double(rs.size());
        m.error.max += r.error.max / double(rs.size());
        m.error.worst_jump += r.error.worst_jump / double(rs.size());
        m.ns_per_query += r.ns_per_query / double(rs.size());
        m.bytes += r.bytes / rs.size(), m.resident_bytes += r.resident_bytes / rs.size();
        m.build_seconds += r.build_seconds / double(rs.size());
    }
    return m;
}

void print_row(const LevelResult& r, const char* what) {
    std::printf("| %s | %s | %s | %zu | %llu | %llu | %.4f | %.4f | %.4f | %.1f |\n", what, r.method.c_str(), r.layout.c_str(),
                r.probes, (unsigned long long)r.bytes, (unsigned long long)r.resident_bytes, r.error.rms, r.error.p95,
                r.error.worst_jump, r.ns_per_query);
    std::fflush(stdout);
}

Json run_level(const LevelArgs& a, const std::string& name, const LevelSettings& settings, const std::vector<uint32_t>& counts) {
    Level level;
    prepare_level(level_path(a, name), a.cache, settings, a.threads, &level);
    Json out = level_json(level, settings);
    std::printf("\n%s: %zu triangles, %zu lights, %zu playable points, mean irradiance %.4g, reference noise %.3g (p95 %.3g)\n",
                level.name.c_str(), level.triangles, level.lights, level.playable.size() / 3, level.mean, level.noise_rms,
                level.noise_p95);
    std::printf("| set | method | layout | probes | bytes | resident | RMS | p95 | worst jump | ns |\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    const PlacementRules rules;
    const CandidateSet candidates = find_candidates(level, rules, settings);
    const size_t candidate_count = candidates.positions.size() / 3;
    out["candidates"] = {{"count", candidate_count}, {"spacing", rules.spacing},
                         {"find_seconds", candidates.find_seconds}, {"bake_seconds", candidates.bake_seconds}};
    const double bake_per_probe = candidate_count ? candidates.bake_seconds / double(candidate_count) : 0.0;
    Json results = Json::array(), skipped = Json::array();
    auto add = [&](LevelResult r, const Json& extra, const char* what) {
        print_row(r, what);
        Json j = r.json();
        for (auto it = extra.begin(); it != extra.end(); ++it) j[it.key()] = it.value();
        results.push_back(j);
    };
    auto subset = [&](const std::vector<uint32_t>& picks, std::vector<float>* p, std::vector<float>* sh) {
        p->clear(), sh->clear();
        for (uint32_t i : picks) {
            p->insert(p->end(), &candidates.positions[3 * size_t(i)], &candidates.positions[3 * size_t(i)] + 3);
            sh->insert(sh->end(), &candidates.sh[27 * size_t(i)], &candidates.sh[27 * size_t(i)] + 27);
        }
    };
    std::vector<std::pair<std::string, size_t>> budgets;  // (what, bytes) the peers are built at
    for (uint32_t n : counts) {
        if (n > candidate_count) {
            skipped.push_back({{"method", "tetprobe"}, {"target", n}, {"why", "more than the " + std::to_string(candidate_count) + " candidates"}});
            continue;
        }
        double place_seconds = 0;
        const std::vector<float> placed = placed_probes(level, rules, n, &place_seconds);
        const std::vector<float> placed_sh = sh_of(level, candidates, placed, settings);
        std::vector<float> p, sh;
        for (const StoreLayout& layout : store_layouts()) {
            LevelResult r = evaluate_tetprobe(level, placed, placed_sh, layout);
            r.method = "tetprobe_placed";
            r.label = "tetprobe, placed, " + layout.label;
            r.placement_seconds = place_seconds;
            r.bake_seconds = bake_per_probe * double(r.probes);
            budgets.push_back({"tetprobe placed " + layout.id + " " + std::to_string(n), size_t(r.bytes)});
            add(r, {{"target", n}}, "placed");
            std::vector<LevelResult> randoms;
            for (int seed = 0; seed < kRandomSeeds; ++seed) {
                subset(random_pick(candidate_count, n, 100 + uint64_t(seed)), &p, &sh);
                randoms.push_back(evaluate_tetprobe(level, p, sh, layout));
            }
            LevelResult m = mean_of(randoms);
            m.method = "tetprobe_random", m.label = "tetprobe, random subsample (mean of 3), " + layout.label;
            m.bake_seconds = bake_per_probe * double(m.probes);
            add(m, {{"target", n}, {"seeds", kRandomSeeds}}, "random");
            subset(lattice_pick(candidates.positions, n), &p, &sh);
            LevelResult l = evaluate_tetprobe(level, p, sh, layout);
            l.method = "tetprobe_lattice", l.label = "tetprobe, uniform lattice pick, " + layout.label;
            l.bake_seconds = bake_per_probe * double(l.probes);
            add(l, {{"target", n}}, "lattice");
        }
        for (bool damped : {false, true}) add(evaluate_knn(level, placed, placed_sh, damped), {{"target", n}, {"probe_set", "placed"}}, "knn");
    }
    for (const StoreLayout& layout : store_layouts()) {
        LevelResult r = evaluate_tetprobe(level, candidates.positions, candidates.sh, layout);
        r.method = "tetprobe_all", r.label = "tetprobe, all candidates, " + layout.label;
        r.placement_seconds = candidates.find_seconds, r.bake_seconds = candidates.bake_seconds;
        add(r, {{"target", nullptr}}, "all");
    }
    // Equal memory, tetprobe at its best layout: at the bytes of each count's compact placed store (a budget the
    // peers below are built at), every layout holds as many probes of one placement order as fit: a prefix of the
    // greedy's order to 4,000 (placement exchanges only sets below about 1,000 at their own target, so a prefix is
    // the greedy's set for that count, not the exchanged set a target of that count would give).
    const size_t order_count = std::min<size_t>(candidate_count, kPlacementCounts.back());
    if (order_count >= 4 && !counts.empty()) {
        double order_seconds = 0;
        const std::vector<float> order = placed_probes(level, rules, uint32_t(order_count), &order_seconds);
        const std::vector<float> order_sh = sh_of(level, candidates, order, settings);
        for (const auto& budget : budgets) {
            if (budget.first.rfind("tetprobe placed compact ", 0) != 0) continue;
            for (const StoreLayout& layout : store_layouts()) {
                const size_t fit = tetprobe_count_within(level, order, order_sh, budget.second, layout);
                if (fit == 0) {
                    skipped.push_back({{"method", "tetprobe_placed_at_bytes"}, {"budget_bytes", budget.second},
                                       {"why", "4 probes of the " + layout.id + " layout exceed the budget"}});
                    continue;
                }
                const std::vector<float> p(order.begin(), order.begin() + 3 * fit);
                const std::vector<float> sh(order_sh.begin(), order_sh.begin() + 27 * fit);
                LevelResult r = evaluate_tetprobe(level, p, sh, layout);
                if (fit == order_count)
                    r.note = "all " + std::to_string(fit) + " probes of the placement order fit (it stops at " +
                             std::to_string(order_count) + ")";
                r.method = "tetprobe_placed_at_bytes";
                r.label = "tetprobe, placed, as many as fit, " + layout.label;
                r.placement_seconds = order_seconds;
                r.bake_seconds = bake_per_probe * double(r.probes);
                add(r, {{"target", fit}, {"budget_bytes", budget.second}, {"budget_of", budget.first}}, "at bytes");
            }
        }
    }
    for (const auto& budget : budgets) {
        const Json extra = {{"budget_bytes", budget.second}, {"budget_of", budget.first}};
        for (GridEncoding e : {GridEncoding::half, GridEncoding::apv8}) add(evaluate_grid(level, budget.second, e, settings, a.threads), extra, "grid");
        try {
            add(evaluate_bricks(level, budget.second, settings, a.threads), extra, "bricks");
        } catch (const std::runtime_error& e) {
            skipped.push_back({{"method", "bricks_apv8"}, {"budget_bytes", budget.second}, {"why", e.what()}});
            std::printf("| bricks | skipped at %zu bytes: %s |\n", budget.second, e.what());
        }
    }
    out["results"] = results;
    out["skipped"] = skipped;
    return out;
}

int run_part(const LevelArgs& a, const LevelSettings& settings) {
    std::vector<std::string> names = a.levels;
    if (names.empty() || (names.size() == 1 && names[0] == "default")) names = kDefaultLevels;
    if (names.size() == 1 && names[0] == "all") names = kAllLevels;
    const std::vector<uint32_t>& counts = a.quick ? kQuickCounts : kCounts;
    Json doc = {{"schema", "tetprobe-bench-levels/1"}, {"machine", machine_json(a.quick)}};
    doc["settings"] = {{"reference_rays", settings.reference_rays}, {"probe_rays", settings.probe_rays},
                       {"bounces", settings.bounces}, {"points", settings.points}, {"noise_points", settings.noise_points},
                       {"light_clearance", settings.light_clearance}, {"paths", settings.paths},
                       {"frame_step", settings.frame_step}, {"counts", counts}, {"random_seeds", kRandomSeeds},
                       {"space", {{"spacing", settings.space.spacing}, {"layer", settings.space.layer},
                                  {"band", {settings.space.band_min, settings.space.band_max}},
                                  {"floor_cosine", settings.space.floor_cosine}, {"clearance", settings.space.clearance}}},
                       {"placement", {{"mode", "walkable"}, {"spacing", PlacementRules().spacing},
                                      {"band", {PlacementRules().walk_min_height, PlacementRules().walk_max_height}},
                                      {"rays", PlacementRules().rays}, {"error_bound", 0}}},
                       {"layouts", Json::array()}};
    for (const StoreLayout& l : store_layouts()) doc["settings"]["layouts"].push_back({{"id", l.id}, {"label", l.label}});
    doc["metric"] = kMetricText;
    doc["import"] = kImportText;
    doc["all_levels"] = kAllLevels;
    doc["default_levels"] = kDefaultLevels;
    Json levels = Json::array();
    int status = 0;
    for (const std::string& name : names) {
        try {
            levels.push_back(run_level(a, name, settings, counts));
        } catch (const std::exception& e) {
            std::printf("%s: not run: %s\n", name.c_str(), e.what());
            levels.push_back({{"name", name}, {"not_run", e.what()}});
            status = 1;
        }
        if (!a.out.empty()) {
            doc["levels"] = levels;
            write_json_file(a.out, "levels.json", doc);  // after every level: a later failure keeps the earlier ones
        }
    }
    return status;
}

// Placement against the simpler choices on one level (see the top of this file: levels placement).
Json run_level_placement(const LevelArgs& a, const std::string& name, const LevelSettings& settings) {
    Level level;
    prepare_level(level_path(a, name), a.cache, settings, a.threads, &level);
    Json out = level_json(level, settings);
    const PlacementRules rules;
    const CandidateSet candidates = find_candidates(level, rules, settings);
    const size_t candidate_count = candidates.positions.size() / 3;
    const StoreLayout& plain = *find_store_layout("compact");
    const StoreLayout& leak = *find_store_layout("compact_leak");
    const uint32_t largest = uint32_t(std::min<size_t>(kPlacementCounts.back(), candidate_count));
    const PlacementRun run = placement_run(level, rules, largest, a.threads);
    std::printf("\n%s: %zu candidates, placement to %u probes in %.1f s (%zu progress reports), reference noise %.3g\n",
                level.name.c_str(), candidate_count, largest, run.seconds, run.progress_calls, level.noise_rms);
    std::printf("| probes | placed | placed, leak control | random (mean of %d) | lattice | placed / random | placed / lattice | "
                "reported | reported / measured |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n", kRandomSeeds);
    auto nullable = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
    auto subset = [&](const std::vector<uint32_t>& picks, std::vector<float>* p, std::vector<float>* sh) {
        p->clear(), sh->clear();
        for (uint32_t i : picks) {
            p->insert(p->end(), &candidates.positions[3 * size_t(i)], &candidates.positions[3 * size_t(i)] + 3);
            sh->insert(sh->end(), &candidates.sh[27 * size_t(i)], &candidates.sh[27 * size_t(i)] + 27);
        }
    };
    Json counts = Json::array();
    for (uint32_t n : kPlacementCounts) {
        if (n > largest) continue;
        const PlacementRun own = n == largest ? run : placement_run(level, rules, n, a.threads);
        const std::vector<float>& placed = own.positions;
        const std::vector<float> placed_sh = sh_of(level, candidates, placed, settings);
        const LevelError placed_error = evaluate_tetprobe(level, placed, placed_sh, plain).error;
        const double placed_rms = placed_error.rms;
        const double leak_rms = evaluate_tetprobe(level, placed, placed_sh, leak).error.rms;
        std::vector<float> p, sh;
        double random_rms = 0, random_p95 = 0;
        for (int seed = 0; seed < kRandomSeeds; ++seed) {
            subset(random_pick(candidate_count, n, 100 + uint64_t(seed)), &p, &sh);
            const LevelError e = evaluate_tetprobe(level, p, sh, plain).error;
            random_rms += e.rms / kRandomSeeds, random_p95 += e.p95 / kRandomSeeds;
        }
        subset(lattice_pick(candidates.positions, n), &p, &sh);
        const LevelError lattice_error = evaluate_tetprobe(level, p, sh, plain).error;
        const double lattice_rms = lattice_error.rms;
        const double reported = curve_error_at(own.curve, n);
        std::printf("| %u | %.4f | %.4f | %.4f | %.4f | %.3f | %.3f | %.4f | %.3f |\n", n, placed_rms, leak_rms, random_rms,
                    lattice_rms, placed_rms / random_rms, placed_rms / lattice_rms, reported, reported / placed_rms);
        std::fflush(stdout);
        counts.push_back({{"probes", n}, {"placed", placed_rms}, {"placed_leak", leak_rms}, {"random", random_rms},
                          {"lattice", lattice_rms}, {"reported", nullable(reported)}, {"placement_seconds", own.seconds},
                          {"p95", {{"placed", placed_error.p95}, {"random", random_p95}, {"lattice", lattice_error.p95}}}});
    }
    const double all_rms = evaluate_tetprobe(level, candidates.positions, candidates.sh, plain).error.rms;
    const double all_leak = evaluate_tetprobe(level, candidates.positions, candidates.sh, leak).error.rms;
    std::printf("| all %zu | %.4f | %.4f | | | | | | |\n", candidate_count, all_rms, all_leak);
    Json curve = Json::array();
    for (size_t k = 0; k + 1 < run.curve.size(); k += 2) curve.push_back({run.curve[k], run.curve[k + 1]});
    out["candidates"] = candidate_count;
    out["placement_seconds"] = run.seconds;
    out["placement_progress_calls"] = run.progress_calls;
    out["curve"] = curve;
    out["all"] = {{"rms", all_rms}, {"rms_leak", all_leak}};
    out["counts"] = counts;
    return out;
}

int run_placement_part(const LevelArgs& a, const LevelSettings& settings) {
    std::vector<std::string> names = a.levels;
    if (names.empty() || (names.size() == 1 && names[0] == "default")) names = kDefaultLevels;
    if (names.size() == 1 && names[0] == "all") names = kAllLevels;
    const PlacementRules rules;
    Json doc = {{"schema", "tetprobe-bench-levels-placement/1"}, {"machine", machine_json(false)}};
    doc["settings"] = {{"counts", kPlacementCounts}, {"random_seeds", kRandomSeeds}, {"threads", a.threads},
                       {"placement", {{"mode", "walkable"}, {"spacing", rules.spacing},
                                      {"band", {rules.walk_min_height, rules.walk_max_height}},
                                      {"rays", rules.rays}, {"error_bound", 0}, {"runs", "one per count, target = count"}}}};
    doc["metric"] = kMetricText;
    Json levels = Json::array();
    int status = 0;
    for (const std::string& name : names) {
        try {
            levels.push_back(run_level_placement(a, name, settings));
        } catch (const std::exception& e) {
            std::printf("%s: not run: %s\n", name.c_str(), e.what());
            levels.push_back({{"name", name}, {"not_run", e.what()}});
            status = 1;
        }
        if (!a.out.empty()) {
            doc["levels"] = levels;
            write_json_file(a.out, "levels_placement.json", doc);
        }
    }
    return status;
}

// Every level of --maps: what the choice of the benchmark's levels was made from.
int run_survey(const LevelArgs& a) {
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(a.maps))
        if (entry.path().extension() == ".bsp") files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
    std::printf("| level | triangles | light entities | spawn points | sky faces | size (m) |\n|---|---:|---:|---:|---:|---|\n");
    for (const std::string& file : files) {
        try {
            const tetprobe::Quake3Level l = tetprobe::read_quake3_bsp(file);
            float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            for (size_t i = 0; i < l.vertices.size(); ++i) lo[i % 3] = std::min(lo[i % 3], l.vertices[i]), hi[i % 3] = std::max(hi[i % 3], l.vertices[i]);
            std::printf("| %s | %zu | %zu | %zu | %u | %.0f x %.0f x %.0f |\n", fs::path(file).stem().c_str(), l.triangle_count(),
                        l.lights.size(), l.spawn_points.size() / 3, l.counts.sky, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
        } catch (const std::exception& e) {
            std::printf("| %s | not read: %s |\n", fs::path(file).stem().c_str(), e.what());
        }
    }
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

// Leak control point by point (see the top of this file: levels leakpoints).
int run_leak_points(const LevelArgs& a, const LevelSettings& settings) {
    if (a.levels.size() != 1 || a.out.empty())
        throw std::invalid_argument("levels leakpoints needs one --level and --out DIR");
    Level level;
    prepare_level(level_path(a, a.levels[0]), a.cache, settings, a.threads, &level);
    const PlacementRules rules;
    const CandidateSet candidates = find_candidates(level, rules, settings);
    std::vector<float> positions = candidates.positions, sh = candidates.sh;
    const uint32_t target = a.count;
    if (target) {
        const PlacementRun run = placement_run(level, rules, target, a.threads);
        const size_t n = std::min<size_t>(target, run.positions.size() / 3);
        positions.assign(run.positions.begin(), run.positions.begin() + 3 * std::ptrdiff_t(n));
        sh = sh_of(level, candidates, positions, settings);
    }
    const size_t count = positions.size() / 3;
    using StoreHandle = std::unique_ptr<tp_store, tp_status (*)(tp_store*)>;
    StoreHandle stores[2] = {StoreHandle(nullptr, tp_store_release), StoreHandle(nullptr, tp_store_release)};
    for (int k = 0; k < 2; ++k) {
        tp_build_options options;
        tp_build_options_init(&options);
        find_store_layout(k ? "compact_leak" : "compact")->apply(&options, level.handle.get());
        tp_store* built = nullptr;
        if (tp_store_build(positions.data(), 0, sh.data(), 0, count, &options, &built) != TP_OK)
            throw std::runtime_error(level.name + ": tp_store_build: " + tp_last_error());
        stores[k].reset(built);
    }
    const std::vector<float> probe_light = luminance6(sh.data(), count);
    const double origin[3] = {0, 0, 0};
    const tetprobe::RayCaster caster(level.scene, origin);
    const auto mean6 = [&](const float* v) { return (v[0] + v[1] + v[2] + v[3] + v[4] + v[5]) / 6.0 / level.mean; };
    const std::string path = a.out + "/leak_points_" + level.name + "_" + (target ? std::to_string(target) : "all") + ".csv";
    fs::create_directories(a.out);
    std::ofstream csv(path);
    csv << "point,x,y,z,reference,without,with,squared_error_without,squared_error_with";
    for (int j = 0; j < 4; ++j)
        csv << ",probe" << j << ",weight_without" << j << ",weight_with" << j << ",light" << j << ",sees_query" << j
            << ",distance" << j;
    csv << "\n";
    double sum[2] = {0, 0};
    for (size_t i = 0; i < level.points.size() / 3; ++i) {
        const float* q = &level.points[3 * i];
        float out[2][27], weights[2][4];
        uint32_t probes[2][4];
        for (int k = 0; k < 2; ++k) {
            int32_t hint = -1;
            if (tp_store_interpolate(stores[k].get(), q, &hint, out[k]) != TP_OK)
                throw std::runtime_error(level.name + ": point " + std::to_string(i) + ": " + tp_last_error());
            hint = -1;
            if (tp_store_weights(stores[k].get(), q, &hint, probes[k], weights[k]) != TP_OK)
                throw std::runtime_error(level.name + ": point " + std::to_string(i) + ": " + tp_last_error());
        }
        const std::vector<float> reference = luminance6(&level.reference[27 * i], 1);
        double squared[2] = {0, 0};
        std::vector<float> light[2];
        for (int k = 0; k < 2; ++k) {
            light[k] = luminance6(out[k], 1);
            for (int c = 0; c < 6; ++c) squared[k] += std::pow((light[k][c] - reference[c]) / level.mean, 2);
            sum[k] += squared[k];
        }
        char row[256];
        std::snprintf(row, sizeof row, "%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g", i, q[0], q[1], q[2],
                      mean6(reference.data()), mean6(light[0].data()), mean6(light[1].data()), squared[0], squared[1]);
        csv << row;
        for (int j = 0; j < 4; ++j) {
            const uint32_t p = probes[0][j];
            float with = 0;  // the same probe's weight in the leak-control store (unused slots repeat a probe)
            for (int m = 0; m < 4; ++m)
                if (probes[1][m] == p) with = std::max(with, weights[1][m]);
            float d[3];
            double length = 0;
            for (int c = 0; c < 3; ++c) d[c] = positions[3 * size_t(p) + c] - q[c], length += double(d[c]) * d[c];
            length = std::sqrt(length);
            for (float& c : d) c = float(c / length);
            const bool sees = !(length > 0) || !caster.occluded(q, d, 0.0f, float(length), -1);
            std::snprintf(row, sizeof row, ",%u,%.6g,%.6g,%.6g,%d,%.4g", p, weights[0][j], with,
                          mean6(&probe_light[6 * size_t(p)]), sees ? 1 : 0, length);
            csv << row;
        }
        csv << "\n";
    }
    const size_t values = level.points.size() / 3 * 6;
    std::printf("%s, %zu probes: rms %.4f without, %.4f with leak control; wrote %s\n", level.name.c_str(), count,
                std::sqrt(sum[0] / values), std::sqrt(sum[1] / values), path.c_str());
    return 0;
}

}  // namespace

int run_levels_bench(int argc, char** argv) {
    try {
        const LevelArgs a = parse_level_args(argc, argv);
        LevelSettings settings;
        if (a.command == "eval") return run_eval(a, settings);
        if (a.command == "prepare") return run_prepare(a, settings);
        if (a.command == "survey") return run_survey(a);
        if (a.command == "leakpoints") return run_leak_points(a, settings);
        if (a.command == "placement") return run_placement_part(a, settings);
        if (a.command.empty() || a.command == "run") return run_part(a, settings);
        std::fprintf(stderr, "usage: tetprobe_bench levels [run]|eval|placement|leakpoints|prepare|survey ... (see samples/bench/bench_levels.cpp)\n");
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetprobe_bench levels: %s\n", e.what());
        return 1;
    }
}
