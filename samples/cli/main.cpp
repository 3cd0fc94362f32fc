// `tetprobe`: build, inspect, query and bake probe stores from the command line, plan a bake, and the demo.
#include "cli.h"

#include <cstdio>
#include <cstring>
#include <exception>

namespace {

const char* const kUsage =
    "usage:\n"
    "  tetprobe build INPUT.(csv|json) -o STORE [--compact] [--sh-encoding E] [--quantize-positions]\n"
    "                                                csv: x,y,z[,27 sh] per line; json: {\"probes\": [[x,y,z],...],\n"
    "                                                \"sh\": [[27 floats],...]}; --compact: no neighbours stored;\n"
    "                                                E: half (default), unorm8, half_l1 or unorm8_l1;\n"
    "                                                --quantize-positions: 16 bits per axis\n"
    "  tetprobe info STORE [--json]\n"
    "  tetprobe query STORE x y z [--weights] [--json]\n"
    "  tetprobe bake SCENE.json -o STORE [--rays N] [--bounces N] [--seed N] [--threads N]\n"
    "  tetprobe plan SCENE.json [--rays N] [--bounces N] [--seed N] [--threads N] [--json]\n"
    "  tetprobe place SCENE.json -o PROBES.csv [--mode whole|walkable] [--spacing S] [--margin M]\n"
    "                 [--target N] [--error E] [--rays N] [--seed N] [--threads N] [--curve CURVE.json]\n"
    "                 [--min-height H] [--max-height H]   probe positions proposed for a scene\n"
    "  tetprobe demo [--out DIR] [--scene FILE] [--rays N]\n"
    "  tetprobe version\n";

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "help")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const std::string command = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    try {
        if (command == "build") return cli::command_build(args);
        if (command == "info") return cli::command_info(args);
        if (command == "query") return cli::command_query(args);
        if (command == "bake") return cli::command_bake(args);
        if (command == "plan") return cli::command_plan(args);
        if (command == "demo") return cli::command_demo(args);
        if (command == "place") return cli::command_place(args);
        if (command == "version") {
            const uint32_t v = tp_version();
            std::printf("tetprobe %u.%u.%u\n", v >> 16, (v >> 8) & 0xFFu, v & 0xFFu);
            return 0;
        }
        throw cli::UsageError("unknown command \"" + command + "\"");
    } catch (const cli::UsageError& e) {
        std::fprintf(stderr, "tetprobe: %s\n%s", e.what(), kUsage);
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tetprobe: error: %s\n", e.what());
        return 1;
    } catch (...) {
        std::fprintf(stderr, "tetprobe: error: unknown failure\n");
        return 1;
    }
}
