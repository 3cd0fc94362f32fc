// Scene files: the JSON scene (required keys, defaults, files placed with their own scale and up), and
// glTF, FBX and OBJ through Assimp. A glTF, a .glb and an OBJ + MTL written here bake the same SH, bit
// for bit, as the JSON scene of the same triangles, materials and lights after conversion; bad files
// give Status::scene naming the file and what is wrong, and Assimp prints nothing.
#include <catch2/catch.hpp>

#include "bake/lighting_bake.h"
#include "bake/placement_candidates.h"
#include "bake/scene.h"
#include "bake/scene_file.h"
#include "bake/up_axis.h"
#include "core/error.h"
#include "placement_scenes.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <unistd.h>

using namespace tetprobe;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kPi = 3.14159265358979323846;

template <class F>
Error error_of(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    FAIL("no error was thrown");
    return Error(Status::ok, "");
}

bool mentions(const Error& e, const std::string& text) {
    const bool found = std::string(e.what()).find(text) != std::string::npos;
    if (!found) WARN("message: " << e.what() << " (expected to mention '" << text << "')");
    return found;
}

bool noted(const Scene& scene, const std::string& text) {
    for (const std::string& note : scene.notes())
        if (note.find(text) != std::string::npos) return true;
    std::string all;
    for (const std::string& note : scene.notes()) all += "\n  " + note;
    WARN("no note mentions '" << text << "'; the notes:" << all);
    return false;
}

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("tetprobe_import_test_" + std::to_string(getpid()) + "_" +
                                            std::to_string(reinterpret_cast<uintptr_t>(this)));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(path / name, std::ios::binary) << bytes;
        return (path / name).string();
    }
};

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
        out += digits[(n >> 18) & 63];
        out += digits[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? digits[n & 63] : '=';
    }
    return out;
}

