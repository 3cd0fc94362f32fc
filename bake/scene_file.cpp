#include "bake/scene_file.h"

#include "bake/quake3_bsp.h"
#include "bake/quake3_scene.h"
#include "bake/scene_import.h"
#include "core/error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>

namespace tetprobe {

namespace {

// The start of a file and its extension (lower case, with the dot), which is what formats are told by.
struct FileStart {
    std::string bytes;      // up to the first 64 bytes
    std::string extension;  // ".glb"

    bool starts_with(const char* magic) const { return bytes.compare(0, std::char_traits<char>::length(magic), magic) == 0; }
    bool first_text_is(char c) const {
        for (char b : bytes)
            if (!std::isspace(static_cast<unsigned char>(b))) return b == c;
        return false;
    }
};

struct SceneFormat {
    const char* name;
    bool (*recognises)(const FileStart& file);
    SceneImporter import;
};

// A Quake 3 level is read in y-up metres (bake/quake3_bsp.h): it is placed as it is.
void import_quake3_level(Scene& scene, const SceneImport& import) {
    const bool y_up = (import.file_up == UpAxis::file || import.file_up == UpAxis::pos_y) &&
                      (import.scene_up == UpAxis::file || import.scene_up == UpAxis::pos_y);
    if (!(import.scale == 0 || import.scale == 1) || !y_up)
        throw Error(Status::invalid_argument, import.label + ": a Quake 3 level is read in y-up metres; it takes no other scale or up");
    add_quake3_level(scene, read_quake3_bsp(import.path));
    if (import.scene_up == UpAxis::file) scene.set_up(UpAxis::pos_y);
}

// Magic bytes first (they cannot lie), then extensions. A new format is one more row.
const SceneFormat kFormats[] = {
    {"Quake 3 level",
     [](const FileStart& f) { return looks_like_quake3_bsp(reinterpret_cast<const uint8_t*>(f.bytes.data()), f.bytes.size()); },
     import_quake3_level},
    {"binary glTF", [](const FileStart& f) { return f.starts_with("glTF"); }, import_assimp_file},
    {"FBX", [](const FileStart& f) { return f.starts_with("Kaydara FBX Binary"); }, import_assimp_file},
    {"binary glTF", [](const FileStart& f) { return f.extension == ".glb"; }, import_assimp_file},
    {"glTF", [](const FileStart& f) { return f.extension == ".gltf"; }, import_assimp_file},
    {"FBX", [](const FileStart& f) { return f.extension == ".fbx"; }, import_assimp_file},
    {"OBJ", [](const FileStart& f) { return f.extension == ".obj"; }, import_assimp_file},
    {"JSON scene", [](const FileStart& f) { return f.extension == ".json" || (f.extension.empty() && f.first_text_is('{')); },
     import_json_scene},
};

std::string lower_extension(const std::string& path) {
    const size_t slash = path.find_last_of("/\\"), dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string extension = path.substr(dot);
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

}  // namespace

SceneImporter importer_for(const std::string& path, std::string* format) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(Status::io, "cannot read scene file '" + path + "'");
    FileStart start;
    char bytes[64];
    in.read(bytes, sizeof bytes);
    start.bytes.assign(bytes, size_t(in.gcount()));
    start.extension = lower_extension(path);
    for (const SceneFormat& f : kFormats)
        if (f.recognises(start)) {
            if (format) *format = f.name;
            return f.import;
        }
    throw Error(Status::scene, path + ": not a scene file this library reads (by its content or its extension '" +
                                   start.extension + "'): glTF 2.0 (.gltf, .glb), FBX (.fbx), OBJ (.obj), a Quake 3 level (.bsp) or a JSON scene (.json)");
}

Scene load_scene_file(const std::string& path, const SceneLoadOptions& options) {
    if (!(std::isfinite(options.scale) && options.scale >= 0))
        throw Error(Status::invalid_argument, "the scale must be 0 (the file's own unit) or positive, got " + std::to_string(options.scale));
    if (options.up != UpAxis::file && !is_axis(options.up))
        throw Error(Status::invalid_argument, "unknown up axis " + std::to_string(uint32_t(options.up)) + " (TP_UP_*)");
    std::string format;
    const SceneImporter import = importer_for(path, &format);
    SceneImport request;
    request.path = path;
    request.label = path;
    request.format = format;
    request.scale = options.scale;
    request.file_up = options.up;
    Scene scene;
    import(scene, request);
    if (scene.empty()) throw Error(Status::scene, path + ": the scene is empty (no mesh, light or sky)");
    return scene;
}

}  // namespace tetprobe
