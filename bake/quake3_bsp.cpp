#include "bake/quake3_bsp.h"

#include "bake/quake3_entities.h"
#include "bake/quake3_patch.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <strings.h>

namespace tetprobe {

namespace {

// The file's layout (little-endian): "IBSP", version 46, then 17 lumps of (offset, length).
constexpr int kVersion = 46;
constexpr int kLumpCount = 17;
constexpr size_t kHeaderBytes = 8 + 8 * kLumpCount;
// Only what is read is checked: the fog a face names is not (levels in the wild name fog 0 without a
// fogs lump; fog volumes are left out by their shaders' contents instead).
enum Lump { kEntities = 0, kShaders = 1, kModels = 7, kVertices = 10, kMeshVertices = 11, kFaces = 13 };
constexpr size_t kShaderBytes = 72;   // char name[64]; int surface_flags; int contents
constexpr size_t kModelBytes = 40;    // float mins[3], maxs[3]; int face, faces; int brush, brushes
constexpr size_t kVertexBytes = 44;   // float position[3], st[2], lightmap_st[2], normal[3]; byte color[4]
constexpr size_t kFaceBytes = 104;    // see Face

// Shader flags (q3map's surfaceflags.h) that decide what is drawn and what lets light through.
constexpr int32_t kSurfaceSky = 0x4, kSurfaceNodraw = 0x80;
constexpr int32_t kContentsSolid = 0x1, kContentsLava = 0x8, kContentsSlime = 0x10, kContentsWater = 0x20,
                  kContentsFog = 0x40;

enum FaceType { kPolygon = 1, kPatch = 2, kMesh = 3, kBillboard = 4 };

struct Face {
    int32_t shader, type, first_vertex, vertex_count, first_mesh_vertex, mesh_vertex_count;
    int32_t patch_width, patch_height;
};

class Bytes {
public:
    Bytes(const uint8_t* data, size_t size, const std::string& name) : data_(data), size_(size), name_(name) {}

    int32_t i32(size_t at) const {
        uint32_t v = uint32_t(data_[at]) | uint32_t(data_[at + 1]) << 8 | uint32_t(data_[at + 2]) << 16 |
                     uint32_t(data_[at + 3]) << 24;
        int32_t s;
        std::memcpy(&s, &v, sizeof s);
        return s;
    }
    float f32(size_t at) const {
        const uint32_t v = uint32_t(i32(at));
        float f;
        std::memcpy(&f, &v, sizeof f);
        return f;
    }
    [[noreturn]] void fail(const std::string& what) const { throw Error(Status::scene, name_ + ": " + what); }

    const uint8_t* data() const { return data_; }
    size_t size() const { return size_; }

private:
    const uint8_t* data_;
    size_t size_;
    const std::string& name_;
};

const char* lump_name(int lump) {
    static const char* const names[kLumpCount] = {"entities", "shaders",  "planes",     "nodes",   "leafs",   "leaf faces",
                                                  "leaf brushes", "models", "brushes",  "brush sides", "vertices",
                                                  "mesh vertices", "fogs",  "faces",     "lightmaps", "light grid",
                                                  "visibility"};
    return names[lump];
}

struct LumpRange {
    size_t offset = 0, count = 0;
};

// The lump's records, checked to lie inside the file and to hold whole records.
LumpRange lump(const Bytes& b, int which, size_t record) {
    const int32_t offset = b.i32(8 + 8 * size_t(which)), length = b.i32(12 + 8 * size_t(which));
    const std::string what = std::string("the ") + lump_name(which) + " lump";
    if (offset < 0 || length < 0)
        b.fail(what + " has a negative offset or length (" + std::to_string(offset) + ", " + std::to_string(length) + ")");
    if (uint64_t(offset) + uint64_t(length) > b.size())
        b.fail(what + " (bytes " + std::to_string(offset) + " to " + std::to_string(uint64_t(offset) + uint64_t(length)) +
               ") is out of range: the file has " + std::to_string(b.size()) + " bytes (truncated?)");
    if (size_t(length) % record != 0)
        b.fail(what + " has " + std::to_string(length) + " bytes, not a multiple of its " + std::to_string(record) +
               "-byte records");
    return {size_t(offset), size_t(length) / record};
}

std::string face_where(size_t f) { return "face " + std::to_string(f) + ": "; }

// Q3 (x, y, z) z-up units to y-up metres.
void to_metres(const double q[3], double out[3]) {
    out[0] = q[0] / kQuake3UnitsPerMetre;
    out[1] = q[2] / kQuake3UnitsPerMetre;
    out[2] = -q[1] / kQuake3UnitsPerMetre;
}

class LevelBuilder {
public:
    LevelBuilder(const Bytes& b, Quake3Level& level) : b_(b), level_(level) {
        vertices_ = lump(b, kVertices, kVertexBytes);
        mesh_vertices_ = lump(b, kMeshVertices, 4);
    }

