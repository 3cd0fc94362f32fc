// Scenes and scene files: validation names what is wrong and where; files load meshes inline and
// from OBJ; every sample scene loads.
#include <catch2/catch.hpp>

#include "bake/scene.h"
#include "bake/scene_file.h"
#include "core/error.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace tetprobe;
namespace fs = std::filesystem;

namespace {

const float kQuad[12] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
const uint32_t kQuadIndices[6] = {0, 2, 1, 0, 3, 2};

// Runs f and returns the Error it throws (fails the test if it throws nothing).
template <class F>
Error error_of(F f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    FAIL("no error was thrown");
    return Error(tetprobe::Status::ok, "");
}

bool mentions(const Error& e, const std::string& text) {
    const bool found = std::string(e.what()).find(text) != std::string::npos;
    if (!found) WARN("message: " << e.what() << " (expected to mention '" << text << "')");
    return found;
}

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("tetprobe_scene_test_" + std::to_string(std::rand()) + "_" +
                                            std::to_string(reinterpret_cast<uintptr_t>(this)));
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(path / name) << text;
        return (path / name).string();
    }
};

}  // namespace

TEST_CASE("scene: meshes are validated with messages naming mesh and index", "[scene]") {
    Scene scene;
    const std::vector<Material> grey(1);
    CHECK(scene.add_mesh(kQuad, 4, kQuadIndices, 2, grey, nullptr) == 0);
    CHECK(scene.meshes()[0].triangle_count() == 2);
    CHECK(scene.meshes()[0].bounds_max[0] == 1.0f);

    float nan_vertex[12];
    std::copy(kQuad, kQuad + 12, nan_vertex);
    nan_vertex[7] = NAN;
    Error e = error_of([&] { scene.add_mesh(nan_vertex, 4, kQuadIndices, 2, grey, nullptr); });
    CHECK(e.status() == tetprobe::Status::scene);
    CHECK(mentions(e, "mesh 1"));
    CHECK(mentions(e, "vertex 2"));

    const uint32_t out_of_range[6] = {0, 2, 1, 0, 3, 4};
    e = error_of([&] { scene.add_mesh(kQuad, 4, out_of_range, 2, grey, nullptr); });
    CHECK(e.status() == tetprobe::Status::scene);
    CHECK(mentions(e, "triangle 1"));
    CHECK(mentions(e, "index 4"));

    const uint32_t bad_material[2] = {0, 1};
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 2, grey, bad_material); });
    CHECK(mentions(e, "material 1"));

    std::vector<Material> bright(1);
    bright[0].albedo = {0.5f, 1.5f, 0.5f};
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 2, bright, nullptr); });
    CHECK(mentions(e, "albedo"));
    std::vector<Material> negative(1);
    negative[0].emission = {0.0f, -1.0f, 0.0f};
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 2, negative, nullptr); });
    CHECK(mentions(e, "emission"));
    CHECK(scene.meshes().size() == 1);  // nothing half-added

    // Zero-area triangles (a repeated index, collinear points) are dropped and counted.
    const float line[12] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 1};
    const uint32_t some_degenerate[9] = {0, 1, 2, 0, 0, 3, 0, 3, 1};
    CHECK(scene.add_mesh(line, 4, some_degenerate, 3, grey, nullptr) == 1);
    CHECK(scene.meshes()[1].triangle_count() == 1);
    CHECK(scene.meshes()[1].dropped_triangles == 2);
    CHECK(scene.dropped_triangles() == 2);
    e = error_of([&] { scene.add_mesh(line, 4, some_degenerate, 1, grey, nullptr); });
    CHECK(mentions(e, "zero area"));
    e = error_of([&] { scene.add_mesh(kQuad, 4, kQuadIndices, 0, grey, nullptr); });
    CHECK(mentions(e, "no triangles"));
}

