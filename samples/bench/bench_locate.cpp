// Part 3 of the report, locate: how many cells the walk visits and what a located query costs, for
// coherent objects (hint of the last frame), cold queries (no hint) with the start grid and without
// it (every walk from cell 0, the inner cell nearest the probes' centre, which is where a store
// without the grid would start), and teleports (hint of the previous random point), next to CGAL's
// exact locate on the same points. The probes and query points are written as .npy so that
// samples/bench/scipy_locate.py times scipy's Delaunay.find_simplex on exactly the same points.
// Also the blend-only floor and tp_store_interpolate on the coherent paths (the report's ratio
// "our query / floor"). Writes locate.json with --out DIR; --quick: one small probe set.
#include "bench.h"

#include "bench_timing.h"
#include "blob_sh.h"
#include "cgal_peer.h"
#include "coherent_timing.h"
#include "part_output.h"
#include "query_sets.h"

#include "capi/tetprobe.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace bench;
using nlohmann::json;

struct StoreDeleter {
    void operator()(tp_store* s) const { tp_store_release(s); }
};
using StorePtr = std::unique_ptr<tp_store, StoreDeleter>;

struct Workload {
    size_t objects, frames, cold_points;
};

double ns(double seconds, size_t queries) { return 1e9 * seconds / double(queries); }

tp_location locate(const tp_store* store, const float* p, int32_t* hint) {
    tp_location loc;
    std::memset(&loc, 0, sizeof loc);
    loc.struct_size = sizeof loc;
    tp_store_locate(store, p, hint, &loc);
    return loc;
}

// A row of the locate table: time per query (median of runs) and walk steps (one counting pass).
struct Row {
    std::string method, query, start;
    double ns = NAN, mean_steps = NAN;
    long max_steps = -1;  // -1: the method does not report steps
    size_t queries = 0;
};

json row_json(const Row& r) {
    json j = {{"method", r.method}, {"query", r.query}, {"start", r.start}, {"queries", r.queries}};
    j["ns_per_query"] = std::isnan(r.ns) ? json(nullptr) : json(r.ns);
    j["mean_steps"] = std::isnan(r.mean_steps) ? json(nullptr) : json(r.mean_steps);
    j["max_steps"] = r.max_steps < 0 ? json(nullptr) : json(r.max_steps);
    return j;
}

// tetprobe over the objects' paths, each object carrying its hint (frame 0 untimed).
Row tetprobe_paths(const tp_store* store, const ObjectPaths& paths, float* sink) {
    Row r{"tetprobe", "coherent", "hint of the last frame"};
    std::vector<int32_t> start(paths.objects, -1);
    for (size_t o = 0; o < paths.objects; ++o) locate(store, paths.at(o, 0), &start[o]);
    r.queries = paths.timed_queries();
    r.ns = ns(median_seconds([&] {
                  float acc = 0;
                  const Clock::time_point t0 = Clock::now();
                  for (size_t o = 0; o < paths.objects; ++o) {
                      int32_t hint = start[o];
                      for (size_t f = 1; f < paths.frames; ++f) acc += locate(store, paths.at(o, f), &hint).weights[0];
                  }
                  const double s = seconds_since(t0);
                  *sink += acc;
                  return s;
              }),
              r.queries);
    double steps = 0;
    long worst = 0;
    for (size_t o = 0; o < paths.objects; ++o) {
        int32_t hint = start[o];
        for (size_t f = 1; f < paths.frames; ++f) {
            const uint32_t s = locate(store, paths.at(o, f), &hint).steps;
            steps += s;
            worst = std::max<long>(worst, s);
        }
    }
    r.mean_steps = steps / double(r.queries);
    r.max_steps = worst;
    return r;
}

// tetprobe over points; fixed_hint >= 0 starts every query there, -1 carries the previous point's
// cell (teleport), -2 gives no hint (the start grid).
Row tetprobe_points(const tp_store* store, const std::vector<float>& points, int32_t fixed_hint, float* sink) {
    Row r{"tetprobe", fixed_hint == -1 ? "teleport" : "cold",
          fixed_hint == -1   ? "hint of the previous random point"
          : fixed_hint == -2 ? "start grid"
                             : "cell 0 (no grid)"};
    const size_t n = points.size() / 3;
    r.queries = n;
    const auto pass = [&](double* steps, long* worst) {
        float acc = 0;
        int32_t hint = -1;
        for (size_t i = 0; i < n; ++i) {
            if (fixed_hint != -1) hint = fixed_hint == -2 ? -1 : fixed_hint;
            const tp_location loc = locate(store, &points[3 * i], &hint);
            acc += loc.weights[0];
            if (steps) {
                *steps += loc.steps;
                *worst = std::max<long>(*worst, loc.steps);
            }
        }
        return acc;
    };
    r.ns = ns(median_seconds([&] {
                  const Clock::time_point t0 = Clock::now();
                  const float acc = pass(nullptr, nullptr);
                  const double s = seconds_since(t0);
                  *sink += acc;
                  return s;
              }),
              n);
    double steps = 0;
    long worst = 0;
    pass(&steps, &worst);
    r.mean_steps = steps / double(n);
    r.max_steps = worst;
    return r;
}

