// Quake 3 levels: a small IBSP version 46 file written here (known faces, a patch, a mesh, a door, two
// lights, sky, water, nodraw and a billboard) imports to exactly the expected triangles, windings, lights
// and spawn points; the scene file loader (behind tp_scene_load_file) takes it by its magic; bad files are refused with
// TP_ERROR_SCENE and a message naming the file and what is wrong, and no prefix or corruption of a good
// file reads out of bounds (run under ASan by `make sanitize`).
#include <catch2/catch.hpp>

#include "bake/quake3_bsp.h"
#include "bake/quake3_patch.h"
#include "bake/quake3_scene.h"
#include "bake/scene_file.h"
#include "capi/tetprobe.h"
#include "core/error.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace tetprobe;
namespace fs = std::filesystem;

namespace {

// Little-endian writer of the lumps this importer reads (the others stay empty).
struct BspWriter {
    std::string entities;
    std::vector<uint8_t> shaders, models, vertices, mesh_vertices, faces;

    static void i32(std::vector<uint8_t>& out, int32_t v) {
        for (int k = 0; k < 4; ++k) out.push_back(uint8_t(uint32_t(v) >> (8 * k)));
    }
    static void f32(std::vector<uint8_t>& out, float v) {
        int32_t bits;
        std::memcpy(&bits, &v, 4);
        i32(out, bits);
    }
    int32_t shader(const char* name, int32_t surface_flags, int32_t contents) {
        char padded[64] = {};
        std::strncpy(padded, name, 63);
        shaders.insert(shaders.end(), padded, padded + 64);
        i32(shaders, surface_flags);
        i32(shaders, contents);
        return int32_t(shaders.size() / 72 - 1);
    }
    int32_t vertex(float x, float y, float z, float nx, float ny, float nz) {
        for (float v : {x, y, z, 0.0f, 0.0f, 0.0f, 0.0f, nx, ny, nz}) f32(vertices, v);
        for (int k = 0; k < 4; ++k) vertices.push_back(255);
        return int32_t(vertices.size() / 44 - 1);
    }
    int32_t face(int32_t shader_index, int32_t type, int32_t first_vertex, int32_t vertex_count,
                 const std::vector<int32_t>& mesh, int32_t width = 0, int32_t height = 0) {
        const int32_t first_mesh = int32_t(mesh_vertices.size() / 4);
        for (int32_t m : mesh) i32(mesh_vertices, m);
        for (int32_t v : {shader_index, -1, type, first_vertex, vertex_count, first_mesh, int32_t(mesh.size()), 0})
            i32(faces, v);
        for (int k = 0; k < 4 + 3 + 6 + 3; ++k) i32(faces, 0);  // lightmap start, size; origin; vecs; normal
        i32(faces, width);
        i32(faces, height);
        return int32_t(faces.size() / 104 - 1);
    }
    void model(int32_t first_face, int32_t face_count) {
        for (int k = 0; k < 6; ++k) f32(models, 0);
        for (int32_t v : {first_face, face_count, 0, 0}) i32(models, v);
    }