template <class T>
std::string raw_bytes(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// ---- The test scene, three ways: a floor, a double-sided wall and an emissive panel; a point light, a
// spot light and a directional light. Intensities are powers of two and colours dyadic, so that
// glTF's colour x intensity (which Assimp folds together) is exactly the JSON's colour and intensity.

struct TestMesh {
    std::string name;
    std::vector<float> vertices;
    std::vector<uint32_t> indices;
    std::array<float, 3> albedo, emission;
    bool two_sided;
};

std::vector<TestMesh> test_meshes() {
    return {
        {"floor", {0, 0, 0, 0, 0, 4, 4, 0, 4, 4, 0, 0}, {0, 1, 2, 0, 2, 3}, {0.5f, 0.5f, 0.25f}, {0, 0, 0}, false},
        {"wall", {1, 0, 2, 3, 0, 2, 3, 2, 2, 1, 2, 2}, {0, 1, 2, 0, 2, 3}, {0.75f, 0.5f, 0.5f}, {0, 0, 0}, true},
        {"panel", {1.5f, 3, 1.5f, 2.5f, 3, 1.5f, 2.5f, 3, 2.5f, 1.5f, 3, 2.5f}, {0, 1, 2, 0, 2, 3}, {0, 0, 0}, {2, 1, 4}, false},
    };
}

const std::vector<float> kProbes = {2, 1, 1, 2, 1, 3, 1, 0.5f, 3, 3, 1.5f, 1, 0.5f, 2.5f, 0.5f};

// glTF's spot cone half-angles (radians) as our full angles (degrees), the way the importer converts them.
float full_angle(double half_radians) { return float(2.0 * half_radians * 180.0 / kPi); }

std::string number9(double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

json json_scene(bool with_lights, bool two_sided_wall = true) {
    json meshes = json::array();
    for (const TestMesh& m : test_meshes()) {
        json mesh = {{"name", m.name}, {"vertices", m.vertices}, {"indices", m.indices}};
        mesh["material"] = {{"albedo", m.albedo}, {"emission", m.emission}, {"two_sided", m.two_sided && two_sided_wall}};
        meshes.push_back(mesh);
    }
    json scene = {{"meshes", meshes}};
    if (with_lights)
        scene["lights"] = json::parse(R"([
            {"type": "point", "position": [1, 2.5, 1], "color": [1, 0.5, 0.25], "intensity": 8, "range": 16},
            {"type": "spot", "position": [3, 2.5, 3], "direction": [0, -1, 0], "color": [0.5, 1, 1], "intensity": 16,
             "inner_angle": )" + number9(full_angle(0.25)) + R"(, "outer_angle": )" + number9(full_angle(0.5)) + R"(},
            {"type": "directional", "direction": [0, -1, 0], "color": [1, 1, 0.5], "intensity": 2}])");
    return scene;
}

// The glTF document of the test scene; its one buffer is returned in *buffer (the caller embeds it as a
// data URI or a .glb chunk).
json gltf_scene(std::string* buffer) {
    json accessors = json::array(), views = json::array(), meshes = json::array(), materials = json::array(),
         nodes = json::array();
    buffer->clear();
    for (const TestMesh& m : test_meshes()) {
        for (int part = 0; part < 2; ++part) {
            const std::string bytes = part == 0 ? raw_bytes(m.vertices) : raw_bytes(m.indices);
            views.push_back({{"buffer", 0}, {"byteOffset", buffer->size()}, {"byteLength", bytes.size()}});
            json accessor = {{"bufferView", views.size() - 1}, {"componentType", part == 0 ? 5126 : 5125},
                             {"count", part == 0 ? m.vertices.size() / 3 : m.indices.size()},
                             {"type", part == 0 ? "VEC3" : "SCALAR"}};
            if (part == 0) {
                std::array<float, 3> lo{{INFINITY, INFINITY, INFINITY}}, hi{{-INFINITY, -INFINITY, -INFINITY}};
                for (size_t v = 0; v < m.vertices.size(); ++v)
                    lo[v % 3] = std::min(lo[v % 3], m.vertices[v]), hi[v % 3] = std::max(hi[v % 3], m.vertices[v]);
                accessor["min"] = lo;
                accessor["max"] = hi;
            }
            accessors.push_back(accessor);
            *buffer += bytes;
        }
        json material = {{"name", m.name + " material"},
                         {"pbrMetallicRoughness", {{"baseColorFactor", {m.albedo[0], m.albedo[1], m.albedo[2], 1.0}}, {"metallicFactor", 0}}},
                         {"doubleSided", m.two_sided}};
        if (m.emission[0] > 0) {
            // emissiveFactor x emissiveStrength = (0.5, 0.25, 1) x 4 = the JSON's emission (2, 1, 4).
            material["emissiveFactor"] = {m.emission[0] / 4, m.emission[1] / 4, m.emission[2] / 4};
            material["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}}};
        }
        materials.push_back(material);
        meshes.push_back({{"name", m.name}, {"primitives", {{{"attributes", {{"POSITION", accessors.size() - 2}}},
                                                            {"indices", accessors.size() - 1},
                                                            {"material", materials.size() - 1}}}}});
        nodes.push_back({{"name", m.name}, {"mesh", meshes.size() - 1}});
    }
    // The matrix (column-major) turns the lights' -z onto -y exactly: a quarter turn about x.
    const json down = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 3, 2.5, 3, 1};
    const json sun_down = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1};
    nodes.push_back({{"name", "lamp"}, {"translation", {1, 2.5, 1}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    nodes.push_back({{"name", "spot"}, {"matrix", down}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    nodes.push_back({{"name", "sun"}, {"matrix", sun_down}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    json lights = json::parse(R"([
        {"type": "point", "color": [0.125, 0.0625, 0.03125], "intensity": 64, "range": 16},
        {"type": "spot", "color": [0.5, 1, 1], "intensity": 16, "spot": {"innerConeAngle": 0.25, "outerConeAngle": 0.5}},
        {"type": "directional", "color": [1, 1, 0.5], "intensity": 2}])");
    json scene_nodes = json::array();
    for (size_t n = 0; n < nodes.size(); ++n) scene_nodes.push_back(n);
    return {{"asset", {{"version", "2.0"}}},
            {"extensionsUsed", {"KHR_lights_punctual", "KHR_materials_emissive_strength"}},
            {"extensions", {{"KHR_lights_punctual", {{"lights", lights}}}}},
            {"scene", 0},
            {"scenes", {{{"nodes", scene_nodes}}}},
            {"nodes", nodes},
            {"meshes", meshes},
            {"materials", materials},
            {"accessors", accessors},
            {"bufferViews", views},
            {"buffers", {{{"byteLength", buffer->size()}}}}};
}

std::string gltf_text(json document, const std::string& buffer) {
    document["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(buffer);
    document["buffers"][0]["byteLength"] = buffer.size();
    return document.dump();
}

std::string glb_bytes(const json& document, std::string buffer) {
    std::string text = document.dump();
    while (text.size() % 4) text += ' ';
    while (buffer.size() % 4) buffer += '\0';
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const uint32_t length = uint32_t(12 + 8 + text.size() + 8 + buffer.size());
    return "glTF" + u32(2) + u32(length) + u32(uint32_t(text.size())) + "JSON" + text + u32(uint32_t(buffer.size())) +
           std::string("BIN\0", 4) + buffer;
}

std::string obj_and_mtl(std::string* mtl) {
    std::ostringstream obj, materials;
    obj << "mtllib scene.mtl\n";
    size_t base = 1;
    for (const TestMesh& m : test_meshes()) {
        obj << "o " << m.name << "\nusemtl " << m.name << "_material\n";
        for (size_t v = 0; v < m.vertices.size(); v += 3)
            obj << "v " << number9(m.vertices[v]) << ' ' << number9(m.vertices[v + 1]) << ' ' << number9(m.vertices[v + 2]) << '\n';
        for (size_t t = 0; t < m.indices.size(); t += 3)
            obj << "f " << base + m.indices[t] << ' ' << base + m.indices[t + 1] << ' ' << base + m.indices[t + 2] << '\n';
        base += m.vertices.size() / 3;
        materials << "newmtl " << m.name << "_material\nKd " << m.albedo[0] << ' ' << m.albedo[1] << ' ' << m.albedo[2]
                  << "\nKe " << m.emission[0] << ' ' << m.emission[1] << ' ' << m.emission[2] << "\n\n";
    }
    *mtl = materials.str();
    return obj.str();
}

BakeSettings bake_settings() {
    BakeSettings s;
    s.rays = 64;
    s.bounces = 2;
    s.seed = 7;
    s.threads = 2;
    return s;
}

void check_same_meshes(const Scene& a, const Scene& b) {
    REQUIRE(a.meshes().size() == b.meshes().size());
    for (size_t m = 0; m < a.meshes().size(); ++m) {
        INFO("mesh " << m);
        const Mesh &x = a.meshes()[m], &y = b.meshes()[m];
        // The same triangles: corner positions in order (Assimp's OBJ reader gives each face its own vertices).
        REQUIRE(x.triangle_count() == y.triangle_count());
        for (size_t i = 0; i < x.indices.size(); ++i)
            for (int k = 0; k < 3; ++k) CHECK(x.vertices[3 * x.indices[i] + k] == y.vertices[3 * y.indices[i] + k]);
        for (size_t t = 0; t < x.triangle_count(); ++t) {
            const Material &p = x.materials[x.triangle_materials[t]], &q = y.materials[y.triangle_materials[t]];
            CHECK(p.albedo == q.albedo);
            CHECK(p.emission == q.emission);
            CHECK(p.two_sided == q.two_sided);
        }
    }
}

void check_same_lights(const Scene& a, const Scene& b) {
    REQUIRE(a.lights().size() == b.lights().size());
    for (size_t l = 0; l < a.lights().size(); ++l) {
        INFO("light " << l);
        const Light &x = a.lights()[l], &y = b.lights()[l];
        CHECK(x.type == y.type);
        for (int c = 0; c < 3; ++c) CHECK(x.color[c] * x.intensity == y.color[c] * y.intensity);
        CHECK(x.position == y.position);
        if (x.type != LightType::point) CHECK(x.direction == y.direction);
        CHECK(x.range == y.range);
        CHECK(x.cos_inner == y.cos_inner);
        CHECK(x.cos_outer == y.cos_outer);
    }
}

void check_same_bake(const Scene& a, const Scene& b) {
    const std::vector<float> sa = bake_lighting(a, kProbes, bake_settings());
    const std::vector<float> sb = bake_lighting(b, kProbes, bake_settings());
    REQUIRE(sa.size() == sb.size());
    CHECK(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(float)) == 0);
    double energy = 0;
    for (float c : sa) energy += std::abs(c);
    CHECK(energy > 1.0);  // the scene is lit: equality is not of zeros
}

// The ASCII FBX 7.4 of one quad (two triangles) at (1, 2, 3), in a file of the given unit and up axis.
std::string fbx_quad(double unit_cm, int up_axis, bool with_mesh = true) {
    std::ostringstream f;
    f << "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n\tFBXVersion: 7400\n}\n"
      << "GlobalSettings:  {\n\tVersion: 1000\n\tProperties70:  {\n"
      << "\t\tP: \"UpAxis\", \"int\", \"Integer\", \"\"," << up_axis << "\n"
      << "\t\tP: \"UpAxisSign\", \"int\", \"Integer\", \"\",1\n"
      << "\t\tP: \"UnitScaleFactor\", \"double\", \"Number\", \"\"," << unit_cm << "\n\t}\n}\n"
      << "Objects:  {\n";
    if (with_mesh)
        f << "\tGeometry: 1000, \"Geometry::quad\", \"Mesh\" {\n\t\tVertices: *12 {\n\t\t\ta: 0,0,0,1,0,0,1,1,0,0,1,0\n\t\t}\n"
          << "\t\tPolygonVertexIndex: *4 {\n\t\t\ta: 0,1,2,-4\n\t\t}\n\t\tGeometryVersion: 124\n\t}\n";
    f << "\tModel: 2000, \"Model::quad\", \"Mesh\" {\n\t\tVersion: 232\n\t\tProperties70:  {\n"
      << "\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\",1,2,3\n\t\t}\n\t}\n}\n"
      << "Connections:  {\n\tC: \"OO\",2000,0\n" << (with_mesh ? "\tC: \"OO\",1000,2000\n" : "") << "}\n";
    return f.str();
}

// Everything written to stdout and stderr while f runs.
template <class F>
std::string console_output_of(F f) {
    std::fflush(stdout);
    std::fflush(stderr);
    char name[] = "/tmp/tetprobe_console_XXXXXX";
    const int capture = mkstemp(name);
    REQUIRE(capture >= 0);
    const int saved_out = dup(1), saved_err = dup(2);
    dup2(capture, 1);
    dup2(capture, 2);
    f();
    std::fflush(stdout);
    std::fflush(stderr);
    dup2(saved_out, 1);
    dup2(saved_err, 2);
    close(saved_out);
    close(saved_err);
    close(capture);
    std::ifstream in(name, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    std::remove(name);
    return text.str();
}

}  // namespace

TEST_CASE("up axis: turns between axes are exact rotations, and back", "[scene][import]") {
    const UpAxis axes[6] = {UpAxis::pos_x, UpAxis::neg_x, UpAxis::pos_y, UpAxis::neg_y, UpAxis::pos_z, UpAxis::neg_z};
    for (UpAxis from : axes)
        for (UpAxis to : axes) {
            const AxisTurn turn = turn_between(from, to);
            CHECK(turn.apply(from) == to);
            int m[3][3] = {};
            for (int i = 0; i < 3; ++i) m[i][turn.from[i]] = turn.sign[i];
            const int det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                            m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
            CHECK(det == 1);  // a rotation: one-sided faces keep facing the same way
            const float p[3] = {0.1f, -2.5f, 7.25f};
            float q[3], back[3];
            turn.apply(p, q);
            turn.inverse().apply(q, back);
            CHECK(std::memcmp(p, back, sizeof p) == 0);
            CHECK(turn.identity() == (from == to));
        }
    CHECK(parse_up_axis("-z", "x") == UpAxis::neg_z);
    CHECK(error_of([] { parse_up_axis("up", "scene.json"); }).status() == Status::scene);
}

TEST_CASE("JSON scene: inline meshes, files, lights, sky, probes and grids", "[scene][import]") {
    TempDir dir;
    fs::create_directories(dir.path / "meshes");
    dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    const std::string path = dir.write("scene.json", R"({
      "meshes": [
        {"name": "floor", "vertices": [[0,0,0],[1,0,0],[1,0,1],[0,0,1]], "indices": [0,2,1, 0,3,2],
         "materials": [{"albedo": [0.5,0.5,0.5]}, {"emission": [1,2,3], "two_sided": true}],
         "triangle_materials": [0, 1]},
        {"name": "wall", "file": "meshes/tri.obj", "material": {"albedo": [0.2,0.3,0.4]}}
      ],
      "lights": [
        {"type": "directional", "direction": [0,-2,0], "intensity": 3, "mode": "realtime", "shadows": false},
        {"type": "point", "position": [1,2,3], "range": "inf", "intensity": 2, "near_distance": 0.5},
        {"type": "spot", "position": [0,5,0], "direction": [0,-1,0], "inner_angle": 10, "outer_angle": 30, "range": 9,
         "intensity": 5, "name": "torch"}
      ],
      "sky": {"color": [0.1, 0.2, 0.3]},
      "probes": [[0,0.5,0], [1,0.5,1]],
      "probe_grids": [{"min": [0,1,0], "max": [1,1,1], "counts": [2,1,3]}]
    })");
    Scene scene = load_scene_file(path);
    REQUIRE(scene.meshes().size() == 2);
    CHECK(scene.meshes()[0].label.find("'floor'") != std::string::npos);
    CHECK(scene.meshes()[0].materials[1].two_sided);
    CHECK(scene.meshes()[0].emissive());
    CHECK(scene.meshes()[1].triangle_count() == 2);
    CHECK(scene.meshes()[1].materials[0].albedo[2] == 0.4f);
    REQUIRE(scene.lights().size() == 3);
    CHECK(scene.lights()[0].realtime);
    CHECK_FALSE(scene.lights()[0].shadows);
    CHECK(scene.lights()[0].direction[1] == -1.0);
    CHECK(scene.lights()[0].intensity == 3.0f);
    CHECK(std::isinf(scene.lights()[1].range));
    CHECK(scene.lights()[1].near_distance == 0.5);
    CHECK(scene.lights()[2].near_distance == 0);
    CHECK(scene.lights()[2].cos_inner == Approx(std::cos(5.0 * kPi / 180.0)));
    CHECK(scene.sky().kind == SkyKind::color);
    CHECK(scene.up() == UpAxis::pos_y);
    REQUIRE(scene.probe_count() == 8);
    CHECK(scene.probes()[3 * 7 + 2] == 1.0f);  // the grid's last probe
    CHECK(scene.probes()[3 * 4 + 2] == 0.5f);  // x varies fastest, then y, then z
}

TEST_CASE("JSON scene: optional keys take their documented defaults", "[scene][import]") {
    TempDir dir;
    const Scene scene = load_scene_file(dir.write("defaults.json", R"({
      "meshes": [{"vertices": [0,0,0, 1,0,0, 0,0,1], "indices": [0,2,1]}],
      "lights": [{"type": "spot", "position": [0,1,0], "direction": [0,-1,0], "intensity": 2}]})"));
    const Material& m = scene.meshes()[0].materials[0];
    CHECK(m.albedo == std::array<float, 3>{{kDefaultAlbedo, kDefaultAlbedo, kDefaultAlbedo}});
    CHECK(m.emission == std::array<float, 3>{{0, 0, 0}});
    CHECK_FALSE(m.two_sided);
    const Light& l = scene.lights()[0];
    CHECK(l.color == std::array<float, 3>{{1, 1, 1}});
    CHECK_FALSE(l.realtime);
    CHECK_FALSE(l.mixed);
    CHECK(l.shadows);
    CHECK(std::isinf(l.range));
    CHECK(l.cos_inner == Approx(std::cos(kDefaultSpotInnerAngle / 2 * kPi / 180)));
    CHECK(l.cos_outer == Approx(std::cos(kDefaultSpotOuterAngle / 2 * kPi / 180)));
    CHECK(l.near_distance == 0);
    CHECK(scene.up() == UpAxis::pos_y);
    CHECK(scene.probe_count() == 0);
    CHECK(scene.sky().kind == SkyKind::none);
    CHECK(scene.notes().empty());
}

TEST_CASE("JSON scene: an absolute file path is used as it is", "[scene][import]") {
    const std::string obj = std::string(TP_SOURCE_DIR) + "/samples/scenes/two_rooms.obj";
    REQUIRE(fs::path(obj).is_absolute());
    TempDir dir;
    fs::copy_file(obj, dir.path / "copy.obj");
    const Scene absolute = load_scene_file(dir.write("absolute.json", R"({"meshes": [{"file": ")" + obj + R"("}]})"));
    const Scene relative = load_scene_file(dir.write("relative.json", R"({"meshes": [{"file": "copy.obj"}]})"));
    REQUIRE(absolute.meshes().size() == 1);
    CHECK(absolute.meshes()[0].triangle_count() > 0);
    check_same_meshes(absolute, relative);
}

TEST_CASE("JSON scene: errors name the file, the mesh or light and what is wrong", "[scene][import]") {
    TempDir dir;
    auto expect = [&](const std::string& text, Status status, std::initializer_list<const char*> words) {
        const std::string path = dir.write("bad.json", text);
        Error e = error_of([&] { load_scene_file(path); });
        CHECK(e.status() == status);
        CHECK(mentions(e, "bad.json"));
        for (const char* w : words) CHECK(mentions(e, w));
    };
    const char* point = R"({"type": "point", "position": [0,0,0], "intensity": 1})";
    expect("{\"meshes\": [ {\"vertices\": [1, 2, }", Status::scene, {"malformed JSON", "line 1"});
    expect("[1, 2, 3]", Status::scene, {"expected an object"});
    expect("{\"mehses\": []}", Status::scene, {"unknown key \"mehses\""});
    expect("{}", Status::scene, {"empty"});
    expect(R"({"meshes": [{"name": "a", "vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2]},
                          {"name": "b", "vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,3]}]})",
           Status::scene, {"mesh 1 ('b')", "index 3"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1], "indices": [0,1,2]}]})", Status::scene, {"mesh 0", "not a multiple of 3"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,-2]}]})", Status::scene, {"mesh 0", "index 2"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2], "material": {"albedo": [2,0,0]}}]})",
           Status::scene, {"mesh 0", "albedo"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2], "material": {"albedo": "red"}}]})",
           Status::scene, {"albedo", "expected [x, y, z]"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2], "scale": 2}]})", Status::scene,
           {"mesh 0", "\"scale\" applies only to a \"file\""});
    expect(R"({"meshes": [{"name": "walls", "file": "missing.obj"}]})", Status::scene, {"mesh 0 ('walls')", "missing.obj"});
    expect(R"({"meshes": [{"name": "walls", "obj": "walls.obj"}]})", Status::scene, {"mesh 0", "unknown key \"obj\""});
    expect(std::string(R"({"lights": [)") + point + R"(, {"type": "laser", "intensity": 1}]})", Status::scene, {"light 1", "laser"});
    expect(R"({"lights": [{"type": "point", "position": [0,0,0], "intensity": -4}]})", Status::scene, {"light 0", "intensity"});
    expect(R"({"lights": [{"type": "point", "position": [0,0,0], "color": [1,1,1]}]})", Status::scene,
           {"light 0", "needs an \"intensity\""});
    expect(R"({"lights": [{"type": "point", "intensity": 1}]})", Status::scene, {"light 0", "position"});
    expect(R"({"lights": [{"type": "point", "position": [0,0,0], "intensity": 1, "near_distance": -1}]})", Status::scene,
           {"light 0", "near distance"});
    expect(R"({"lights": [{"type": "point", "position": [0,0,0], "intensity": 1, "near_distance": "close"}]})",
           Status::scene, {"light 0", "near_distance"});
    expect(R"({"lights": [{"position": [0,0,0], "intensity": 1, "name": "lamp"}]})", Status::scene, {"light 0 ('lamp')", "type"});
    expect(std::string(R"({"lights": [)") + point + R"(], "up": "north"})", Status::scene, {"up", "north"});
    expect(R"({"sky": {"sh": [1, 2, 3]}})", Status::scene, {"sky", "27"});
    expect(R"({"sky": {"color": [1, 1, 1]}, "probes": [[0, 0, 0], [1, 2]]})", Status::scene, {"probes[1]"});
    dir.write("inner.json", R"({"sky": {"color": [1, 1, 1]}})");
    expect(R"({"meshes": [{"file": "inner.json"}]})", Status::scene, {"mesh 0", "JSON scene"});

    Error missing = error_of([&] { load_scene_file((dir.path / "nowhere.json").string()); });
    CHECK(missing.status() == Status::io);
    CHECK(mentions(missing, "nowhere.json"));
    const std::string sky = dir.write("sky.json", R"({"sky": {"color": [1, 1, 1]}})");
    SceneLoadOptions scaled;
    scaled.scale = 2;
    CHECK(error_of([&] { load_scene_file(sky, scaled); }).status() == Status::invalid_argument);
    SceneLoadOptions negative;
    negative.scale = -1;
    CHECK(error_of([&] { load_scene_file(sky, negative); }).status() == Status::invalid_argument);
    const std::string unknown = dir.write("level.dae", "<COLLADA/>");
    Error format = error_of([&] { load_scene_file(unknown); });
    CHECK(format.status() == Status::scene);
    CHECK(mentions(format, "level.dae"));
    CHECK(mentions(format, ".gltf"));
}