// tp_store_interpolate on the paths and the blend-only floor on the same probes and weights.
void interpolate_and_floor(const tp_store* store, const ObjectPaths& paths, json* out, float* sink) {
    (*out)["interpolate_coherent_ns"] = time_coherent_single(store, paths, sink);
    BlobSh blob;
    if (!read_blob_sh(store, &blob)) {
        (*out)["floor_ns"] = nullptr;
        return;
    }
    (*out)["floor_ns"] = time_blend_floor(store, blob, paths, sink);
}

json run_size(size_t n, const Workload& w, const PartOptions& options, float* sink) {
    const std::vector<float> positions = random_probes(n, 7), sh = random_sh(n, 8);
    const ObjectPaths paths = moving_objects(w.objects, w.frames, 0.05f * kBox, 0.95f * kBox, 11);
    const std::vector<float> cold = random_points(w.cold_points, 0.05f * kBox, 0.95f * kBox, 12);
    tp_store* raw = nullptr;
    if (tp_store_build(positions.data(), 0, sh.data(), 0, n, nullptr, &raw) != TP_OK)
        throw std::runtime_error(std::string("tp_store_build: ") + tp_last_error());
    const StorePtr store(raw);

    json size = {{"probes", n}, {"objects", w.objects}, {"frames", w.frames}, {"cold_points", w.cold_points}};
    const std::string prefix = "locate_" + std::to_string(n) + "_";
    size["files"] = {{"probes", prefix + "probes.npy"}, {"coherent", prefix + "coherent.npy"},
                     {"cold", prefix + "cold.npy"}};
    if (!options.out_dir.empty()) {
        write_npy_f32(options.out_dir, prefix + "probes.npy", positions.data(), n, 3);
        write_npy_f32(options.out_dir, prefix + "coherent.npy", paths.by_object.data(), w.objects * w.frames, 3);
        write_npy_f32(options.out_dir, prefix + "cold.npy", cold.data(), w.cold_points, 3);
    }

    std::vector<Row> rows = {tetprobe_paths(store.get(), paths, sink), tetprobe_points(store.get(), cold, -2, sink),
                             tetprobe_points(store.get(), cold, 0, sink), tetprobe_points(store.get(), cold, -1, sink)};
    if (cgal_peer_available()) {
        BlobSh blob;
        read_blob_sh(store.get(), &blob);
        const auto cgal = CgalPeer::build(positions.data(), blob.input_remap.data(), n, blob.sh, blob.stride);
        Row coherent{"CGAL", "coherent", "hint of the last frame"}, fresh{"CGAL", "cold", "none (CGAL's own start)"},
            teleport{"CGAL", "teleport", "hint of the previous random point"};
        coherent.queries = paths.timed_queries();
        coherent.ns = ns(median_seconds([&] { return cgal->locate_paths(paths, sink); }), coherent.queries);
        fresh.queries = teleport.queries = w.cold_points;
        fresh.ns = ns(median_seconds([&] { return cgal->locate_points(cold.data(), w.cold_points, false, sink); }),
                      w.cold_points);
        teleport.ns = ns(median_seconds([&] { return cgal->locate_points(cold.data(), w.cold_points, true, sink); }),
                         w.cold_points);
        rows.insert(rows.end(), {coherent, fresh, teleport});
    }
    size["rows"] = json::array();
    for (const Row& r : rows) size["rows"].push_back(row_json(r));
    interpolate_and_floor(store.get(), paths, &size, sink);
    return size;
}

}  // namespace

int run_locate_bench(int argc, char** argv) {
    const PartOptions options = part_options(argc, argv);
    const std::vector<size_t> counts =
        options.quick ? std::vector<size_t>{300} : std::vector<size_t>{1500, 10000, 65000};
    const Workload w = options.quick ? Workload{32, 10, 500} : Workload{512, 100, 20000};
    json result = {{"part", "locate"}, {"machine", machine_json(options.quick)}, {"repetitions", kRepetitions}};
    result["peers_not_run"] = json::object();
    if (!cgal_peer_available()) result["peers_not_run"]["CGAL"] = "libcgal-dev not found when tetprobe_bench was built";
    result["sizes"] = json::array();
    float sink = 0;
    try {
        for (size_t n : counts) {
            std::fprintf(stderr, "locate benchmark: %zu probes...\n", n);
            result["sizes"].push_back(run_size(n, w, options, &sink));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "locate benchmark failed: %s\n", e.what());
        return 1;
    }
    std::printf("## Locate\n\n| probes | method | query | start | ns/query | mean steps | max steps |\n");
    std::printf("| ---: | --- | --- | --- | ---: | ---: | ---: |\n");
    for (const json& size : result["sizes"])
        for (const json& r : size["rows"])
            std::printf("| %zu | %s | %s | %s | %s | %s | %s |\n", size["probes"].get<size_t>(),
                        r["method"].get<std::string>().c_str(), r["query"].get<std::string>().c_str(),
                        r["start"].get<std::string>().c_str(), r["ns_per_query"].dump().c_str(),
                        r["mean_steps"].dump().c_str(), r["max_steps"].dump().c_str());
    std::printf("\n(checksum %g)\n", double(sink));
    if (!options.out_dir.empty()) write_json_file(options.out_dir, "locate.json", result);
    return 0;
}
