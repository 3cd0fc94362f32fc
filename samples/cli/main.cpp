// `tetprobe`: build, inspect, query and bake probe stores from the command line, plan a bake, and the demo.
#include "cli.h"

#include <cstdio>
#include <cstring>
#include <exception>

namespace {

const char* const kUsage =
    "usage:\n"
    "  tetprobe build PROBES.(csv|json) -o STORE [--compact] [--scene SCENE [--scale S] [--up AXIS]]\n"
    "                                                probe files: docs/probe-file.md; --compact: the smallest blob;\n"
    "                                                --scene: leak control (probe pairs a wall separates)\n"
    "  tetprobe info STORE [--json]\n"
    "  tetprobe query STORE x y z [--weights] [--json]\n"
    "  tetprobe bake SCENE -o STORE|BAKED.csv [--probes PROBES.csv] [--rays N] [--bounces N] [--seed N] [--threads N]\n"
    "  tetprobe plan SCENE [--probes PROBES.csv] [--rays N] [--bounces N] [--seed N] [--threads N] [--json]\n"
    "  tetprobe place SCENE -o PROBES.csv [--mode whole|walkable] [--spacing S] [--margin M]\n"
    "                 [--target N] [--error E] [--rays N] [--seed N] [--threads N] [--curve CURVE.json]\n"
    "                 [--min-height H] [--max-height H]   probe positions proposed for a scene\n"
    "  tetprobe demo [--out DIR] [--scene FILE] [--rays N]\n"
    "  tetprobe version\n"
    "SCENE: a glTF 2.0 (.gltf, .glb), FBX, OBJ or JSON scene (docs/scene-format.md); every command that reads one\n"
    "takes --scale S (world units per file unit; default the file's unit in metres) and --up +x|-x|+y|-y|+z|-z\n"
    "(the file's up; default what the file says). Without --probes, bake and plan use the scene's own probes.\n";

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