TEST_CASE("glTF: bakes the same SH, bit for bit, as the JSON scene of its triangles, materials and lights", "[scene][import]") {
    TempDir dir;
    std::string buffer;
    const json document = gltf_scene(&buffer);
    const Scene from_gltf = load_scene_file(dir.write("scene.gltf", gltf_text(document, buffer)));
    const Scene from_json = load_scene_file(dir.write("scene.json", json_scene(true).dump()));
    check_same_meshes(from_gltf, from_json);
    check_same_lights(from_gltf, from_json);
    CHECK(from_gltf.up() == UpAxis::pos_y);
    CHECK(from_gltf.lights()[0].range == 16.0);
    CHECK(from_gltf.lights()[1].cos_inner == Approx(std::cos(0.25)).epsilon(1e-6));  // half-angle 0.25 rad
    CHECK(from_gltf.lights()[1].cos_outer == Approx(std::cos(0.5)).epsilon(1e-6));
    check_same_bake(from_gltf, from_json);

    // The same as a .glb: the container holds the same document and buffer.
    const Scene from_glb = load_scene_file(dir.write("scene.glb", glb_bytes(document, buffer)));
    check_same_meshes(from_glb, from_json);
    check_same_lights(from_glb, from_json);
    check_same_bake(from_glb, from_json);
    // And with a .bin buffer beside it.
    dir.write("scene.bin", buffer);
    json external = document;
    external["buffers"][0]["uri"] = "scene.bin";
    const Scene from_external = load_scene_file(dir.write("external.gltf", external.dump()));
    check_same_meshes(from_external, from_json);
}