    std::vector<uint8_t> bytes(int32_t version = 46) const {
        std::vector<uint8_t> out = {'I', 'B', 'S', 'P'};
        i32(out, version);
        std::vector<std::vector<uint8_t>> lumps(17);
        lumps[0].assign(entities.begin(), entities.end());
        lumps[0].push_back(0);
        lumps[1] = shaders, lumps[7] = models, lumps[10] = vertices, lumps[11] = mesh_vertices, lumps[13] = faces;
        size_t offset = 8 + 17 * 8;
        for (const auto& lump : lumps) {
            i32(out, int32_t(offset));
            i32(out, int32_t(lump.size()));
            offset += lump.size();
        }
        for (const auto& lump : lumps) out.insert(out.end(), lump.begin(), lump.end());
        return out;
    }
};

constexpr int32_t kSolid = 1, kWater = 32, kSky = 4, kNodraw = 0x80;
constexpr float kPatchRise = 16.0f;  // the patch's centre control point above its plane (units)

// The level of these tests: a floor quad (polygon), a patch (3 x 3, centre raised), a mesh triangle whose
// normals face against Q3's winding, a door (brush model 1); sky, water, nodraw and a billboard left out.
BspWriter test_level() {
    BspWriter w;
    const int32_t floor = w.shader("textures/floor", 0, kSolid);
    const int32_t sky = w.shader("textures/skies/sky", kSky, kSolid);
    const int32_t water = w.shader("textures/liquids/water", 0, kWater);
    const int32_t clip = w.shader("textures/common/caulk", kNodraw, kSolid);
    // Floor at z = 0, facing +z; (0, 1, 2) is clockwise seen from above, as Q3 winds a front.
    int32_t v = w.vertex(0, 0, 0, 0, 0, 1);
    w.vertex(0, 64, 0, 0, 0, 1), w.vertex(64, 64, 0, 0, 0, 1), w.vertex(64, 0, 0, 0, 0, 1);
    w.face(floor, 1, v, 4, {0, 1, 2, 0, 2, 3});
    // Sky at z = 256 facing down, water and a nodraw quad: all left out.
    for (int32_t s : {sky, water, clip}) {
        v = w.vertex(0, 0, 256, 0, 0, -1);
        w.vertex(64, 0, 256, 0, 0, -1), w.vertex(64, 64, 256, 0, 0, -1);
        w.face(s, 1, v, 3, {0, 1, 2});
    }
    // Patch over [0, 128] x [0, 128] at z = 64, centre control point raised by kPatchRise.
    v = -1;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const int32_t k = w.vertex(64.0f * c, 64.0f * r, 64.0f + (r == 1 && c == 1 ? kPatchRise : 0.0f), 0, 0, 1);
            if (v < 0) v = k;
        }
    w.face(floor, 2, v, 9, {}, 3, 3);
    // Mesh triangle counter-clockwise seen from +z but with normals toward -z: it faces down.
    v = w.vertex(0, 0, 128, 0, 0, -1);
    w.vertex(64, 0, 128, 0, 0, -1), w.vertex(0, 64, 128, 0, 0, -1);
    w.face(floor, 3, v, 3, {0, 1, 2});
    // Billboard (a flare): left out.
    v = w.vertex(32, 32, 32, 0, 0, 1);
    w.face(floor, 4, v, 1, {});
    // Door: brush model 1, a wall quad at x = 96 facing -x.
    v = w.vertex(96, 0, 0, -1, 0, 0);
    w.vertex(96, 0, 128, -1, 0, 0), w.vertex(96, 64, 128, -1, 0, 0), w.vertex(96, 64, 0, -1, 0, 0);
    const int32_t door = w.face(floor, 1, v, 4, {0, 1, 2, 0, 2, 3});
    w.model(0, door);
    w.model(door, 1);
    w.entities =
        "{\n\"classname\" \"worldspawn\"\n\"message\" \"Test Arena\"\n}\n"
        "{\n\"classname\" \"light\"\n\"origin\" \"32 64 96\"\n\"light\" \"200\"\n\"_color\" \"1 0.5 0.5\"\n}\n"
        "{\n\"classname\" \"light\"\n\"origin\" \"64 0 64\"\n}\n"
        "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"32 32 24\"\n\"angle\" \"90\"\n}\n"
        "{\n\"classname\" \"team_CTF_bluespawn\"\n\"origin\" \"-32 0 40\"\n}\n"
        "{\n\"model\" \"*1\"\n\"classname\" \"func_door\"\n}\n";
    return w;
}