    // Control point or vertex v (checked by the caller): Q3 position and normal.
    void vertex(size_t v, double position[3], double normal[3]) const {
        const size_t at = vertices_.offset + v * kVertexBytes;
        for (int a = 0; a < 3; ++a) position[a] = b_.f32(at + 4 * size_t(a)), normal[a] = b_.f32(at + 28 + 4 * size_t(a));
    }

    void check_vertices(size_t f, const Face& face) const {
        if (face.first_vertex < 0 || face.vertex_count < 0 ||
            uint64_t(face.first_vertex) + uint64_t(face.vertex_count) > vertices_.count)
            b_.fail(face_where(f) + "vertices " + std::to_string(face.first_vertex) + " + " +
                    std::to_string(face.vertex_count) + " out of range (the vertices lump holds " +
                    std::to_string(vertices_.count) + ")");
        for (int32_t k = 0; k < face.vertex_count; ++k) {
            double p[3], n[3];
            vertex(size_t(face.first_vertex) + size_t(k), p, n);
            for (int a = 0; a < 3; ++a)
                if (!std::isfinite(p[a]) || !std::isfinite(n[a]))
                    b_.fail(face_where(f) + "vertex " + std::to_string(face.first_vertex + k) + " is not finite");
        }
    }

    // A polygon's or mesh's triangle list: mesh vertices are offsets from the face's first vertex.
    void add_triangle_list(size_t f, const Face& face) {
        check_vertices(f, face);
        if (face.first_mesh_vertex < 0 || face.mesh_vertex_count < 0 ||
            uint64_t(face.first_mesh_vertex) + uint64_t(face.mesh_vertex_count) > mesh_vertices_.count)
            b_.fail(face_where(f) + "mesh vertices " + std::to_string(face.first_mesh_vertex) + " + " +
                    std::to_string(face.mesh_vertex_count) + " out of range (the mesh vertices lump holds " +
                    std::to_string(mesh_vertices_.count) + ")");
        if (face.mesh_vertex_count % 3 != 0)
            b_.fail(face_where(f) + std::to_string(face.mesh_vertex_count) + " mesh vertices, not whole triangles");
        for (int32_t t = 0; t < face.mesh_vertex_count; t += 3) {
            double p[3][3], n[3][3];
            for (int k = 0; k < 3; ++k) {
                const int32_t offset = b_.i32(mesh_vertices_.offset + 4 * (size_t(face.first_mesh_vertex) + size_t(t + k)));
                if (offset < 0 || offset >= face.vertex_count)
                    b_.fail(face_where(f) + "mesh vertex " + std::to_string(face.first_mesh_vertex + t + k) + " (" +
                            std::to_string(offset) + ") is outside the face's " + std::to_string(face.vertex_count) +
                            " vertices");
                vertex(size_t(face.first_vertex) + size_t(offset), p[k], n[k]);
            }
            add_triangle(p, n);
        }
    }