TEST_CASE("OBJ + MTL: albedo from Kd, emission from Ke; the same bake as the JSON scene", "[scene][import]") {
    TempDir dir;
    std::string mtl;
    const std::string obj = obj_and_mtl(&mtl);
    dir.write("scene.mtl", mtl);
    const std::string obj_path = dir.write("scene.obj", obj);
    const Scene from_obj = load_scene_file(obj_path);
    // OBJ has no double-sided faces and no lights.
    const Scene from_json = load_scene_file(dir.write("scene.json", json_scene(false, false).dump()));
    check_same_meshes(from_obj, from_json);
    CHECK(from_obj.lights().empty());
    CHECK(from_obj.up() == UpAxis::pos_y);
    check_same_bake(from_obj, from_json);

    // A JSON scene placing the OBJ, with the JSON's lights: the same as everything inline.
    json placing = json_scene(true, false);
    placing["meshes"] = json::array({{{"name", "level"}, {"file", "scene.obj"}}});
    const Scene placed = load_scene_file(dir.write("placing.json", placing.dump()));
    const Scene inline_scene = load_scene_file(dir.write("inline.json", json_scene(true, false).dump()));
    check_same_meshes(placed, inline_scene);
    check_same_lights(placed, inline_scene);
    check_same_bake(placed, inline_scene);
}