struct TempFile {
    fs::path path;
    TempFile(const std::string& name, const std::vector<uint8_t>& bytes)
        : path(fs::temp_directory_path() / ("tetprobe_q3_" + std::to_string(std::random_device{}()) + "_" + name)) {
        std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    ~TempFile() { fs::remove(path); }
};

Quake3Level parse(const std::vector<uint8_t>& bytes) { return parse_quake3_bsp(bytes.data(), bytes.size(), "test.bsp"); }

// The message of the Error the bytes are refused with (fails unless it is Status::scene).
std::string refusal(const std::vector<uint8_t>& bytes) {
    try {
        parse(bytes);
    } catch (const Error& e) {
        CHECK(e.status() == Status::scene);
        return e.what();
    }
    FAIL("the bytes were accepted");
    return "";
}

void set_i32(std::vector<uint8_t>& bytes, size_t at, int32_t v) {
    for (int k = 0; k < 4; ++k) bytes[at + size_t(k)] = uint8_t(uint32_t(v) >> (8 * k));
}
size_t lump_offset(const std::vector<uint8_t>& bytes, int lump) {
    int32_t v;
    std::memcpy(&v, &bytes[8 + 8 * size_t(lump)], 4);
    return size_t(v);
}

std::array<double, 3> normal_of(const Quake3Level& level, size_t t) {
    const float* a = &level.vertices[3 * level.indices[3 * t]];
    const float* b = &level.vertices[3 * level.indices[3 * t + 1]];
    const float* c = &level.vertices[3 * level.indices[3 * t + 2]];
    const double e1[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double e2[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    std::array<double, 3> n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x /= length;
    return n;
}

}  // namespace

TEST_CASE("quake3: the test level imports to exactly its drawn triangles, lights and spawn points", "[quake3]") {
    const Quake3Level level = parse(test_level().bytes());
    const uint32_t patch_triangles = 2 * kQuake3PatchSegments * kQuake3PatchSegments;
    REQUIRE(level.triangle_count() == 2 + patch_triangles + 1 + 2);
    CHECK(level.vertices.size() == 9 * level.triangle_count());
    const Quake3Counts& c = level.counts;
    CHECK(c.faces == 8);
    CHECK(c.polygons == 2);
    CHECK(c.patches == 1);
    CHECK(c.meshes == 1);
    CHECK(c.billboards == 1);
    CHECK(c.sky == 1);
    CHECK(c.liquid_or_fog == 1);
    CHECK(c.nodraw == 1);
    CHECK(c.brush_model_faces == 1);
    CHECK(c.winding_by_normals == level.triangle_count());
    CHECK(level.worldspawn_message == "Test Arena");

    // Q3 (x, y, z) units -> (x, z, -y) / 32 metres; fronts counter-clockwise, on the side the normals give.
    for (size_t t = 0; t < 2; ++t) {  // the floor: y = 0, facing up
        for (int k = 0; k < 3; ++k) CHECK(level.vertices[3 * level.indices[3 * t + size_t(k)] + 1] == 0.0f);
        CHECK(normal_of(level, t)[1] == Approx(1.0));
    }
    const float* first = &level.vertices[0];
    CHECK(first[0] == 0.0f);
    CHECK(first[2] == 0.0f);
    for (size_t t = 2; t < 2 + patch_triangles; ++t) CHECK(normal_of(level, t)[1] > 0.9);  // the patch faces up
    const size_t mesh_triangle = 2 + patch_triangles;
    CHECK(normal_of(level, mesh_triangle)[1] == Approx(-1.0));  // its normals win over its winding
    for (size_t t = mesh_triangle + 1; t < level.triangle_count(); ++t)  // the door faces -x
        CHECK(normal_of(level, t)[0] == Approx(-1.0));

    // The patch: every tessellated vertex on the biquadratic surface, height 64 + rise * B(u) B(v) units with
    // B(t) = 2 t (1 - t) the centre control point's Bernstein weight; corners at 2 m, the top at u = v = 1/2.
    double lowest = INFINITY, highest = -INFINITY;
    for (size_t t = 2; t < 2 + patch_triangles; ++t)
        for (int k = 0; k < 3; ++k) {
            const float* p = &level.vertices[3 * level.indices[3 * t + size_t(k)]];
            const double u = p[0] * 32.0 / 128.0, v = -p[2] * 32.0 / 128.0;
            const double height = (64.0 + kPatchRise * (2 * u * (1 - u)) * (2 * v * (1 - v))) / 32.0;
            CHECK(p[1] == Approx(height).margin(1e-6));
            lowest = std::min(lowest, double(p[1])), highest = std::max(highest, double(p[1]));
        }
    CHECK(lowest == 2.0);
    CHECK(highest == Approx((64.0 + kPatchRise / 4) / 32.0));

    REQUIRE(level.lights.size() == 2);
    CHECK(level.lights[0].position == std::array<double, 3>{{1.0, 3.0, -2.0}});
    CHECK(level.lights[0].light == 200);
    CHECK(level.lights[0].color == std::array<float, 3>{{1.0f, 0.5f, 0.5f}});
    CHECK(level.lights[1].position == std::array<double, 3>{{2.0, 2.0, 0.0}});
    CHECK(level.lights[1].light == 300);  // Q3's default
    CHECK_FALSE(level.lights[0].spot);
    REQUIRE(level.spawn_points.size() == 6);
    CHECK(level.spawn_points == std::vector<float>{1.0f, 0.75f, -1.0f, -1.0f, 1.25f, -0.0f});
}

TEST_CASE("quake3: the scene has the level's mesh, its lights with the stated intensity, a sun and a sky", "[quake3]") {
    const BspWriter w = test_level();
    const TempFile file("level.bsp", w.bytes());
    const Scene scene = load_scene_file(file.path.string());  // by its magic, not its name
    REQUIRE(scene.meshes().size() == 1);
    CHECK(scene.meshes()[0].triangle_count() == parse(w.bytes()).triangle_count());
    CHECK_FALSE(scene.meshes()[0].materials[0].two_sided);
    CHECK(scene.meshes()[0].materials[0].albedo[1] == kQuake3Albedo);
    REQUIRE(scene.lights().size() == 3);
    const Light& red = scene.lights()[0];
    CHECK(red.type == LightType::point);
    CHECK(red.intensity == Approx(200 * kQuake3IntensityPerLight));
    CHECK(red.color[1] == 0.5f);
    // The light ends where its irradiance falls to pi / 255 (q3map's envelope: L * 7500 / d^2 = 1).
    CHECK(red.range == Approx(std::sqrt(200.0 * 7500.0) / 32.0).epsilon(1e-5));
    // Closer than 16 units (half a metre) q3map2 holds the distance at 16: no hot spot next to a light.
    CHECK(red.near_distance == Approx(0.5).epsilon(1e-6));
    CHECK(scene.lights()[1].near_distance == Approx(0.5).epsilon(1e-6));
    CHECK(scene.lights()[2].type == LightType::directional);
    CHECK(scene.lights()[2].direction[1] < 0);  // the sun shines down
    CHECK(scene.sky().kind == SkyKind::color);
}

TEST_CASE("quake3: a spot light aims at its target with the cone its radius gives", "[quake3]") {
    BspWriter w = test_level();
    w.entities += "{\n\"classname\" \"light\"\n\"origin\" \"0 0 128\"\n\"target\" \"t1\"\n\"radius\" \"32\"\n}\n"
                  "{\n\"classname\" \"info_null\"\n\"targetname\" \"t1\"\n\"origin\" \"0 0 0\"\n}\n";
    const Quake3Level level = parse(w.bytes());
    REQUIRE(level.lights.size() == 3);
    const Quake3Light& spot = level.lights[2];
    CHECK(spot.spot);
    CHECK(spot.spot_direction == std::array<double, 3>{{0.0, -1.0, 0.0}});
    CHECK(spot.spot_cos_outer == Approx(128.0 / std::sqrt(128.0 * 128.0 + 32.0 * 32.0)));
}

TEST_CASE("quake3: bad files are refused with a message naming the file and what is wrong", "[quake3]") {
    const std::vector<uint8_t> good = test_level().bytes();
    {
        std::vector<uint8_t> b = good;
        b[0] = 'V';
        CHECK(refusal(b).find("IBSP") != std::string::npos);
        CHECK(refusal(b).find("test.bsp") != std::string::npos);
    }
    CHECK(refusal(test_level().bytes(47)).find("version 47") != std::string::npos);
    CHECK(refusal(std::vector<uint8_t>(good.begin(), good.begin() + 100)).find("truncated") != std::string::npos);
    {
        std::vector<uint8_t> b = good;
        set_i32(b, 8 + 8 * 13 + 4, int32_t(good.size()));  // the faces lump runs past the end
        CHECK(refusal(b).find("faces lump") != std::string::npos);
        CHECK(refusal(b).find("out of range") != std::string::npos);
    }
    {
        std::vector<uint8_t> b = good;
        set_i32(b, 8 + 8 * 10 + 4, 45);  // the vertices lump is not whole records
        CHECK(refusal(b).find("not a multiple") != std::string::npos);
    }
    {
        std::vector<uint8_t> b = good;
        set_i32(b, lump_offset(b, 11) + 4, 9);  // a mesh vertex beyond the floor's 4 vertices
        const std::string m = refusal(b);
        CHECK(m.find("face 0") != std::string::npos);
        CHECK(m.find("mesh vertex 1") != std::string::npos);
    }
    {
        std::vector<uint8_t> b = good;
        set_i32(b, lump_offset(b, 13) + 12, 1000);  // the floor's first vertex beyond the lump
        CHECK(refusal(b).find("vertices 1000 + 4 out of range") != std::string::npos);
    }
    {
        std::vector<uint8_t> b = good;
        set_i32(b, lump_offset(b, 13), 99);  // shader index
        CHECK(refusal(b).find("shader 99 out of range") != std::string::npos);
    }
    {
        std::vector<uint8_t> b = good;
        set_i32(b, lump_offset(b, 13) + 4 * 104 + 96, 4);  // the patch (face 4) 4 control points wide
        CHECK(refusal(b).find("face 4: a patch of 4 x 3") != std::string::npos);
    }
    {
        std::vector<uint8_t> b = good;
        set_i32(b, lump_offset(b, 7) + 40 + 28, 50);  // model 1 holds faces beyond the lump
        CHECK(refusal(b).find("model 1") != std::string::npos);
    }
    {
        BspWriter w = test_level();
        w.entities = "{ \"classname\" \"light\" ";  // an entity that does not end
        CHECK(refusal(w.bytes()).find("entities lump") != std::string::npos);
        w.entities = "\"classname\" \"light\"";  // a key outside an entity
        CHECK(refusal(w.bytes()).find("expected '{'") != std::string::npos);
    }
    // Through the scene file loader (what tp_scene_load_file calls; Status::scene is TP_ERROR_SCENE there).
    static_assert(int(Status::scene) == int(TP_ERROR_SCENE), "the C ABI's status of a bad scene");
    std::vector<uint8_t> b = good;
    b[4] = 45;
    const TempFile file("old.bsp", b);
    try {
        load_scene_file(file.path.string());
        FAIL("an IBSP version 45 file was accepted");
    } catch (const Error& e) {
        CHECK(e.status() == Status::scene);
        CHECK(std::string(e.what()).find(file.path.string()) != std::string::npos);
        CHECK(std::string(e.what()).find("version 45") != std::string::npos);
    }
}

TEST_CASE("quake3: every prefix and random corruptions of a good file are refused or read within bounds", "[quake3]") {
    const std::vector<uint8_t> good = test_level().bytes();
    for (size_t size = 0; size < good.size(); ++size) {
        std::vector<uint8_t> prefix(good.begin(), good.begin() + std::ptrdiff_t(size));  // its own buffer: ASan sees overreads
        CHECK_THROWS_AS(parse(prefix), Error);
    }
    std::mt19937 rng(15);
    size_t accepted = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::vector<uint8_t> b = good;
        for (int flips = 1 + int(rng() % 4); flips > 0; --flips) b[rng() % b.size()] = uint8_t(rng());
        try {
            const Quake3Level level = parse(b);
            for (uint32_t i : level.indices) REQUIRE(i < level.vertices.size() / 3);
            ++accepted;
        } catch (const Error& e) {
            REQUIRE(e.status() == Status::scene);
        }
    }
    CHECK(accepted > 0);  // corruptions of unread bytes (lightmap fields, padding) are harmless
}

TEST_CASE("quake3: patch pieces meet exactly along their shared edge", "[quake3]") {
    // A 5 x 3 grid (two pieces side by side), curved: the pieces' shared column of vertices coincides.
    std::vector<double> positions, normals;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 5; ++c) {
            positions.insert(positions.end(), {double(c), double(r), std::sin(double(c * 3 + r))});
            normals.insert(normals.end(), {0.0, 0.0, 1.0});
        }
    const uint32_t segments = 4;
    const PatchTessellation t = tessellate_quake3_patch(positions.data(), normals.data(), 5, 3, segments);
    const size_t side = segments + 1;
    REQUIRE(t.positions.size() == 3 * 2 * side * side);
    REQUIRE(t.triangles.size() == 3 * 2 * 2 * segments * segments);
    for (size_t j = 0; j < side; ++j)
        for (int a = 0; a < 3; ++a)
            CHECK(t.positions[3 * (j * side + segments) + size_t(a)] == t.positions[3 * (side * side + j * side) + size_t(a)]);
    // Corners of a piece are its corner control points.
    for (int a = 0; a < 3; ++a) CHECK(t.positions[size_t(a)] == positions[size_t(a)]);
}
