// Scene files: glTF 2.0 (.gltf, .glb), FBX and OBJ (with its .mtl) read through Assimp, and the JSON
// scene (docs/scene-format.md) for what those cannot say: a sky, light modes, probes, and files of the
// other formats placed with their own units and up; also Quake 3 levels (bake/quake3_scene.h). The
// format is chosen by the file's magic bytes, then by its extension (bake/scene_import.h lists the
// importers).
#pragma once

#include "bake/scene.h"
#include "bake/up_axis.h"

#include <string>

namespace tetprobe {

struct SceneLoadOptions {
    // World units per file unit; 0 = the file's own unit in metres (glTF and OBJ 1, FBX its
    // UnitScaleFactor / 100). A JSON scene is in world units: 0 or 1 only.
    double scale = 0;
    // Which way is up in the file; file = what the file says (glTF and OBJ +y, FBX its UpAxis, a JSON
    // scene its "up", +y by default). Coordinates are not turned: the scene records its up.
    UpAxis up = UpAxis::file;
};

// Loads a scene file. A file that cannot be read throws Error(Status::io); everything wrong inside it
// (malformed, truncated, an unknown light type, a file it references that cannot be read, no mesh)
// throws Error(Status::scene) with a message naming the file and what is wrong; bad options throw
// Error(Status::invalid_argument). What the file holds that a bake cannot use (cameras, textures,
// animations, area lights) is noted on the scene (Scene::notes), never dropped silently.
Scene load_scene_file(const std::string& path, const SceneLoadOptions& options = {});

}  // namespace tetprobe
