// tetprobe_bench precision [--out DIR] [--quick] [--scene PATH]: part 2 of issue 8. SH float32 (the baked
// floats blended with tetprobe's own weights, tp_store_weights) against half (tp_store_interpolate), fast
// against compact layout, the 8-bit and L1 SH encodings and the quantised positions of issue 17
// (unorm8, half_l1, unorm8_l1 and half at 16-bit positions in the fast layout; unorm8 at 16-bit positions
// in the compact one: the smallest L2 store), and the
// evaluation choices L1, ZH3 (from L1) and full L2, each without a window,
// with Sloan's window and with the smallest non-negative window. Orders (ZH3 included) and Sloan's window are
// applied per query (tp_sh_eval_irradiance_ex on the blend); the non-negative window, which costs tens of
// minimum searches, is applied once per probe (tp_sh_apply_options before the store is built). ZH3 and the
// non-negative window do not commute with interpolation (tetprobe.h): per probe is a valid interpolant but
// not the per-query one, so the non-negative rows measure the per-probe interpolant (windowed probes
// blended), not the window applied to each query's blend. Writes DIR/precision.json (schema at the top
// of bench_methods.cpp).
#include "bench.h"

#include "bench_timing.h"
#include "method_json.h"
#include "method_scene.h"

#include "capi/tetprobe.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iterator>
#include <memory>
#include <stdexcept>

