// Scene files: JSON (nlohmann-json) with meshes inline or from OBJ files (tinyobjloader) relative
// to the JSON file, lights, a sky and probe positions. The format is documented in scene_file.cpp.
// A file starting with the magic "IBSP" is read as a Quake 3 level instead (bake/quake3_scene.h).
#pragma once

#include "bake/scene.h"

#include <string>

namespace tetprobe {

// Loads a scene file. A file that cannot be read throws Error(Status::io); malformed JSON, an
// unknown key, a value of the wrong type and every invalid value throw Error(Status::scene) with a
// message naming the file, the mesh or light and the index.
Scene load_scene_file(const std::string& path);

}  // namespace tetprobe
