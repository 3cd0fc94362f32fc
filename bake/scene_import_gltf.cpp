#include "bake/scene_import_gltf.h"

#include "core/error.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <sstream>

namespace tetprobe {

namespace {

using nlohmann::json;

[[noreturn]] void fail_at(const std::string& where, const std::string& what) {
    throw Error(Status::scene, where + ": " + what);
}

uint32_t little_endian32(const std::string& bytes, size_t at) {
    return uint32_t(uint8_t(bytes[at])) | uint32_t(uint8_t(bytes[at + 1])) << 8 | uint32_t(uint8_t(bytes[at + 2])) << 16 |
           uint32_t(uint8_t(bytes[at + 3])) << 24;
}

// The JSON chunk of a binary glTF, after checking every chunk header against the file.
std::string glb_json(const std::string& bytes, const std::string& label) {
    const std::string size = std::to_string(bytes.size());
    if (bytes.size() < 12) fail_at(label, "truncated binary glTF: " + size + " bytes, less than its 12-byte header");
    if (bytes.compare(0, 4, "glTF") != 0) fail_at(label, "not a binary glTF (no \"glTF\" magic at its start)");
    const uint32_t version = little_endian32(bytes, 4), length = little_endian32(bytes, 8);
    if (version != 2) fail_at(label, "binary glTF version " + std::to_string(version) + " (only 2 is read)");
    if (length > bytes.size())
        fail_at(label, "truncated binary glTF: its header declares " + std::to_string(length) + " bytes, the file has " + size);
    std::string json_chunk;
    for (size_t at = 12, chunk = 0; at < length; ++chunk) {
        if (length - at < 8) fail_at(label, "truncated binary glTF: chunk " + std::to_string(chunk) + " has no complete header");
        const uint32_t chunk_length = little_endian32(bytes, at), type = little_endian32(bytes, at + 4);
        if (chunk_length > length - at - 8)
            fail_at(label, "truncated binary glTF: chunk " + std::to_string(chunk) + " declares " + std::to_string(chunk_length) +
                               " bytes, " + std::to_string(length - at - 8) + " remain");
        if (chunk == 0) {
            if (type != 0x4E4F534Au) fail_at(label, "binary glTF whose first chunk is not JSON");
            json_chunk = bytes.substr(at + 8, chunk_length);
        }
        at += 8 + size_t(chunk_length);
    }
    if (json_chunk.empty()) fail_at(label, "binary glTF without a JSON chunk");
    return json_chunk;
}

const json* member(const json& object, const char* key) {
    if (!object.is_object()) return nullptr;
    auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

}  // namespace

GltfFacts read_gltf_facts(const std::string& path, bool binary, const std::string& label) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(Status::io, "cannot read scene file '" + path + "'");
    std::stringstream contents;
    contents << in.rdbuf();
    std::string text = contents.str();
    if (binary) text = glb_json(text, label);

    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& e) {
        fail_at(label, "malformed glTF: its JSON is invalid at byte " + std::to_string(e.byte) + " (" + e.what() + ")");
    }
    if (!root.is_object()) fail_at(label, "malformed glTF: the JSON is not an object");
    const json* asset = member(root, "asset");
    const json* version = asset ? member(*asset, "version") : nullptr;
    if (!version || !version->is_string()) fail_at(label, "malformed glTF: no asset.version");
    if (version->get<std::string>().compare(0, 2, "2.") != 0)
        fail_at(label, "glTF " + version->get<std::string>() + " (only glTF 2.0 is read)");

    GltfFacts facts;
    if (const json* scenes = member(root, "scenes"); scenes && scenes->is_array()) facts.scenes = scenes->size();
    if (const json* materials = member(root, "materials"); materials && materials->is_array()) {
        for (size_t m = 0; m < materials->size(); ++m) {
            double strength = 1.0;
            const json* extensions = member((*materials)[m], "extensions");
            const json* emissive = extensions ? member(*extensions, "KHR_materials_emissive_strength") : nullptr;
            const json* value = emissive ? member(*emissive, "emissiveStrength") : nullptr;
            if (value) {
                if (!value->is_number() || !(value->get<double>() >= 0))
                    fail_at(label, "material " + std::to_string(m) + ": emissiveStrength must be a number >= 0, got " + value->dump());
                strength = value->get<double>();
            }
            facts.emissive_strength.push_back(strength);
        }
    }
    const json* extensions = member(root, "extensions");
    const json* punctual = extensions ? member(*extensions, "KHR_lights_punctual") : nullptr;
    const json* lights = punctual ? member(*punctual, "lights") : nullptr;
    if (lights && lights->is_array()) {
        for (size_t l = 0; l < lights->size(); ++l) {
            const json& light = (*lights)[l];
            std::string where = "light " + std::to_string(l);
            if (const json* name = member(light, "name"); name && name->is_string()) where += " ('" + name->get<std::string>() + "')";
            const json* type = member(light, "type");
            if (!type || !type->is_string()) fail_at(label, where + " has no \"type\"");
            const std::string t = type->get<std::string>();
            if (t != "directional" && t != "point" && t != "spot")
                fail_at(label, where + " has the unknown type \"" + t + "\" (KHR_lights_punctual: directional, point or spot)");
        }
        facts.lights = lights->size();
    }
    if (const json* nodes = member(root, "nodes"); nodes && nodes->is_array())
        for (const json& node : *nodes) {
            const json* node_extensions = member(node, "extensions");
            if (node_extensions && member(*node_extensions, "KHR_lights_punctual")) ++facts.light_placements;
        }
    return facts;
}

}  // namespace tetprobe