namespace {

using namespace bench;
using Json = nlohmann::ordered_json;

// A timed run lasts about this long (medians of 5 runs), at most kMaxTimedQueries queries.
constexpr double kTimedSeconds = 0.05;
constexpr size_t kMaxTimedQueries = 200000;

void check(tp_status status, const char* what) {
    if (status != TP_OK) throw std::runtime_error(std::string(what) + ": " + tp_last_error());
}

tp_store* build_store(const MethodScene& s, const std::vector<float>& probe_sh, uint32_t flags, uint32_t sh_encoding,
                      bool quantize_positions) {
    tp_build_options options;
    tp_build_options_init(&options);
    options.flags = flags;
    options.sh_encoding = sh_encoding;
    options.quantize_positions = quantize_positions ? 1u : 0u;
    tp_store* store = nullptr;
    check(tp_store_build(s.probes.data(), 0, probe_sh.data(), 0, s.probes.size() / 3, &options, &store), "tp_store_build");
    return store;
}

double store_bytes(const tp_store* store) {
    tp_store_info info;
    info.struct_size = sizeof(info);
    check(tp_store_get_info(store, &info), "tp_store_get_info");
    return double(info.bytes);
}

// How the SH of a point are obtained: from a store in one SH encoding (fast, compact, or compact with
// quantised positions) or from float SH blended with the fast store's weights (tp_store_weights).
struct Storage {
    std::string precision, layout;
    double store_bytes_per_probe = 0;
    std::shared_ptr<tp_store> store;
    std::vector<float> float_sh;
    std::function<void(const float*, int32_t*, float*)> interpolate;
};

// precision "float32" or a store's SH encoding ("half", "unorm8", "half_l1", "unorm8_l1"); layout
// "fast" or "compact", "_quantized" for 16-bit positions; over the given probe SH.
Storage make_storage(const MethodScene& s, const std::string& precision, const std::string& layout,
                     const std::vector<float>& probe_sh) {
    static const char* const encodings[4] = {"half", "unorm8", "half_l1", "unorm8_l1"};  // by TP_SH_ENCODING_*
    uint32_t encoding = TP_SH_ENCODING_HALF;
    for (uint32_t e = 0; e < 4; ++e)
        if (precision == encodings[e]) encoding = e;
    Storage storage;
    storage.precision = precision;
    storage.layout = layout;
    const bool quantized = layout.size() > 10 && layout.compare(layout.size() - 10, 10, "_quantized") == 0;
    storage.store.reset(build_store(s, probe_sh, layout.compare(0, 7, "compact") == 0 ? TP_BUILD_COMPACT : 0u, encoding,
                                    quantized),
                        tp_store_release);
    const double probes = double(s.probes.size() / 3);
    tp_store* store = storage.store.get();
    if (precision != "float32") {
        storage.store_bytes_per_probe = store_bytes(store) / probes;
        storage.interpolate = [store](const float* p, int32_t* hint, float* out) { tp_store_interpolate(store, p, hint, out); };
    } else {
        storage.store_bytes_per_probe = store_bytes(store) / probes + 27 * 2;  // 27 floats in place of 27 halves
        storage.float_sh = probe_sh;
        const float* sh = storage.float_sh.data();
        storage.interpolate = [store, sh](const float* p, int32_t* hint, float* out) {
            uint32_t probes[4];
            float weights[4];
            tp_store_weights(store, p, hint, probes, weights);
            for (int i = 0; i < 27; ++i) out[i] = 0;
            for (int k = 0; k < 4; ++k)
                for (int i = 0; i < 27; ++i) out[i] += weights[k] * sh[27 * size_t(probes[k]) + i];
        };
    }
    return storage;
}

// One evaluation choice: `options` is what it means; per_probe choices are applied to every probe's SH
// before the store is built, and the query evaluates the blend plainly (query_options: L2, no window).
struct Evaluation {
    std::string order_name, window_name;
    tp_sh_eval_options options, query_options;
    bool per_probe = false;
};

float luminance_ex(const float sh[27], const float n[3], const tp_sh_eval_options& options) {
    float rgb[3];
    check(tp_sh_eval_irradiance_ex(sh, n, &options, rgb), "tp_sh_eval_irradiance_ex");
    return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
}

struct RowResult {
    Json json;
    double rms = 0, ns = 0, bytes = 0;
    std::vector<double> squares;  // squared relative error per query point and normal, in a fixed order
};

RowResult bench_row(const MethodScene& s, const MethodSettings& settings, const Storage& storage, const Evaluation& e,
                    size_t probe_count) {
    // Errors against the reference's plain L2 irradiance.
    std::vector<double> squares;
    ErrorStats stats;
    size_t negative = 0;
    float sh[27];
    for (size_t i = 0; i < s.queries.size() / 3; ++i) {
        int32_t hint = -1;
        storage.interpolate(&s.queries[3 * i], &hint, sh);
        for (const auto& n : kAxisNormals) {
            const double error = (luminance_ex(sh, n, e.query_options) - irradiance_luminance(&s.reference[27 * i], n)) /
                                 s.mean_irradiance;
            stats.add(error);
            squares.push_back(error * error);
        }
        float min_rgb[3], normal[3];
        check(tp_sh_min_irradiance(sh, &e.query_options, min_rgb, normal), "tp_sh_min_irradiance");
        negative += min_rgb[0] < 0 || min_rgb[1] < 0 || min_rgb[2] < 0;
    }
    const double rms = stats.rms();

    // At the probes, against the probes' own bake evaluated with the same options.
    ErrorStats at_probes;
    for (size_t p = 0; p < probe_count; ++p) {
        int32_t hint = -1;
        storage.interpolate(&s.probes[3 * p], &hint, sh);
        for (const auto& n : kAxisNormals)
            at_probes.add((luminance_ex(sh, n, e.query_options) - luminance_ex(&s.probe_sh[27 * p], n, e.options)) /
                          s.mean_irradiance);
    }

    const size_t frames = s.path.size() / 3;
    float sink = 0;
    int32_t hint = -1;
    const size_t repetitions = repetitions_for(
        [&] {
            float rgb[3];
            for (size_t f = 0; f < frames; ++f) {
                storage.interpolate(&s.path[3 * f], &hint, sh);
                tp_sh_eval_irradiance_ex(sh, kUp, &e.query_options, rgb);
            }
        },
        settings.quick ? kTimedSeconds / 50 : kTimedSeconds, kMaxTimedQueries / frames + 1);
    const double seconds = median_seconds([&] {
        const Clock::time_point start = Clock::now();
        for (size_t r = 0; r < repetitions; ++r)
            for (size_t f = 0; f < frames; ++f) {
                float rgb[3];
                storage.interpolate(&s.path[3 * f], &hint, sh);
                tp_sh_eval_irradiance_ex(sh, kUp, &e.query_options, rgb);
                sink += rgb[1];
            }
        return seconds_since(start);
    });
    if (sink == 12345.678f) std::printf(" ");

    // float32 and half: L1 and ZH3 evaluated per query read 12 coefficients (the bytes of such a store);
    // ZH3 applied per probe stores its band 2. The other encodings: the store's own bytes.
    const bool adjusted = storage.precision == "float32" || storage.precision == "half";
    const double coefficient_bytes = storage.precision == "half" ? 2.0 : 4.0;
    const double read_coefficients =
        e.options.order == TP_SH_ORDER_L1 || (e.options.order == TP_SH_ORDER_ZH3 && !e.per_probe) ? 12.0 : 27.0;
    RowResult r;
    r.rms = rms;
    r.squares = std::move(squares);
    r.ns = 1e9 * seconds / double(repetitions * frames);
    r.bytes = adjusted ? storage.store_bytes_per_probe - 27.0 * coefficient_bytes + read_coefficients * coefficient_bytes
                       : storage.store_bytes_per_probe;
    r.json["id"] = storage.precision + "_" + storage.layout + "_" + e.order_name + "_" + e.window_name;
    r.json["precision"] = storage.precision;
    r.json["layout"] = storage.layout;
    r.json["order"] = e.order_name;
    r.json["window"] = e.window_name;
    r.json["applied"] = e.per_probe ? "per probe" : "per query";
    r.json["rms_error"] = rms;
    r.json["max_error"] = stats.max;
    r.json["negative_fraction"] = double(negative) / double(s.queries.size() / 3);
    r.json["ns_per_query"] = r.ns;
    r.json["bytes_per_probe"] = r.bytes;
    r.json["store_bytes_per_probe"] = storage.store_bytes_per_probe;
    r.json["at_probes_max_error"] = at_probes.max;
    return r;
}

// Two standard errors of the mean paired difference of squared errors between rows a and b (the same
// points, normals and reference), expressed on the RMS scale around a's RMS error.
double paired_margin(const RowResult& a, const RowResult& b) {
    const size_t n = a.squares.size();
    double mean = 0, variance = 0;
    for (size_t i = 0; i < n; ++i) mean += (b.squares[i] - a.squares[i]) / double(n);
    for (size_t i = 0; i < n; ++i) {
        const double d = b.squares[i] - a.squares[i] - mean;
        variance += d * d / double(n - 1);
    }
    const double mse_margin = 2 * std::sqrt(variance / double(n));
    return std::sqrt(a.rms * a.rms + mse_margin) - a.rms;
}

// Error first: a row ties with the lowest-error row when its RMS error is within the paired margin (noise
// of the comparison over the query points); of the tied rows, those within 10% of the fastest; of those, the
// fewest bytes per probe (then the fewest ns).
Json decide(const std::string& question, const std::vector<const RowResult*>& rows) {
    const RowResult* lowest = rows[0];
    for (const RowResult* r : rows)
        if (r->rms < lowest->rms) lowest = r;
    std::vector<const RowResult*> tied;
    double fastest = INFINITY, margin = 0;
    Json tied_ids = Json::array();
    for (const RowResult* r : rows) {
        const double pair_margin = paired_margin(*lowest, *r);
        if (r->rms <= lowest->rms + pair_margin) {
            tied.push_back(r), fastest = std::min(fastest, r->ns), margin = std::max(margin, pair_margin);
            tied_ids.push_back(r->json["id"]);
        }
    }
    const RowResult* winner = nullptr;
    for (const RowResult* r : tied)
        if (r->ns <= 1.1 * fastest &&
            (!winner || r->bytes < winner->bytes || (r->bytes == winner->bytes && r->ns < winner->ns)))
            winner = r;
    Json candidates = Json::array();
    for (const RowResult* r : rows) candidates.push_back(r->json["id"]);
    char why[400];
    std::snprintf(why, sizeof why,
                  "lowest RMS error %.4f (%s); %zu of %zu rows tie with it within the paired noise margin; of those "
                  "within 10%% of the fastest (%.1f ns), the fewest bytes per probe (%.1f)",
                  lowest->rms, lowest->json["id"].get<std::string>().c_str(), tied.size(), rows.size(), fastest,
                  winner->bytes);
    return {{"question", question}, {"candidates", candidates}, {"winner", winner->json["id"]}, {"why", why},
            {"tied", tied_ids}, {"tie_margin", margin}};
}

Json bench_scene(const std::string& path, const MethodSettings& settings) {
    MethodScene s;
    prepare_method_scene(path, settings, false, &s);
    const size_t probe_count = s.probes.size() / 3;
    // Sloan's window at one fixed strength: the one that de-rings a single directional light (a delta of
    // radiance, the hardest non-negative signal), so the fixed window guarantees what it can for any probe.
    float delta_sh[27] = {0};
    const float down[3] = {0, -1, 0}, white[3] = {1, 1, 1};
    check(tp_sh_add_directional(delta_sh, down, white), "tp_sh_add_directional");
    float sloan_strength = 0;
    check(tp_sh_nonnegative_window_strength(delta_sh, nullptr, &sloan_strength), "tp_sh_nonnegative_window_strength");

    std::vector<Evaluation> evaluations;
    const std::pair<uint32_t, const char*> orders[] = {{TP_SH_ORDER_L2, "L2"}, {TP_SH_ORDER_L1, "L1"}, {TP_SH_ORDER_ZH3, "ZH3"}};
    const std::pair<uint32_t, const char*> windows[] = {
        {TP_SH_WINDOW_NONE, "none"}, {TP_SH_WINDOW_SLOAN, "sloan"}, {TP_SH_WINDOW_NONNEGATIVE, "nonnegative"}};
    for (const auto& order : orders)
        for (const auto& window : windows) {
            Evaluation e;
            e.order_name = order.second;
            e.window_name = window.second;
            check(tp_sh_eval_options_init(&e.options), "tp_sh_eval_options_init");
            e.options.order = order.first;
            e.options.window = window.first;
            e.options.window_strength = window.first == TP_SH_WINDOW_SLOAN ? sloan_strength : 0.0f;
            e.per_probe = window.first == TP_SH_WINDOW_NONNEGATIVE;
            e.query_options = e.options;
            if (e.per_probe) check(tp_sh_eval_options_init(&e.query_options), "tp_sh_eval_options_init");
            evaluations.push_back(e);
        }

    const std::pair<const char*, const char*> storage_kinds[] = {
        {"float32", "fast"},  {"half", "fast"},      {"half", "compact"},           {"half", "fast_quantized"},
        {"unorm8", "fast"},   {"half_l1", "fast"},   {"unorm8_l1", "fast"},         {"unorm8", "compact_quantized"}};
    std::vector<RowResult> results;
    results.reserve(std::size(storage_kinds) * evaluations.size());
    for (const auto& kind : storage_kinds) {
        const Storage plain = make_storage(s, kind.first, kind.second, s.probe_sh);
        for (const Evaluation& e : evaluations) {
            if (!e.per_probe) {
                results.push_back(bench_row(s, settings, plain, e, probe_count));
                continue;
            }
            std::vector<float> applied = s.probe_sh;
            for (size_t p = 0; p < probe_count; ++p)
                check(tp_sh_apply_options(&applied[27 * p], &e.options), "tp_sh_apply_options");
            results.push_back(bench_row(s, settings, make_storage(s, kind.first, kind.second, applied), e, probe_count));
        }
    }

    std::vector<const RowResult*> storage_rows, evaluation_rows, all_rows;
    for (const RowResult& r : results) {
        all_rows.push_back(&r);
        if (r.json["order"] == "L2" && r.json["window"] == "none") storage_rows.push_back(&r);
        if (r.json["precision"] == "half" && r.json["layout"] == "fast") evaluation_rows.push_back(&r);
    }
    Json rows = Json::array();
    for (const RowResult& r : results) rows.push_back(r.json);
    Json decisions = Json::array({decide("precision and layout", storage_rows), decide("order and window", evaluation_rows),
                                  decide("overall", all_rows)});

    std::printf("\n### %s (%zu probes, %zu queries)\n\n", s.name.c_str(), probe_count, s.queries.size() / 3);
    std::printf("| row | RMS error | max error | negative | ns/query | bytes/probe |\n| --- | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Json& r : rows)
        std::printf("| %s | %.4f | %.4f | %.3f | %.1f | %.1f |\n", r["id"].get<std::string>().c_str(),
                    r["rms_error"].get<double>(), r["max_error"].get<double>(), r["negative_fraction"].get<double>(),
                    r["ns_per_query"].get<double>(), r["bytes_per_probe"].get<double>());
    for (const Json& d : decisions)
        std::printf("\n%s: **%s** (%s)\n", d["question"].get<std::string>().c_str(), d["winner"].get<std::string>().c_str(),
                    d["why"].get<std::string>().c_str());

    ErrorStats noise;
    for (size_t i = 0; i < s.queries.size() / 3; ++i)
        for (const auto& n : kAxisNormals)
            noise.add((irradiance_luminance(&s.second_reference[27 * i], n) - irradiance_luminance(&s.reference[27 * i], n)) /
                      s.mean_irradiance);
    Json j;
    j["name"] = s.name;
    j["file"] = s.file;
    j["probes"] = probe_count;
    j["queries"] = s.queries.size() / 3;
    j["mean_irradiance"] = s.mean_irradiance;
    j["reference_noise"] = noise.rms();
    j["tie_margin"] = decisions[2]["tie_margin"];
    j["sloan_strength"] = sloan_strength;
    j["rows"] = rows;
    j["decisions"] = decisions;
    return j;
}

}  // namespace

int run_precision_bench(int argc, char** argv) {
    const MethodArgs args = parse_method_args(argc, argv, {"samples/scenes/two_rooms.json"});
    const MethodSettings settings = method_settings(args.quick);
    std::printf("## Precision, layout and SH order\n");
    if (args.scenes.empty()) {
        std::fprintf(stderr, "No scene found: run from the repository root or pass --scene PATH.\n");
        return 1;
    }
    Json j;
    j["schema"] = "tetprobe-bench-precision/1";
    j["quick"] = settings.quick;
    j["bake"] = method_bake_json(settings);
    j["sh_options"] = "the library's tp_sh_eval_options (capi/tetprobe.h); orders and Sloan's window per query "
                      "(tp_sh_eval_irradiance_ex on the blend), the non-negative window per probe (tp_sh_apply_options "
                      "before the store is built; the query evaluates the blend plainly)";
    j["sloan_strength_rule"] = "the strength tp_sh_nonnegative_window_strength gives a single directional light";
    j["error"] = "|E_row - E_reference| (Rec. 709 luminance of the irradiance; the reference in full L2, no window) over "
                 "every query point and the 6 axis normals, divided by mean_irradiance";
    j["rule"] = "error first: a row ties with the lowest-error row when the mean paired difference of their squared "
                "errors (same points, normals, reference) is within 2 standard errors, i.e. within the noise of the "
                "comparison (tie_margin: the largest such margin among the tied rows, on the RMS scale); of the tied "
                "rows, those within 10% of the fastest ns_per_query; of those, the fewest bytes_per_probe (then the "
                "fewest ns)";
    j["scenes"] = Json::array();
    try {
        for (const std::string& path : args.scenes) j["scenes"].push_back(bench_scene(path, settings));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "precision benchmark failed: %s\n", e.what());
        return 1;
    }
    return write_json(args.out, "precision.json", j);
}