TEST_CASE("glTF: node transforms, mirroring, scale and up", "[scene][import]") {
    TempDir dir;
    // One floor triangle (facing +y) under a parent that moves it by (1, 2, 3) and a child that scales
    // it by 2 and mirrors z: the mirrored triangle must still face +y (glTF: a negative determinant
    // flips the winding).
    const std::vector<float> tri = {0, 0, 0, 0, 0, 1, 1, 0, 0};
    const std::vector<uint32_t> idx = {0, 1, 2};
    const std::string buffer = raw_bytes(tri) + raw_bytes(idx);
    json g = {{"asset", {{"version", "2.0"}}},
              {"scene", 0},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"name", "parent"}, {"translation", {1, 2, 3}}, {"children", {1}}},
                         {{"name", "child"}, {"scale", {2, 2, -2}}, {"mesh", 0}}}},
              {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
              {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
                              {"min", {0, 0, 0}}, {"max", {1, 0, 1}}},
                             {{"bufferView", 1}, {"componentType", 5125}, {"count", 3}, {"type", "SCALAR"}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                               {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 12}}}},
              {"buffers", {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}}}};
    const std::string path = dir.write("moved.gltf", g.dump());
    const Scene moved = load_scene_file(path);
    const Mesh& mesh = moved.meshes().at(0);
    auto corner = [&](const Mesh& m, int k, int a) { return m.vertices[3 * m.indices[k] + a]; };
    // Corner 1 (0, 0, 1) goes to (1, 2, 3 - 2); corner 2 (1, 0, 0) to (3, 2, 3).
    std::vector<std::array<float, 3>> corners;
    for (int k = 0; k < 3; ++k) corners.push_back({corner(mesh, k, 0), corner(mesh, k, 1), corner(mesh, k, 2)});
    CHECK(std::count(corners.begin(), corners.end(), std::array<float, 3>{{1, 2, 3}}) == 1);
    CHECK(std::count(corners.begin(), corners.end(), std::array<float, 3>{{1, 2, 1}}) == 1);
    CHECK(std::count(corners.begin(), corners.end(), std::array<float, 3>{{3, 2, 3}}) == 1);
    const float e1[3] = {corners[1][0] - corners[0][0], corners[1][1] - corners[0][1], corners[1][2] - corners[0][2]};
    const float e2[3] = {corners[2][0] - corners[0][0], corners[2][1] - corners[0][1], corners[2][2] - corners[0][2]};
    CHECK(e1[2] * e2[0] - e1[0] * e2[2] > 0);  // the normal's y: still facing up

    // Scale: positions, light positions and ranges scale; point and spot intensities by scale^2, so
    // irradiance at the scaled place is the same; a directional light's irradiance is unchanged.
    std::string scene_buffer;
    const std::string scene_path = dir.write("scene.gltf", gltf_text(gltf_scene(&scene_buffer), scene_buffer));
    SceneLoadOptions twice;
    twice.scale = 2;
    const Scene one = load_scene_file(scene_path), two = load_scene_file(scene_path, twice);
    for (size_t i = 0; i < one.meshes()[0].vertices.size(); ++i)
        CHECK(two.meshes()[0].vertices[i] == 2 * one.meshes()[0].vertices[i]);
    for (size_t l = 0; l < one.lights().size(); ++l) {
        const Light &a = one.lights()[l], &b = two.lights()[l];
        for (int k = 0; k < 3; ++k) CHECK(b.position[k] == 2 * a.position[k]);
        CHECK(b.intensity == (a.positional() ? 4 : 1) * a.intensity);
        if (a.positional()) CHECK(b.range == 2 * a.range);
    }
    std::vector<float> doubled(kProbes);
    for (float& c : doubled) c *= 2;
    // Every length doubles exactly in binary floating point: the same SH at the doubled places, bit for bit.
    const std::vector<float> sa = bake_lighting(one, kProbes, bake_settings()), sb = bake_lighting(two, doubled, bake_settings());
    CHECK(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(float)) == 0);

    // Up: the file's own (glTF: +y) unless the options say otherwise; coordinates are kept.
    SceneLoadOptions z_up;
    z_up.up = UpAxis::pos_z;
    const Scene as_z = load_scene_file(scene_path, z_up);
    CHECK(as_z.up() == UpAxis::pos_z);
    CHECK(as_z.meshes()[0].vertices == one.meshes()[0].vertices);
}

