// What one scene file importer is asked to do, and the importers (bake/scene_file.cpp chooses one by
// the file's magic bytes, then its extension). Each adds what its file holds to a Scene, in the
// scene's frame, and notes on the scene what it left out or converted; each throws
// Error(Status::scene) with a message that starts with the request's label.
#pragma once

#include "bake/scene.h"
#include "bake/up_axis.h"

#include <map>
#include <string>

namespace tetprobe {

struct SceneImport {
    std::string path;
    std::string label;                // names the file in messages and notes ("level.glb", "a.json: mesh 2")
    std::string format;               // the format's name as importer_for gives it ("glTF", "FBX", ...)
    double scale = 0;                 // world units per file unit; 0 = the file's own unit in metres
    UpAxis file_up = UpAxis::file;    // which way is up in the file; file = what the file says
    // The frame to turn the file into (exactly: axes permuted); file = keep the file's frame and make
    // its up the scene's.
    UpAxis scene_up = UpAxis::file;
    const Material* material = nullptr;          // when set, replaces every material of the file
    std::map<std::string, LightMode> light_modes; // the file's lights by name; a name it lacks is an error
};

using SceneImporter = void (*)(Scene& scene, const SceneImport& import);

// The importer for the file at path (by magic bytes, then extension, case-insensitive), and its
// format's name in *format; throws Error(Status::io) when the file cannot be read and
// Error(Status::scene) naming the supported formats when none reads it.
SceneImporter importer_for(const std::string& path, std::string* format);

// The JSON scene (docs/scene-format.md). Only as the top-level file: scale 0 or 1, no turn.
void import_json_scene(Scene& scene, const SceneImport& import);
// glTF 2.0, FBX and OBJ through Assimp (bake/scene_import_assimp.cpp).
void import_assimp_file(Scene& scene, const SceneImport& import);

}  // namespace tetprobe
