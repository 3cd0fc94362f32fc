// What Assimp 5.2 does not read from a glTF 2.0 file, read from the file's JSON: the type of every
// KHR_lights_punctual light (Assimp takes an unknown type for a spot), each material's
// KHR_materials_emissive_strength, and what Assimp leaves out without a word (scenes other than the
// default one, a light placed by several nodes).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace tetprobe {

struct GltfFacts {
    std::vector<double> emissive_strength;  // per material of the file (1 where the extension is absent)
    size_t lights = 0;                      // KHR_lights_punctual lights, all of known types
    size_t light_placements = 0;            // nodes that place a light
    size_t scenes = 0;
};

// Reads a .gltf file's JSON, or (binary) a .glb file's JSON chunk after checking the container (magic,
// version 2, every chunk inside the declared length, the declared length present in the file). Throws
// Error(Status::scene) starting with `label` for a truncated or malformed file, a glTF other than 2.x
// and a light of an unknown type.
GltfFacts read_gltf_facts(const std::string& path, bool binary, const std::string& label);

}  // namespace tetprobe