    void add_patch(size_t f, const Face& face) {
        check_vertices(f, face);
        const int32_t w = face.patch_width, h = face.patch_height;
        if (w < 3 || h < 3 || w % 2 == 0 || h % 2 == 0 || w > 65 || h > 65)
            b_.fail(face_where(f) + "a patch of " + std::to_string(w) + " x " + std::to_string(h) +
                    " control points (each must be odd, 3 to 65)");
        if (int64_t(w) * h != face.vertex_count)
            b_.fail(face_where(f) + "a patch of " + std::to_string(w) + " x " + std::to_string(h) + " control points has " +
                    std::to_string(face.vertex_count) + " vertices");
        std::vector<double> positions(3 * size_t(face.vertex_count)), normals(positions.size());
        for (int32_t k = 0; k < face.vertex_count; ++k)
            vertex(size_t(face.first_vertex) + size_t(k), &positions[3 * size_t(k)], &normals[3 * size_t(k)]);
        const PatchTessellation mesh =
            tessellate_quake3_patch(positions.data(), normals.data(), w, h, kQuake3PatchSegments);
        for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
            double p[3][3], n[3][3];
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a)
                    p[k][a] = mesh.positions[3 * mesh.triangles[t + k] + a], n[k][a] = mesh.normals[3 * mesh.triangles[t + k] + a];
            add_triangle(p, n);
        }
    }

private:
    // Appends one triangle (Q3 coordinates), front side counter-clockwise (see quake3_bsp.h).
    void add_triangle(const double p[3][3], const double n[3][3]) {
        double e1[3], e2[3], s[3];
        for (int a = 0; a < 3; ++a) e1[a] = p[1][a] - p[0][a], e2[a] = p[2][a] - p[0][a], s[a] = n[0][a] + n[1][a] + n[2][a];
        const double g[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double agreement = g[0] * s[0] + g[1] * s[1] + g[2] * s[2];
        bool flip;
        if (agreement != 0) {
            flip = agreement < 0;
            ++level_.counts.winding_by_normals;
        } else {
            flip = true;  // Q3 winds clockwise seen from the front
            ++level_.counts.winding_by_q3;
        }
        const uint32_t first = uint32_t(level_.vertices.size() / 3);
        for (int k = 0; k < 3; ++k) {
            double m[3];
            to_metres(p[k], m);
            for (double c : m) level_.vertices.push_back(float(c));
        }
        level_.indices.push_back(first);
        level_.indices.push_back(flip ? first + 2 : first + 1);
        level_.indices.push_back(flip ? first + 1 : first + 2);
    }

    const Bytes& b_;
    Quake3Level& level_;
    LumpRange vertices_, mesh_vertices_;
};

Face read_face(const Bytes& b, size_t at) {
    Face f;
    f.shader = b.i32(at);
    f.type = b.i32(at + 8);
    f.first_vertex = b.i32(at + 12);
    f.vertex_count = b.i32(at + 16);
    f.first_mesh_vertex = b.i32(at + 20);
    f.mesh_vertex_count = b.i32(at + 24);
    f.patch_width = b.i32(at + 96);
    f.patch_height = b.i32(at + 100);
    return f;
}

bool is_spawn_point(const std::string& classname) {
    static const char* const names[] = {"info_player_deathmatch", "info_player_start",   "team_CTF_redplayer",
                                        "team_CTF_blueplayer",    "team_CTF_redspawn",   "team_CTF_bluespawn"};
    for (const char* n : names)
        if (strcasecmp(classname.c_str(), n) == 0) return true;
    return false;
}

double number_or(const Quake3Entity& e, const char* key, double fallback) {
    const std::string* v = e.find(key);
    if (!v) return fallback;
    char* end = nullptr;
    const double x = std::strtod(v->c_str(), &end);
    return end != v->c_str() && std::isfinite(x) ? x : fallback;
}

void read_entities(const Bytes& b, Quake3Level& level, const std::string& name) {
    const LumpRange text = lump(b, kEntities, 1);
    const std::vector<Quake3Entity> entities =
        parse_quake3_entities(reinterpret_cast<const char*>(b.data() + text.offset), text.count, name);
    auto where = [&](const Quake3Entity& e) { return "entity at byte " + std::to_string(e.offset) + " of the entities lump"; };
    for (const Quake3Entity& e : entities) {
        const std::string* classname = e.find("classname");
        if (!classname) continue;
        if (strcasecmp(classname->c_str(), "worldspawn") == 0) {
            if (const std::string* message = e.find("message")) level.worldspawn_message = *message;
            continue;
        }
        const bool light = strcasecmp(classname->c_str(), "light") == 0;
        if (!light && !is_spawn_point(*classname)) continue;
        double q[3] = {0, 0, 0}, origin[3];
        if (const std::string* o = e.find("origin"))
            if (!parse_quake3_vector(*o, q)) b.fail(where(e) + ": origin \"" + *o + "\" is not three numbers");
        to_metres(q, origin);
        if (!light) {
            for (double c : origin) level.spawn_points.push_back(float(c));
            continue;
        }
        Quake3Light l;
        for (int a = 0; a < 3; ++a) l.position[a] = origin[a];
        l.light = number_or(e, "light", number_or(e, "_light", 300.0));
        if (const std::string* c = e.find("_color")) {
            double rgb[3];
            if (!parse_quake3_vector(*c, rgb)) b.fail(where(e) + ": _color \"" + *c + "\" is not three numbers");
            const double top = std::max(rgb[0], std::max(rgb[1], rgb[2]));
            if (top > 0)
                for (int k = 0; k < 3; ++k) l.color[k] = float(std::max(0.0, rgb[k]) / top);
        }
        l.linear = (int(number_or(e, "spawnflags", 0)) & 1) != 0;
        if (const std::string* target = e.find("target")) {
            for (const Quake3Entity& t : entities) {
                const std::string* tn = t.find("targetname");
                const std::string* to = t.find("origin");
                double tq[3], tm[3];
                if (!tn || *tn != *target || !to || !parse_quake3_vector(*to, tq)) continue;
                to_metres(tq, tm);
                double d[3], length = 0;
                for (int a = 0; a < 3; ++a) d[a] = tm[a] - origin[a], length += d[a] * d[a];
                length = std::sqrt(length);
                if (!(length > 0)) break;
                const double radius = number_or(e, "radius", 64.0) / kQuake3UnitsPerMetre;
                l.spot = true;
                for (int a = 0; a < 3; ++a) l.spot_direction[a] = d[a] / length;
                l.spot_cos_outer = length / std::sqrt(length * length + radius * radius);
                break;
            }
        }
        level.lights.push_back(l);
    }
}

}  // namespace

