// Scenes the commands read: any file tp_scene_load_file_ex reads (glTF, FBX, OBJ, a JSON scene), with
// --scale and --up, and what the import left out printed as notes.
#include "cli.h"

#include <cstdio>
#include <cstring>

namespace cli {

namespace {

uint32_t parse_up(const std::string& text) {
    const char* const names[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    for (uint32_t i = 0; i < 6; ++i)
        if (text == names[i]) return TP_UP_POS_X + i;
    throw UsageError("--up is one of +x, -x, +y, -y, +z, -z (got \"" + text + "\")");
}

}  // namespace

ScenePtr load_scene(const std::string& path, const Arguments& a) {
    tp_scene_load_options options;
    check(tp_scene_load_options_init(&options), "tp_scene_load_options_init");
    if (a.has("--scale")) {
        options.scale = float(parse_number(a.value("--scale", ""), "--scale"));
        if (!(options.scale > 0)) throw UsageError("--scale must be positive (world units per unit of the file)");
    }
    if (a.has("--up")) options.up = parse_up(a.value("--up", ""));
    tp_scene* scene = nullptr;
    check(tp_scene_load_file_ex(path.c_str(), &options, &scene), "loading the scene");
    ScenePtr owned(scene);
    size_t size = 0;
    check(tp_scene_notes(scene, nullptr, 0, &size), "tp_scene_notes");
    std::vector<char> notes(size);
    check(tp_scene_notes(scene, notes.data(), notes.size(), nullptr), "tp_scene_notes");
    for (const char* line = notes.data(); *line;) {
        const char* end = std::strchr(line, '\n');
        const size_t length = end ? size_t(end - line) : std::strlen(line);
        std::fprintf(stderr, "tetprobe: note: %.*s\n", int(length), line);
        line += length + (end ? 1 : 0);
    }
    return owned;
}

std::set<std::string> with_scene_options(std::set<std::string> value_options) {
    value_options.insert(kSceneOptions.begin(), kSceneOptions.end());
    return value_options;
}

void write_probe_file(const std::string& path, const std::vector<float>& positions, const std::vector<float>& sh) {
    std::string text;
    char number[32];
    for (size_t i = 0; i < positions.size() / 3; ++i) {
        for (int k = 0; k < 3; ++k) {
            std::snprintf(number, sizeof number, k ? ",%.9g" : "%.9g", positions[3 * i + k]);
            text += number;
        }
        if (!sh.empty())
            for (int k = 0; k < TP_SH_FLOATS; ++k) {
                std::snprintf(number, sizeof number, ",%.9g", sh[TP_SH_FLOATS * i + k]);
                text += number;
            }
        text += "\n";
    }
    write_file_atomically(path, text.data(), text.size());
}

}  // namespace cli