TEST_CASE("JSON scene: a placed file is turned from its up to the scene's, scaled, its lights' modes set", "[scene][import]") {
    TempDir dir;
    std::string buffer;
    dir.write("scene.gltf", gltf_text(gltf_scene(&buffer), buffer));
    const Scene plain = load_scene_file((dir.path / "scene.gltf").string());
    // The glTF said to be z-up, placed in a y-up scene: (x, y, z) becomes (x, z, -y).
    const Scene turned = load_scene_file(dir.write("turned.json", R"({"meshes": [{"file": "scene.gltf", "up": "+z",
        "scale": 0.5, "light_modes": {"sun": "mixed", "lamp": "realtime"}}]})"));
    CHECK(turned.up() == UpAxis::pos_y);
    const std::vector<float>& a = plain.meshes()[1].vertices;
    const std::vector<float>& b = turned.meshes()[1].vertices;
    REQUIRE(a.size() == b.size());
    for (size_t v = 0; v < a.size(); v += 3) {
        CHECK(b[v] == 0.5f * a[v]);
        CHECK(b[v + 1] == 0.5f * a[v + 2]);
        CHECK(b[v + 2] == -0.5f * a[v + 1]);
    }
    CHECK(turned.lights()[0].realtime);
    CHECK_FALSE(turned.lights()[0].mixed);
    CHECK(turned.lights()[2].mixed);
    CHECK_FALSE(turned.lights()[1].realtime);
    CHECK(turned.lights()[2].direction[2] == 1.0);  // the sun's -y turned onto +z
    Error unknown = error_of([&] {
        load_scene_file(dir.write("unknown.json", R"({"meshes": [{"file": "scene.gltf", "light_modes": {"moon": "baked"}}]})"));
    });
    CHECK(unknown.status() == Status::scene);
    CHECK(mentions(unknown, "moon"));
    // A JSON scene that is itself z-up keeps the file's z-up coordinates as they are.
    const Scene z_scene = load_scene_file(dir.write("z.json", R"({"up": "+z", "meshes": [{"file": "scene.gltf", "up": "+z"}]})"));
    CHECK(z_scene.up() == UpAxis::pos_z);
    CHECK(z_scene.meshes()[1].vertices == a);
}

TEST_CASE("FBX: an ASCII file loads with its triangles, unit and up axis", "[scene][import]") {
    TempDir dir;
    // UnitScaleFactor 100: one file unit is a metre; the quad at (1, 2, 3) keeps its coordinates.
    const Scene metres = load_scene_file(dir.write("metres.fbx", fbx_quad(100, 2)));
    REQUIRE(metres.meshes().size() == 1);
    CHECK(metres.meshes()[0].triangle_count() == 2);
    CHECK(metres.up() == UpAxis::pos_z);
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < metres.meshes()[0].vertices.size(); ++v) {
        lo[v % 3] = std::min(lo[v % 3], metres.meshes()[0].vertices[v]);
        hi[v % 3] = std::max(hi[v % 3], metres.meshes()[0].vertices[v]);
    }
    CHECK(lo[0] == 1.0f);
    CHECK(hi[1] == 3.0f);
    CHECK(lo[2] == 3.0f);
    // UnitScaleFactor 1 (centimetres, FBX's default): the same quad a hundredth of the size, in metres.
    const Scene centimetres = load_scene_file(dir.write("centimetres.fbx", fbx_quad(1, 1)));
    CHECK(centimetres.up() == UpAxis::pos_y);
    for (size_t v = 0; v < 12; ++v)
        CHECK(centimetres.meshes()[0].vertices[v] == Approx(0.01 * metres.meshes()[0].vertices[v]).epsilon(1e-6));
    // The options win over the file: one unit = one world unit, and up as given.
    SceneLoadOptions options;
    options.scale = 1;
    options.up = UpAxis::neg_x;
    const Scene as_given = load_scene_file(dir.path.string() + "/centimetres.fbx", options);
    CHECK(as_given.meshes()[0].vertices == metres.meshes()[0].vertices);
    CHECK(as_given.up() == UpAxis::neg_x);
}