bool looks_like_quake3_bsp(const uint8_t* data, size_t size) { return size >= 4 && std::memcmp(data, "IBSP", 4) == 0; }

Quake3Level parse_quake3_bsp(const uint8_t* data, size_t size, const std::string& name) {
    const Bytes b(data, size, name);
    if (size < 8 || std::memcmp(data, "IBSP", 4) != 0)
        b.fail("not a Quake 3 BSP level (it does not start with \"IBSP\")");
    if (b.i32(4) != kVersion)
        b.fail("IBSP version " + std::to_string(b.i32(4)) + " is not supported (only 46, Quake 3 and OpenArena)");
    if (size < kHeaderBytes)
        b.fail("truncated: " + std::to_string(size) + " bytes, shorter than the " + std::to_string(kHeaderBytes) +
               "-byte header");

    Quake3Level level;
    level.name = name;
    const LumpRange shaders = lump(b, kShaders, kShaderBytes);
    const LumpRange models = lump(b, kModels, kModelBytes);
    const LumpRange faces = lump(b, kFaces, kFaceBytes);
    LevelBuilder builder(b, level);

    // Faces from model 1 on belong to brush models; each model's range must lie in the faces lump.
    std::vector<uint8_t> brush_model(faces.count, 0);
    for (size_t m = 0; m < models.count; ++m) {
        const int32_t first = b.i32(models.offset + m * kModelBytes + 24), count = b.i32(models.offset + m * kModelBytes + 28);
        if (first < 0 || count < 0 || uint64_t(first) + uint64_t(count) > faces.count)
            b.fail("model " + std::to_string(m) + ": faces " + std::to_string(first) + " + " + std::to_string(count) +
                   " out of range (the faces lump holds " + std::to_string(faces.count) + ")");
        if (m > 0) std::fill(brush_model.begin() + first, brush_model.begin() + first + count, uint8_t(1));
    }

    Quake3Counts& counts = level.counts;
    counts.faces = uint32_t(faces.count);
    for (size_t f = 0; f < faces.count; ++f) {
        const Face face = read_face(b, faces.offset + f * kFaceBytes);
        if (face.shader < 0 || size_t(face.shader) >= shaders.count)
            b.fail(face_where(f) + "shader " + std::to_string(face.shader) + " out of range (the shaders lump holds " +
                   std::to_string(shaders.count) + ")");
        if (face.type < kPolygon || face.type > kBillboard)
            b.fail(face_where(f) + "unknown face type " + std::to_string(face.type));
        const size_t shader_at = shaders.offset + size_t(face.shader) * kShaderBytes;
        const int32_t surface = b.i32(shader_at + 64), contents = b.i32(shader_at + 68);
        if (face.type == kBillboard) { ++counts.billboards; continue; }
        if (surface & kSurfaceSky) { ++counts.sky; continue; }
        if (surface & kSurfaceNodraw) { ++counts.nodraw; continue; }
        if (contents & (kContentsWater | kContentsSlime | kContentsLava | kContentsFog)) { ++counts.liquid_or_fog; continue; }
        if (!(contents & kContentsSolid)) { ++counts.nonsolid; continue; }
        if (face.type == kPatch) {
            builder.add_patch(f, face);
            ++counts.patches;
        } else {
            builder.add_triangle_list(f, face);
            ++(face.type == kPolygon ? counts.polygons : counts.meshes);
        }
        counts.brush_model_faces += brush_model[f];
    }
    read_entities(b, level, name);
    return level;
}

Quake3Level read_quake3_bsp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(Status::io, "cannot read level file '" + path + "'");
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw Error(Status::io, "cannot read level file '" + path + "'");
    return parse_quake3_bsp(bytes.data(), bytes.size(), path);
}

}  // namespace tetprobe