TEST_CASE("scene: lights, sky and probes are validated", "[scene]") {
    Scene scene;
    LightDescription light;
    CHECK(scene.add_light(light) == 0);
    light.intensity = -1;
    Error e = error_of([&] { scene.add_light(light); });
    CHECK(e.status() == tetprobe::Status::scene);
    CHECK(mentions(e, "light 1"));
    CHECK(mentions(e, "intensity"));
    light.intensity = 1;
    light.type = LightType::directional;
    light.direction = {0, 0, 0};
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "direction"));
    light.type = LightType::spot;
    light.direction[1] = -1;
    light.inner_angle = 50, light.outer_angle = 40;
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "spot angles"));
    light.type = LightType::point;
    light.range = 0;
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "range"));
    light.range = INFINITY;
    light.mode = static_cast<LightMode>(5);
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "mode"));
    light.mode = LightMode::realtime;
    light.color[2] = NAN;
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "colour"));
    light.color[2] = 1;
    light.type = static_cast<LightType>(7);
    CHECK(mentions(error_of([&] { scene.add_light(light); }), "unknown type 7"));
    CHECK(scene.lights().size() == 1);

    const float sky[3] = {1, 2, 3}, bad_sky[3] = {1, -2, 3};
    scene.set_sky_color(sky);
    CHECK_FALSE(scene.sky().black());
    CHECK(mentions(error_of([&] { scene.set_sky_color(bad_sky); }), "sky"));
    const float black[3] = {0, 0, 0};
    scene.set_sky_color(black);
    CHECK(scene.sky().black());

    const float probes[6] = {0, 1, 2, 3, NAN, 5};
    CHECK(mentions(error_of([&] { scene.set_probes(probes, 2); }), "probe 1"));
    scene.set_probes(probes, 1);
    CHECK(scene.probe_count() == 1);
}