TEST_CASE("FBX: a point light as Assimp reports it; an area light is left out and noted", "[scene][import]") {
    TempDir dir;
    std::string text = fbx_quad(100, 1);
    const std::string objects = "Objects:  {\n";
    text.insert(text.find(objects) + objects.size(),
                "\tNodeAttribute: 3000, \"NodeAttribute::Panel\", \"Light\" {\n\t\tProperties70:  {\n"
                "\t\t\tP: \"LightType\", \"enum\", \"\", \"\",3\n\t\t}\n\t\tTypeFlags: \"Light\"\n\t}\n"
                "\tModel: 4000, \"Model::Panel\", \"Light\" {\n\t\tVersion: 232\n\t}\n"
                "\tNodeAttribute: 5000, \"NodeAttribute::Bulb\", \"Light\" {\n\t\tProperties70:  {\n"
                "\t\t\tP: \"LightType\", \"enum\", \"\", \"\",0\n\t\t\tP: \"Color\", \"Color\", \"\", \"A\",1,0.5,0.25\n"
                "\t\t\tP: \"Intensity\", \"Number\", \"\", \"A\",200\n\t\t}\n\t\tTypeFlags: \"Light\"\n\t}\n"
                "\tModel: 6000, \"Model::Bulb\", \"Light\" {\n\t\tVersion: 232\n\t\tProperties70:  {\n"
                "\t\t\tP: \"Lcl Translation\", \"Lcl Translation\", \"\", \"A\",0.5,1,0.5\n\t\t}\n\t}\n");
    const std::string connections = "Connections:  {\n";
    text.insert(text.find(connections) + connections.size(),
                "\tC: \"OO\",4000,0\n\tC: \"OO\",3000,4000\n\tC: \"OO\",6000,0\n\tC: \"OO\",5000,6000\n");
    const Scene scene = load_scene_file(dir.write("lights.fbx", text));
    REQUIRE(scene.lights().size() == 1);
    const Light& bulb = scene.lights()[0];
    CHECK(bulb.type == LightType::point);
    CHECK(bulb.position == std::array<double, 3>{{0.5, 1, 0.5}});
    CHECK(bulb.color == std::array<float, 3>{{2, 1, 0.5f}});  // FBX's colour x intensity / 100
    CHECK(noted(scene, "light 'Panel' is of a kind Assimp cannot represent"));
    CHECK(noted(scene, "Assimp: "));
}

