// `tetprobe build`, `info` and `query`: probe stores from files, described and queried.
#include "cli.h"

#include <nlohmann/json.hpp>

#include <cinttypes>
#include <cstdio>
#include <cstring>

namespace cli {

int command_build(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, with_scene_options({"-o", "--scene"}), {"--compact"});
    if (a.positional.size() != 1 || !a.has("-o")) throw UsageError("build takes INPUT and -o STORE");
    if (!a.has("--scene") && (a.has("--scale") || a.has("--up"))) throw UsageError("--scale and --up go with --scene");
    const ProbeFile input = read_probe_file(a.positional[0]);
    if (input.positions.empty()) throw Failure(a.positional[0] + ": no probes");
    // With a scene, leak control: cells whose probes cannot see each other weigh down the one behind the wall.
    ScenePtr scene = a.has("--scene") ? load_scene(a.value("--scene", ""), a) : ScenePtr();
    StorePtr store = build_store(input.positions, input.sh, false, a.has("--compact") ? TP_BUILD_COMPACT : 0u, scene.get());
    const std::string out = a.value("-o", "");
    check(tp_store_save_file(store.get(), out.c_str()), "saving the store");
    const tp_store_info info = store_info(store.get());
    std::printf("built %s: %u probes (%u merged), %u cells (%u inner, %u outer), %" PRIu64 " bytes, %s layout%s%s\n",
                out.c_str(), info.probes, info.merged_probes, info.cells, info.inner_cells, info.outer_cells,
                info.bytes, store_layout(info), input.sh.empty() ? " (no SH given: zeros)" : "",
                scene ? (", leak control: " + std::to_string(info.leak_edges) + " blocked probe pairs").c_str() : "");
    return 0;
}

int command_info(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, {}, {"--json"});
    if (a.positional.size() != 1) throw UsageError("info takes STORE");
    StorePtr store = load_store(a.positional[0]);
    const tp_store_info i = store_info(store.get());
    nlohmann::ordered_json j;
    j["format_version"] = i.format_version;
    j["dimension"] = i.dimension;
    j["probes"] = i.probes;
    j["input_probes"] = i.input_probes;
    j["merged_probes"] = i.merged_probes;
    j["cells"] = i.cells;
    j["inner_cells"] = i.inner_cells;
    j["outer_cells"] = i.outer_cells;
    j["index_bits"] = i.index_bits;
    j["layout"] = store_layout(i);
    j["extrapolation"] = (i.flags & TP_BUILD_NO_EXTRAPOLATION) == 0;
    j["grid"] = {i.grid[0], i.grid[1], i.grid[2]};
    j["bytes"] = i.bytes;
    j["origin"] = {i.origin[0], i.origin[1], i.origin[2]};
    j["bounds_min"] = {i.bounds_min[0], i.bounds_min[1], i.bounds_min[2]};
    j["bounds_max"] = {i.bounds_max[0], i.bounds_max[1], i.bounds_max[2]};
    if (a.has("--json")) {
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    for (const auto& item : j.items()) std::printf("%-15s %s\n", (item.key() + ":").c_str(), item.value().dump().c_str());
    return 0;
}

int command_query(const std::vector<std::string>& args) {
    const Arguments a = parse_arguments(args, {}, {"--weights", "--json"});
    if (a.positional.size() != 4) throw UsageError("query takes STORE x y z");
    float position[3];
    for (int k = 0; k < 3; ++k) position[k] = float(parse_number(a.positional[1 + k], "a coordinate"));
    StorePtr store = load_store(a.positional[0]);
    float sh[TP_SH_FLOATS];
    int32_t hint = -1;
    check(tp_store_interpolate(store.get(), position, &hint, sh), "tp_store_interpolate");
    tp_location location;
    std::memset(&location, 0, sizeof location);
    location.struct_size = sizeof location;
    check(tp_store_locate(store.get(), position, nullptr, &location), "tp_store_locate");
    const float up[3] = {0, 1, 0};
    float irradiance[3];
    check(tp_sh_eval_irradiance(sh, up, irradiance), "tp_sh_eval_irradiance");
    nlohmann::ordered_json j;
    j["position"] = {position[0], position[1], position[2]};
    j["cell"] = location.cell;
    j["cell_kind"] = location.cell_kind == TP_CELL_OUTER ? "outer" : "inner";
    j["steps"] = location.steps;
    j["sh"] = std::vector<float>(sh, sh + TP_SH_FLOATS);
    j["irradiance_up"] = {irradiance[0], irradiance[1], irradiance[2]};
    if (a.has("--weights")) {
        j["probes"] = {location.probes[0], location.probes[1], location.probes[2], location.probes[3]};
        j["weights"] = {location.weights[0], location.weights[1], location.weights[2], location.weights[3]};
    }
    if (a.has("--json")) {
        std::printf("%s\n", j.dump(2).c_str());
        return 0;
    }
    std::printf("position   %g %g %g\n", position[0], position[1], position[2]);
    std::printf("cell       %d (%s), %u steps from a cold start\n", location.cell,
                location.cell_kind == TP_CELL_OUTER ? "outer" : "inner", location.steps);
    const char* channels[3] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c) {
        std::printf("sh.%s      ", channels[c]);
        for (int k = 0; k < 9; ++k) std::printf(" %10.6f", sh[9 * c + k]);
        std::printf("\n");
    }
    std::printf("irradiance %g %g %g (normal +y)\n", irradiance[0], irradiance[1], irradiance[2]);
    if (a.has("--weights"))
        for (int k = 0; k < 4; ++k)
            if (location.weights[k] != 0.0f || k == 0)
                std::printf("probe %-8u weight %.6f\n", location.probes[k], location.weights[k]);
    return 0;
}

}  // namespace cli
