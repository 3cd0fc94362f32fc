// The JSON scene (docs/scene-format.md documents every key, its default and an example): meshes inline
// or from glTF, FBX and OBJ files placed with their own scale and up, lights, a sky, probes. Every key
// is optional unless the document says it is required; unknown keys are errors.
#include "bake/scene_import.h"

#include "core/error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>

namespace tetprobe {

namespace {

using nlohmann::json;

[[noreturn]] void fail_at(const std::string& where, const std::string& what) {
    throw Error(Status::scene, where + ": " + what);
}

void only_keys(const json& object, const std::string& where, std::initializer_list<const char*> keys) {
    if (!object.is_object()) fail_at(where, "expected an object");
    for (auto it = object.begin(); it != object.end(); ++it) {
        bool known = false;
        for (const char* k : keys) known = known || it.key() == k;
        if (!known) fail_at(where, "unknown key \"" + it.key() + "\"");
    }
}

double number(const json& value, const std::string& where) {
    if (!value.is_number()) fail_at(where, "expected a number, got " + value.dump());
    return value.get<double>();
}

bool boolean(const json& value, const std::string& where) {
    if (!value.is_boolean()) fail_at(where, "expected true or false, got " + value.dump());
    return value.get<bool>();
}

std::string text(const json& value, const std::string& where) {
    if (!value.is_string()) fail_at(where, "expected a string, got " + value.dump());
    return value.get<std::string>();
}

void vector3(const json& value, const std::string& where, float out[3]) {
    if (!value.is_array() || value.size() != 3) fail_at(where, "expected [x, y, z], got " + value.dump());
    for (int a = 0; a < 3; ++a) out[a] = float(number(value[a], where + "[" + std::to_string(a) + "]"));
}

// Reads [[x,y,z], ...] or a flat [x, y, z, ...] array of `width`-tuples as doubles.
std::vector<double> tuples(const json& value, const std::string& where, size_t width) {
    if (!value.is_array()) fail_at(where, "expected an array");
    std::vector<double> out;
    if (!value.empty() && value[0].is_array()) {
        for (size_t i = 0; i < value.size(); ++i) {
            const std::string at = where + "[" + std::to_string(i) + "]";
            if (!value[i].is_array() || value[i].size() != width)
                fail_at(at, "expected " + std::to_string(width) + " numbers, got " + value[i].dump());
            for (size_t k = 0; k < width; ++k) out.push_back(number(value[i][k], at));
        }
    } else {
        if (value.size() % width != 0)
            fail_at(where, "has " + std::to_string(value.size()) + " numbers, not a multiple of " + std::to_string(width));
        for (size_t i = 0; i < value.size(); ++i) out.push_back(number(value[i], where + "[" + std::to_string(i) + "]"));
    }
    return out;
}

std::vector<uint32_t> indices_from(const std::vector<double>& values, const std::string& where) {
    std::vector<uint32_t> out(values.size());
    for (size_t i = 0; i < values.size(); ++i) {
        double v = values[i];
        if (!(v >= 0) || v > double(UINT32_MAX) || v != std::floor(v))
            fail_at(where, "index " + std::to_string(i) + " is not a non-negative integer (" + std::to_string(v) + ")");
        out[i] = uint32_t(v);
    }
    return out;
}

Material material_from(const json& value, const std::string& where) {
    only_keys(value, where, {"albedo", "emission", "two_sided"});
    Material m;
    if (value.contains("albedo")) vector3(value["albedo"], where + ": albedo", m.albedo.data());
    if (value.contains("emission")) vector3(value["emission"], where + ": emission", m.emission.data());
    if (value.contains("two_sided")) m.two_sided = boolean(value["two_sided"], where + ": two_sided");
    validate_material(m, where);
    return m;
}

std::string directory_of(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

LightMode light_mode(const json& value, const std::string& where) {
    const std::string mode = text(value, where);
    if (mode == "baked") return LightMode::baked;
    if (mode == "realtime") return LightMode::realtime;
    if (mode == "mixed") return LightMode::mixed;
    fail_at(where, "unknown mode \"" + mode + "\" (baked, realtime or mixed)");
}

// A mesh entry's "file": a glTF, FBX or OBJ file (its meshes and lights), turned from its own up to the
// scene's and scaled to world units.
void import_file_entry(Scene& scene, const json& value, const std::string& where, const std::string& file,
                       UpAxis scene_up) {
    for (const char* inline_key : {"vertices", "indices", "materials", "triangle_materials"})
        if (value.contains(inline_key)) fail_at(where, std::string("has both \"file\" and \"") + inline_key + "\"");
    const std::string name = text(value["file"], where + ": file");
    SceneImport request;
    // An absolute path is used as it is; a relative one starts at the JSON file's folder.
    request.path = std::filesystem::path(name).is_absolute() ? name : directory_of(file) + name;
    request.label = where + ": " + name;
    request.scene_up = scene_up;
    if (value.contains("scale")) {
        request.scale = number(value["scale"], where + ": scale");
        if (!(std::isfinite(request.scale) && request.scale > 0))
            fail_at(where, "scale must be positive (world units per unit of the file)");
    }
    if (value.contains("up")) request.file_up = parse_up_axis(text(value["up"], where + ": up"), where);
    Material material;
    if (value.contains("material")) {
        material = material_from(value["material"], where + ": material");
        request.material = &material;
    }
    if (value.contains("light_modes")) {
        const json& modes = value["light_modes"];
        if (!modes.is_object()) fail_at(where + ": light_modes", "expected an object of light name: mode");
        for (auto it = modes.begin(); it != modes.end(); ++it)
            request.light_modes[it.key()] = light_mode(it.value(), where + ": light_modes: " + it.key());
    }
    std::string format;
    SceneImporter import;
    try {
        import = importer_for(request.path, &format);
    } catch (const Error& e) {
        // A file the scene refers to that is missing is an error in the scene.
        throw Error(Status::scene, where + ": " + e.what());
    }
    if (import == import_json_scene) fail_at(where, "file '" + name + "' is a JSON scene: only glTF, FBX and OBJ files can be placed");
    request.format = format;
    import(scene, request);
}

void add_mesh(Scene& scene, const json& value, size_t index, const std::string& file, UpAxis scene_up) {
    std::string where = file + ": mesh " + std::to_string(index);
    only_keys(value, where, {"name", "file", "scale", "up", "light_modes", "vertices", "indices", "material",
                             "materials", "triangle_materials"});
    if (value.contains("name")) where += " ('" + text(value["name"], where + ": name") + "')";
    if (value.contains("file")) return import_file_entry(scene, value, where, file, scene_up);
    for (const char* file_key : {"scale", "up", "light_modes"})
        if (value.contains(file_key)) fail_at(where, std::string("\"") + file_key + "\" applies only to a \"file\"");
    if (!value.contains("vertices") || !value.contains("indices"))
        fail_at(where, "needs \"file\" or both \"vertices\" and \"indices\"");
    std::vector<float> vertices;
    for (double v : tuples(value["vertices"], where + ": vertices", 3)) vertices.push_back(float(v));
    const std::vector<uint32_t> indices = indices_from(tuples(value["indices"], where + ": indices", 3), where + ": indices");

    std::vector<Material> materials;
    std::vector<uint32_t> triangle_materials;
    if (value.contains("material") && value.contains("materials"))
        fail_at(where, "has both \"material\" and \"materials\"");
    if (value.contains("materials")) {
        const json& list = value["materials"];
        if (!list.is_array() || list.empty()) fail_at(where + ": materials", "expected a non-empty array");
        for (size_t m = 0; m < list.size(); ++m)
            materials.push_back(material_from(list[m], where + ": material " + std::to_string(m)));
    } else {
        materials.push_back(value.contains("material") ? material_from(value["material"], where + ": material")
                                                       : Material());
    }
    if (value.contains("triangle_materials")) {
        triangle_materials = indices_from(tuples(value["triangle_materials"], where + ": triangle_materials", 1),
                                          where + ": triangle_materials");
        if (triangle_materials.size() != indices.size() / 3)
            fail_at(where, "has " + std::to_string(triangle_materials.size()) + " triangle_materials for " +
                               std::to_string(indices.size() / 3) + " triangles");
    }
    scene.add_mesh(vertices.data(), vertices.size() / 3, indices.data(), indices.size() / 3, materials,
                   triangle_materials.empty() ? nullptr : triangle_materials.data(), where);
}

void add_light(Scene& scene, const json& value, size_t index, const std::string& file) {
    std::string where = file + ": light " + std::to_string(index);
    only_keys(value, where, {"type", "mode", "shadows", "color", "intensity", "position", "direction", "range",
                             "inner_angle", "outer_angle", "near_distance", "name"});
    if (value.contains("name")) where += " ('" + text(value["name"], where + ": name") + "')";
    LightDescription light;
    if (!value.contains("type")) fail_at(where, "needs a \"type\"");
    const std::string type = text(value["type"], where + ": type");
    if (type == "directional") light.type = LightType::directional;
    else if (type == "point") light.type = LightType::point;
    else if (type == "spot") light.type = LightType::spot;
    else fail_at(where, "unknown type \"" + type + "\" (directional, point or spot)");
    if (value.contains("mode")) light.mode = light_mode(value["mode"], where + ": mode");
    if (value.contains("shadows")) light.shadows = boolean(value["shadows"], where + ": shadows");
    if (value.contains("color")) vector3(value["color"], where + ": color", light.color.data());
    if (!value.contains("intensity")) fail_at(where, "needs an \"intensity\" (irradiance for a directional light, radiant intensity for a point or spot light)");
    light.intensity = float(number(value["intensity"], where + ": intensity"));
    if (value.contains("position")) vector3(value["position"], where + ": position", light.position.data());
    else if (light.type != LightType::directional) fail_at(where, "needs a \"position\"");
    if (value.contains("direction")) vector3(value["direction"], where + ": direction", light.direction.data());
    else if (light.type != LightType::point) fail_at(where, "needs a \"direction\"");
    if (value.contains("range")) {
        const json& range = value["range"];
        if (range.is_string() && range.get<std::string>() == "inf") light.range = INFINITY;
        else light.range = float(number(range, where + ": range"));
    }
    if (value.contains("inner_angle")) light.inner_angle = float(number(value["inner_angle"], where + ": inner_angle"));
    if (value.contains("outer_angle")) light.outer_angle = float(number(value["outer_angle"], where + ": outer_angle"));
    if (value.contains("near_distance"))
        light.near_distance = float(number(value["near_distance"], where + ": near_distance"));
    scene.add_light(light, where);
}

void set_sky(Scene& scene, const json& value, const std::string& file) {
    const std::string where = file + ": sky";
    if (value.is_null()) return;
    only_keys(value, where, {"color", "sh"});
    if (value.contains("color") == value.contains("sh")) fail_at(where, "needs exactly one of \"color\" and \"sh\"");
    if (value.contains("color")) {
        float rgb[3];
        vector3(value["color"], where + ": color", rgb);
        scene.set_sky_color(rgb);
    } else {
        std::vector<double> sh = tuples(value["sh"], where + ": sh", 1);
        if (sh.size() != 27) fail_at(where, "sh has " + std::to_string(sh.size()) + " numbers, expected 27");
        float coefficients[27];
        for (int i = 0; i < 27; ++i) coefficients[i] = float(sh[i]);
        scene.set_sky_sh(coefficients);
    }
}

void append_grid(std::vector<float>& probes, const json& value, const std::string& where) {
    only_keys(value, where, {"min", "max", "counts"});
    if (!value.contains("min") || !value.contains("max") || !value.contains("counts"))
        fail_at(where, "needs \"min\", \"max\" and \"counts\"");
    float lo[3], hi[3];
    vector3(value["min"], where + ": min", lo);
    vector3(value["max"], where + ": max", hi);
    std::vector<uint32_t> counts = indices_from(tuples(value["counts"], where + ": counts", 1), where + ": counts");
    if (counts.size() != 3 || counts[0] == 0 || counts[1] == 0 || counts[2] == 0)
        fail_at(where, "counts must be three positive integers");
    if (double(counts[0]) * counts[1] * counts[2] > 1e7) fail_at(where, "more than 10 million probes");
    for (uint32_t k = 0; k < counts[2]; ++k)
        for (uint32_t j = 0; j < counts[1]; ++j)
            for (uint32_t i = 0; i < counts[0]; ++i) {
                const uint32_t step[3] = {i, j, k};
                for (int a = 0; a < 3; ++a)
                    probes.push_back(counts[a] == 1 ? lo[a]
                                                    : lo[a] + (hi[a] - lo[a]) * float(step[a]) / float(counts[a] - 1));
            }
}

}  // namespace

void import_json_scene(Scene& scene, const SceneImport& import) {
    const std::string& path = import.path;
    if (import.scale != 0 && import.scale != 1)
        throw Error(Status::invalid_argument, path + ": a JSON scene is in world units (scale 0 or 1); give a \"scale\" to the files it places");
    if (import.scene_up != UpAxis::file) fail_at(import.label, "a JSON scene cannot be placed inside another");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(Status::io, "cannot read scene file '" + path + "'");
    std::stringstream contents;
    contents << in.rdbuf();
    json root;
    try {
        root = json::parse(contents.str());
    } catch (const json::parse_error& e) {
        throw Error(Status::scene, path + ": malformed JSON at byte " + std::to_string(e.byte) + ": " + e.what());
    }
    only_keys(root, path, {"meshes", "lights", "sky", "probes", "probe_grids", "up", "name", "description"});

    try {
        // The scene's up first: the files it places are turned into its frame.
        UpAxis up = UpAxis::pos_y;
        if (root.contains("up")) up = parse_up_axis(text(root["up"], path + ": up"), path);
        if (import.file_up != UpAxis::file) up = import.file_up;
        scene.set_up(up);
        if (root.contains("meshes")) {
            const json& meshes = root["meshes"];
            if (!meshes.is_array()) fail_at(path + ": meshes", "expected an array");
            for (size_t i = 0; i < meshes.size(); ++i) add_mesh(scene, meshes[i], i, path, up);
        }
        if (root.contains("lights")) {
            const json& lights = root["lights"];
            if (!lights.is_array()) fail_at(path + ": lights", "expected an array");
            for (size_t i = 0; i < lights.size(); ++i) add_light(scene, lights[i], i, path);
        }
        if (root.contains("sky")) set_sky(scene, root["sky"], path);
        std::vector<float> probes;
        if (root.contains("probes"))
            for (double v : tuples(root["probes"], path + ": probes", 3)) probes.push_back(float(v));
        if (root.contains("probe_grids")) {
            const json& grids = root["probe_grids"];
            if (!grids.is_array()) fail_at(path + ": probe_grids", "expected an array");
            for (size_t g = 0; g < grids.size(); ++g)
                append_grid(probes, grids[g], path + ": probe_grids[" + std::to_string(g) + "]");
        }
        scene.set_probes(probes.data(), probes.size() / 3);
    } catch (const json::exception& e) {
        throw Error(Status::scene, path + ": " + e.what());
    }
}

}  // namespace tetprobe