TEST_CASE("import notes: cameras, animations, textures and transparency are reported, not dropped silently", "[scene][import]") {
    TempDir dir;
    std::string buffer;
    json g = gltf_scene(&buffer);
    // An animation needs its keyframe data in the buffer: two times and two translations.
    const std::vector<float> times = {0, 1}, moves = {0, 0, 0, 0, 1, 0};
    const size_t at = buffer.size();
    buffer += raw_bytes(times) + raw_bytes(moves);
    g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 8}});
    g["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at + 8}, {"byteLength", 24}});
    const size_t view = g["bufferViews"].size();
    g["accessors"].push_back({{"bufferView", view - 2}, {"componentType", 5126}, {"count", 2}, {"type", "SCALAR"},
                              {"min", {0}}, {"max", {1}}});
    g["accessors"].push_back({{"bufferView", view - 1}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
    const size_t accessor = g["accessors"].size();
    g["animations"] = {{{"name", "bob"},
                        {"samplers", {{{"input", accessor - 2}, {"output", accessor - 1}}}},
                        {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};
    g["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
    g["nodes"].push_back({{"name", "eye"}, {"camera", 0}});
    g["scenes"][0]["nodes"].push_back(g["nodes"].size() - 1);
    // The floor's material: a base colour texture (its factor is what is baked) and half transparent.
    g["images"] = {{{"uri", "bricks.png"}}};
    g["textures"] = {{{"source", 0}}};
    g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.5;
    const Scene scene = load_scene_file(dir.write("noted.gltf", gltf_text(g, buffer)));
    CHECK(noted(scene, "camera"));
    CHECK(noted(scene, "animation"));
    CHECK(noted(scene, "floor material' has textures"));
    CHECK(noted(scene, "transparent"));
    for (const std::string& note : scene.notes()) CHECK(note.rfind(dir.path.string() + "/noted.gltf: ", 0) == 0);
    // The texture's factor is the albedo.
    CHECK(scene.meshes()[0].materials[0].albedo == test_meshes()[0].albedo);

    // A glTF without any of that has no notes.
    std::string clean_buffer;
    CHECK(load_scene_file(dir.write("clean.gltf", gltf_text(gltf_scene(&clean_buffer), clean_buffer))).notes().empty());
    // An OBJ without a material library takes the default material, and says so.
    const Scene bare = load_scene_file(dir.write("bare.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n"));
    CHECK(bare.meshes()[0].materials[0].albedo[0] == kDefaultAlbedo);
    CHECK(noted(bare, "default"));
}

TEST_CASE("bad scene files: a clear Status::scene naming the file, and Assimp prints nothing", "[scene][import]") {
    TempDir dir;
    std::string buffer;
    const json document = gltf_scene(&buffer);
    const std::string glb = glb_bytes(document, buffer);
    auto expect = [&](const std::string& name, const std::string& bytes, std::initializer_list<const char*> words) {
        const std::string path = dir.write(name, bytes);
        Error e = error_of([&] { load_scene_file(path); });
        CHECK(e.status() == Status::scene);
        CHECK(mentions(e, name));
        for (const char* w : words) CHECK(mentions(e, w));
    };
    const std::string printed = console_output_of([&] {
        expect("malformed.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [", {"malformed glTF", "invalid"});
        expect("no_asset.gltf", "{\"nodes\": []}", {"asset.version"});
        expect("old.gltf", "{\"asset\": {\"version\": \"1.0\"}}", {"only glTF 2.0"});
        expect("truncated.glb", glb.substr(0, glb.size() / 2), {"truncated"});
        expect("empty.glb", "", {"truncated"});
        // Every prefix of the .glb is refused before Assimp reads it.
        for (size_t cut = 0; cut < glb.size(); cut += 7) {
            const std::string path = dir.write("prefix.glb", glb.substr(0, cut));
            CHECK(error_of([&] { load_scene_file(path); }).status() == Status::scene);
        }
        json area = document;
        area["extensions"]["KHR_lights_punctual"]["lights"][2]["type"] = "area";
        area["extensions"]["KHR_lights_punctual"]["lights"][2]["name"] = "window";
        expect("area_light.gltf", gltf_text(area, buffer), {"light 2 ('window')", "unknown type \"area\""});
        json beyond = document;
        beyond["accessors"][0]["count"] = 1000;  // reads past its buffer
        expect("beyond.gltf", gltf_text(beyond, buffer), {"not a readable glTF"});
        json missing_bin = document;
        missing_bin["buffers"][0]["uri"] = "missing.bin";
        expect("missing_bin.gltf", missing_bin.dump(), {"missing.bin"});
        expect("no_mesh.fbx", fbx_quad(100, 1, false), {"no"});
        expect("missing_mtl.obj", "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n", {"missing.mtl"});
        expect("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n", {"no triangle mesh"});
        expect("garbage.fbx", "this is not an FBX file at all\n", {"garbage.fbx"});
    });
    CHECK(printed.empty());
    if (!printed.empty()) WARN("printed: " << printed);
}

TEST_CASE("scene files: loads on several threads at once each get their own scene and notes", "[scene][import]") {
    TempDir dir;
    std::string buffer;
    const std::string gltf = dir.write("scene.gltf", gltf_text(gltf_scene(&buffer), buffer));
    const std::string bare = dir.write("bare.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n");
    const Scene gltf_alone = load_scene_file(gltf), bare_alone = load_scene_file(bare);
    std::vector<Scene> loaded(8);
    std::vector<std::thread> threads;
    for (size_t t = 0; t < loaded.size(); ++t)
        threads.emplace_back([&, t] { loaded[t] = load_scene_file(t % 2 ? bare : gltf); });
    for (std::thread& thread : threads) thread.join();
    for (size_t t = 0; t < loaded.size(); ++t) {
        const Scene& alone = t % 2 ? bare_alone : gltf_alone;
        check_same_meshes(loaded[t], alone);
        CHECK(loaded[t].notes() == alone.notes());
    }
    CHECK(gltf_alone.notes().empty());
    CHECK(bare_alone.notes().size() == 1);
}

TEST_CASE("placement: walkable columns stand along the scene's up", "[scene][import][placement]") {
    // The room with a pillar and a table of the placement tests, built y-up and turned exactly onto
    // every other up: the candidates are the y-up ones turned the same way.
    Scene upright;
    placement_test::add_box(upright, {0, 0, 0}, {6, 3, 6}, false);
    placement_test::add_box(upright, {2.5f, 0, 2.5f}, {3.5f, 2, 3.5f}, true);
    placement_test::add_box(upright, {4.5f, 0, 0.5f}, {5.5f, 0.8f, 1.5f}, true);
    CandidateRules rules;
    rules.mode = PlacementMode::walkable;
    rules.spacing = 0.75;
    rules.margin = 0.2;
    rules.walk_max_height = 1.5;
    const Candidates expected = find_candidates(upright, rules, 1, 2, Progress{});
    REQUIRE(expected.positions.size() / 3 > 100);
    for (UpAxis up : {UpAxis::pos_z, UpAxis::neg_z, UpAxis::pos_x, UpAxis::neg_y}) {
        INFO("up " << up_axis_name(up));
        const AxisTurn turn = turn_between(UpAxis::pos_y, up);
        Scene turned = upright.meshes_turned(turn);
        CHECK(turned.up() == up);
        const Candidates got = find_candidates(turned, rules, 1, 2, Progress{});
        CHECK(candidate_bound(turned, rules) == expected.tested);
        REQUIRE(got.positions.size() == expected.positions.size());
        REQUIRE(got.validation.size() == expected.validation.size());
        for (size_t i = 0; i < got.positions.size(); i += 3) {
            float want[3];
            turn.apply(&expected.positions[i], want);
            CHECK(std::memcmp(want, &got.positions[i], sizeof want) == 0);
        }
        // Up matters: with +y assumed, the turned room's floors are walls and the answer differs.
        turned.set_up(UpAxis::pos_y);
        if (up != UpAxis::neg_y) CHECK(find_candidates(turned, rules, 1, 2, Progress{}).positions.size() != got.positions.size());
    }
}

TEST_CASE("scene files: the sample scenes load; the glTF two rooms are the JSON's rooms, table and lights", "[scene][import]") {
    const std::string root = std::string(TP_SOURCE_DIR) + "/samples/scenes/";
    for (const char* name : {"cornell_box.json", "two_rooms.json", "race_track.json"}) {
        INFO(name);
        Scene scene = load_scene_file(root + name);
        CHECK(scene.meshes().size() >= 2);
        CHECK(scene.probe_count() >= 50);
        CHECK(scene.dropped_triangles() == 0);
        CHECK(scene.notes().empty());
    }
    Scene track = load_scene_file(root + "race_track.json");
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < track.probe_count(); ++i) {
        lo = std::min(lo, track.probes()[3 * i + 1]);
        hi = std::max(hi, track.probes()[3 * i + 1]);
    }
    CHECK(lo == hi);  // a flat probe set

    // make_scenes.py writes the two rooms as glTF too: the same triangles and materials; the lights
    // after conversion (the sun's direction passes through a quaternion: within float rounding).
    const Scene json_rooms = load_scene_file(root + "two_rooms.json");
    const Scene gltf_rooms = load_scene_file(root + "two_rooms.gltf");
    check_same_meshes(gltf_rooms, json_rooms);
    CHECK(gltf_rooms.notes().empty());
    REQUIRE(gltf_rooms.lights().size() == json_rooms.lights().size());
    for (size_t l = 0; l < json_rooms.lights().size(); ++l) {
        const Light &a = gltf_rooms.lights()[l], &b = json_rooms.lights()[l];
        CHECK(a.type == b.type);
        for (int k = 0; k < 3; ++k) {
            CHECK(a.color[k] * a.intensity == Approx(b.color[k] * b.intensity).epsilon(1e-6));
            CHECK(a.position[k] == Approx(b.position[k]).margin(1e-6));
            CHECK(a.direction[k] == Approx(b.direction[k]).margin(1e-6));
        }
        CHECK(a.range == b.range);
    }
}

TEST_CASE("docs/scene-format.md: its full example loads", "[scene][import]") {
    std::ifstream in(std::string(TP_SOURCE_DIR) + "/docs/scene-format.md");
    REQUIRE(in);
    std::stringstream text;
    text << in.rdbuf();
    const std::string doc = text.str();
    const std::string fence = "```json\n";
    const size_t start = doc.find(fence);
    REQUIRE(start != std::string::npos);
    const size_t end = doc.find("```", start + fence.size());
    const std::string example = doc.substr(start + fence.size(), end - start - fence.size());
    // The example places level.gltf: the sample two rooms stand in for it.
    TempDir dir;
    fs::copy_file(std::string(TP_SOURCE_DIR) + "/samples/scenes/two_rooms.gltf", dir.path / "level.gltf");
    const Scene scene = load_scene_file(dir.write("example.json", example));
    const json parsed = json::parse(example);
    CHECK(scene.up() == UpAxis::pos_y);
    CHECK(scene.meshes().size() == 1 + 2);  // the inline crate and the level's rooms and table
    CHECK(scene.lights().size() == parsed["lights"].size() + 2);
    CHECK(scene.sky().kind != SkyKind::none);
    CHECK(scene.probe_count() > 0);
}
