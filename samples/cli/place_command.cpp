// `tetprobe place`: probe positions proposed for a scene (tp_place_probes), written as CSV, with the
// error against the number of probes as JSON.
#include "cli.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <string>

namespace cli {

void place_scene_probes(tp_scene* scene, float spacing, float error_bound) {
    const float* given = nullptr;
    size_t hand_placed = 0;
    check(tp_scene_probes(scene, &given, &hand_placed), "reading the scene's probes");
    tp_placement_options options;
    check(tp_placement_options_init(&options), "tp_placement_options_init");
    options.spacing = spacing;
    options.error_bound = error_bound;
    size_t bound = 0, count = 0, points = 0;
    check(tp_place_probes_bound(scene, &options, &bound), "sizing the placement");
    std::vector<float> positions(3 * bound), curve(2 * bound + 2);
    const auto start = std::chrono::steady_clock::now();
    check(tp_place_probes(scene, &options, positions.data(), bound, &count, curve.data(), bound + 1, &points),
          "placing probes");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    check(tp_scene_set_probes(scene, positions.data(), count), "setting the placed probes");
    std::printf("placement: %zu probes placed automatically (spacing %g, estimated error %.3f, bound %g) in %.2f s, "
                "instead of the file's %zu hand-placed ones\n",
                count, spacing, points ? double(curve[2 * (points - 1) + 1]) : 0.0, error_bound, seconds, hand_placed);
}

int command_place(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(
        args, with_scene_options({"-o", "--mode", "--spacing", "--margin", "--target", "--error", "--rays", "--bounces",
                                  "--seed", "--threads", "--curve", "--min-height", "--max-height"}),
        {});
    if (a.positional.size() != 1 || !a.has("-o")) throw UsageError("place takes SCENE and -o PROBES.csv");
    tp_placement_options options;
    check(tp_placement_options_init(&options), "tp_placement_options_init");
    const std::string mode = a.value("--mode", "whole");
    if (mode != "whole" && mode != "walkable") throw UsageError("--mode is whole or walkable");
    options.mode = mode == "walkable" ? TP_PLACEMENT_WALKABLE : TP_PLACEMENT_WHOLE;
    options.spacing = float(parse_number(a.value("--spacing", std::to_string(options.spacing)), "--spacing"));
    options.margin = float(parse_number(a.value("--margin", std::to_string(options.margin)), "--margin"));
    options.walk_min_height = float(parse_number(a.value("--min-height", std::to_string(options.walk_min_height)), "--min-height"));
    options.walk_max_height = float(parse_number(a.value("--max-height", std::to_string(options.walk_max_height)), "--max-height"));
    options.target_count = uint32_t(parse_count(a.value("--target", "0"), "--target"));
    // A target alone places that many; an error bound alone (or with the target) also stops placement.
    options.error_bound = float(parse_number(a.value("--error", a.has("--target") ? "0" : std::to_string(options.error_bound)), "--error"));
    options.rays = uint32_t(parse_count(a.value("--rays", std::to_string(options.rays)), "--rays"));
    options.bounces = uint32_t(parse_count(a.value("--bounces", std::to_string(options.bounces)), "--bounces"));
    options.seed = uint64_t(parse_count(a.value("--seed", "0"), "--seed"));
    options.threads = uint32_t(parse_count(a.value("--threads", "0"), "--threads"));

    ScenePtr scene = load_scene(a.positional[0], a);
    size_t bound = 0;
    check(tp_place_probes_bound(scene.get(), &options, &bound), "sizing the placement");
    std::vector<float> positions(3 * bound), curve(2 * bound + 2);
    size_t count = 0, points = 0;
    ProgressBar bar{"place"};
    options.progress = &ProgressBar::callback;
    options.progress_user = &bar;
    const auto start = std::chrono::steady_clock::now();
    const tp_status status = tp_place_probes(scene.get(), &options, positions.data(), bound, &count, curve.data(),
                                             bound + 1, &points);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    bar.finish();
    check(status, "placing probes");

    positions.resize(3 * count);
    const std::string out = a.value("-o", "");
    write_probe_file(out, positions, {});
    const float error = points ? curve[2 * (points - 1) + 1] : 0.0f;
    std::printf("placed %zu probes in %.2f s, estimated error %.4f (luminance irradiance at validation points, "
                "relative to their mean); wrote %s\n",
                count, seconds, error, out.c_str());
    if (a.has("--curve")) {
        nlohmann::json json;
        json["scene"] = a.positional[0];
        json["spacing"] = options.spacing;
        json["margin"] = options.margin;
        json["mode"] = mode;
        json["seconds"] = seconds;
        nlohmann::json rows = nlohmann::json::array();
        for (size_t i = 0; i < points; ++i) rows.push_back({{"probes", int64_t(curve[2 * i])}, {"error", curve[2 * i + 1]}});
        json["error_curve"] = rows;
        const std::string text = json.dump(1) + "\n", path = a.value("--curve", "");
        write_file_atomically(path, text.data(), text.size());
        std::printf("wrote %s (%zu points of error against probe count)\n", path.c_str(), points);
    }
    return 0;
}

}  // namespace cli
