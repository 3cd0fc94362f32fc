// `tetprobe bake` and `plan`: probes (the scene's own, or a probe file's) baked (effects plan, progress,
// summary) into a store or a probe file with SH, or only the effects plan of that bake.
#include "cli.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>

namespace cli {

BakeSettings bake_settings(const Arguments& a, uint32_t default_rays) {
    BakeSettings s;
    s.rays = uint32_t(parse_count(a.value("--rays", std::to_string(default_rays)), "--rays"));
    s.bounces = uint32_t(parse_count(a.value("--bounces", "2"), "--bounces"));
    s.seed = uint64_t(parse_count(a.value("--seed", "0"), "--seed"));
    s.threads = uint32_t(parse_count(a.value("--threads", "0"), "--threads"));
    if (s.rays == 0) throw UsageError("--rays must be at least 1");
    return s;
}

namespace {

std::vector<float> scene_probes(const tp_scene* scene) {
    const float* positions = nullptr;
    size_t count = 0;
    check(tp_scene_probes(scene, &positions, &count), "reading the scene's probes");
    if (count == 0) throw Failure("the scene lists no probe positions");
    return std::vector<float>(positions, positions + 3 * count);
}

tp_bake_options bake_options(const BakeSettings& settings) {
    tp_bake_options options;
    check(tp_bake_options_init(&options), "tp_bake_options_init");
    options.rays = settings.rays;
    options.bounces = settings.bounces;
    options.seed = settings.seed;
    options.threads = settings.threads;
    return options;
}

bool ends_with(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The positions to bake: --probes FILE, or the scene's own.
std::vector<float> probes_to_bake(const Arguments& a) {
    if (!a.has("--probes")) return {};
    const std::string path = a.value("--probes", "");
    const ProbeFile file = read_probe_file(path);
    if (file.positions.empty()) throw Failure(path + ": no probes");
    if (!file.sh.empty()) std::fprintf(stderr, "tetprobe: note: %s: its SH columns are not used (the bake makes new ones)\n", path.c_str());
    return file.positions;
}

}  // namespace

BakeResult bake_scene(const tp_scene* scene, const BakeSettings& settings, const std::vector<float>& positions) {
    BakeResult result;
    result.positions = positions.empty() ? scene_probes(scene) : positions;
    const size_t count = result.positions.size() / 3;
    tp_bake_options options = bake_options(settings);
    std::memset(&result.plan, 0, sizeof result.plan);
    result.plan.struct_size = sizeof result.plan;
    char text[512] = {0};
    check(tp_bake_plan(scene, result.positions.data(), 0, count, &options, &result.plan, text, sizeof text),
          "planning the bake");
    result.plan_text = text;
    std::printf("effects plan: %s\n", text);
    std::fflush(stdout);

    ProgressBar bar{"bake"};
    options.progress = &ProgressBar::callback;
    options.progress_user = &bar;
    result.sh.resize(size_t(count) * TP_SH_FLOATS);
    const auto start = std::chrono::steady_clock::now();
    const tp_status status = tp_bake(scene, result.positions.data(), 0, count, &options, result.sh.data(), 0);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    bar.finish();
    check(status, "baking");
    return result;
}

int command_bake(const std::vector<std::string>& args) {
    const Arguments a =
        parse_arguments(args, with_scene_options({"-o", "--probes", "--rays", "--bounces", "--seed", "--threads"}), {});
    if (a.positional.size() != 1 || !a.has("-o")) throw UsageError("bake takes SCENE and -o STORE (or -o PROBES.csv)");
    const BakeSettings settings = bake_settings(a, 256);
    const std::vector<float> positions = probes_to_bake(a);
    ScenePtr scene = load_scene(a.positional[0], a);
    const BakeResult baked = bake_scene(scene.get(), settings, positions);
    const size_t probes = baked.positions.size() / 3;
    std::printf("baked %zu probes x %u rays, %u bounces (plan: %u) in %.2f s (%.0f probe-rays/s)\n", probes,
                settings.rays, settings.bounces, baked.plan.bounces, baked.seconds,
                double(probes) * settings.rays / (baked.seconds > 0 ? baked.seconds : 1e-9));
    const std::string out = a.value("-o", "");
    if (ends_with(out, ".csv")) {
        write_probe_file(out, baked.positions, baked.sh);
        std::printf("wrote %s: %zu probes with their SH\n", out.c_str(), probes);
        return 0;
    }
    StorePtr store = build_store(baked.positions, baked.sh, false);
    check(tp_store_save_file(store.get(), out.c_str()), "saving the store");
    const tp_store_info info = store_info(store.get());
    std::printf("wrote %s: %u probes (%u merged), %u cells, %u-bit indices, %" PRIu64 " bytes\n", out.c_str(),
                info.probes, info.merged_probes, info.cells, info.index_bits, info.bytes);
    return 0;
}

int command_plan(const std::vector<std::string>& args) {
    const Arguments a =
        parse_arguments(args, with_scene_options({"--probes", "--rays", "--bounces", "--seed", "--threads"}), {"--json"});
    if (a.positional.size() != 1) throw UsageError("plan takes SCENE");
    const BakeSettings settings = bake_settings(a, 256);
    const std::vector<float> given = probes_to_bake(a);
    ScenePtr scene = load_scene(a.positional[0], a);
    const std::vector<float> positions = given.empty() ? scene_probes(scene.get()) : given;
    const tp_bake_options options = bake_options(settings);
    tp_effects_plan plan;
    std::memset(&plan, 0, sizeof plan);
    plan.struct_size = sizeof plan;
    char text[512] = {0};
    check(tp_bake_plan(scene.get(), positions.data(), 0, positions.size() / 3, &options, &plan, text, sizeof text),
          "planning the bake");
    if (!a.has("--json")) {
        std::printf("effects plan: %s\n", text);
        return 0;
    }
    nlohmann::ordered_json j;
    j["probes"] = positions.size() / 3;
    j["lights"] = plan.lights;
    j["direct_lights"] = plan.direct_lights;
    j["realtime_lights"] = plan.realtime_lights;
    j["out_of_range_lights"] = plan.out_of_range_lights;
    j["sky"] = plan.sky != 0;
    j["emissive_meshes"] = plan.emissive_meshes;
    j["bounces"] = plan.bounces;
    j["shadows"] = plan.shadows != 0;
    j["meshes"] = plan.meshes;
    j["shadow_casters"] = plan.shadow_casters;
    j["shadow_caster_candidates"] = plan.shadow_caster_candidates;
    j["inside_probes"] = plan.inside_probes;
    j["text"] = text;
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
}

}  // namespace cli