TEST_CASE("scene file: inline meshes, OBJ meshes, lights, sky, probes and grids", "[scene]") {
    TempDir dir;
    fs::create_directories(dir.path / "meshes");
    dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    const std::string path = dir.write("scene.json", R"({
      "meshes": [
        {"name": "floor", "vertices": [[0,0,0],[1,0,0],[1,0,1],[0,0,1]], "indices": [0,2,1, 0,3,2],
         "materials": [{"albedo": [0.5,0.5,0.5]}, {"emission": [1,2,3], "two_sided": true}],
         "triangle_materials": [0, 1]},
        {"name": "wall", "obj": "meshes/tri.obj", "material": {"albedo": [0.2,0.3,0.4]}}
      ],
      "lights": [
        {"type": "directional", "direction": [0,-2,0], "intensity": 3, "mode": "realtime", "shadows": false},
        {"type": "point", "position": [1,2,3], "range": "inf"},
        {"type": "spot", "position": [0,5,0], "direction": [0,-1,0], "inner_angle": 10, "outer_angle": 30, "range": 9}
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
    CHECK(std::isinf(scene.lights()[1].range));
    CHECK(scene.lights()[2].cos_inner == Approx(std::cos(5.0 * 3.14159265358979323846 / 180.0)));
    CHECK(scene.sky().kind == SkyKind::color);
    REQUIRE(scene.probe_count() == 8);
    CHECK(scene.probes()[3 * 7 + 2] == 1.0f);  // the grid's last probe
    CHECK(scene.probes()[3 * 4 + 2] == 0.5f);  // x varies fastest, then y, then z
}

TEST_CASE("scene file: an absolute OBJ path is used as it is", "[scene]") {
    const std::string obj = std::string(TP_SOURCE_DIR) + "/samples/scenes/two_rooms.obj";
    REQUIRE(fs::path(obj).is_absolute());
    TempDir dir;
    fs::copy_file(obj, dir.path / "copy.obj");
    const Scene absolute = load_scene_file(dir.write("absolute.json", R"({"meshes": [{"obj": ")" + obj + R"("}]})"));
    const Scene relative = load_scene_file(dir.write("relative.json", R"({"meshes": [{"obj": "copy.obj"}]})"));
    REQUIRE(absolute.meshes().size() == 1);
    REQUIRE(relative.meshes().size() == 1);
    CHECK(absolute.meshes()[0].triangle_count() > 0);
    CHECK(absolute.meshes()[0].vertices == relative.meshes()[0].vertices);
    CHECK(absolute.meshes()[0].indices == relative.meshes()[0].indices);
}

TEST_CASE("scene file: errors name the file, the mesh or light and the index", "[scene]") {
    TempDir dir;
    auto expect = [&](const std::string& json, tetprobe::Status status, std::initializer_list<const char*> words) {
        const std::string path = dir.write("bad.json", json);
        Error e = error_of([&] { load_scene_file(path); });
        CHECK(e.status() == status);
        CHECK(mentions(e, "bad.json"));
        for (const char* w : words) CHECK(mentions(e, w));
    };
    expect("{\"meshes\": [ {\"vertices\": [1, 2, }", tetprobe::Status::scene, {"malformed JSON", "line 1"});
    expect("[1, 2, 3]", tetprobe::Status::scene, {"expected an object"});
    expect("{\"mehses\": []}", tetprobe::Status::scene, {"unknown key \"mehses\""});
    expect("{}", tetprobe::Status::scene, {"empty"});
    expect(R"({"meshes": [{"name": "a", "vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2]},
                          {"name": "b", "vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,3]}]})",
           tetprobe::Status::scene, {"mesh 1 ('b')", "index 3"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1], "indices": [0,1,2]}]})", tetprobe::Status::scene,
           {"mesh 0", "not a multiple of 3"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,-2]}]})", tetprobe::Status::scene,
           {"mesh 0", "index 2"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2], "material": {"albedo": [2,0,0]}}]})",
           tetprobe::Status::scene, {"mesh 0", "albedo"});
    expect(R"({"meshes": [{"vertices": [0,0,0, 1,0,0, 0,1,0], "indices": [0,1,2], "material": {"albedo": "red"}}]})",
           tetprobe::Status::scene, {"albedo", "expected [x, y, z]"});
    expect(R"({"meshes": [{"name": "walls", "obj": "missing.obj"}]})", tetprobe::Status::io, {"mesh 0 ('walls')", "missing.obj"});
    expect(R"({"lights": [{"type": "point", "position": [0,0,0]}, {"type": "laser"}]})", tetprobe::Status::scene,
           {"light 1", "laser"});
    expect(R"({"lights": [{"type": "point", "position": [0,0,0], "intensity": -4}]})", tetprobe::Status::scene,
           {"light 0", "intensity"});
    expect(R"({"lights": [{"type": "point"}]})", tetprobe::Status::scene, {"light 0", "position"});
    expect(R"({"sky": {"sh": [1, 2, 3]}})", tetprobe::Status::scene, {"sky", "27"});
    expect(R"({"sky": {"color": [1, 1, 1]}, "probes": [[0, 0, 0], [1, 2]]})", tetprobe::Status::scene, {"probes[1]"});

    dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    expect(R"({"meshes": [{"name": "broken", "obj": "broken.obj"}]})", tetprobe::Status::scene, {"mesh 0 ('broken')"});

    Error missing = error_of([&] { load_scene_file((dir.path / "nowhere.json").string()); });
    CHECK(missing.status() == tetprobe::Status::io);
    CHECK(mentions(missing, "nowhere.json"));
}

TEST_CASE("scene file: the sample scenes load with their probes", "[scene]") {
    const std::string root = std::string(TP_SOURCE_DIR) + "/samples/scenes/";
    for (const char* name : {"cornell_box.json", "two_rooms.json", "race_track.json"}) {
        INFO(name);
        Scene scene = load_scene_file(root + name);
        CHECK(scene.meshes().size() >= 2);
        CHECK(scene.probe_count() >= 50);
        CHECK(scene.dropped_triangles() == 0);
    }
    Scene track = load_scene_file(root + "race_track.json");
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < track.probe_count(); ++i) {
        lo = std::min(lo, track.probes()[3 * i + 1]);
        hi = std::max(hi, track.probes()[3 * i + 1]);
    }
    CHECK(lo == hi);  // a flat probe set
}
