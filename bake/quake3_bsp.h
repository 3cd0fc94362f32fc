// Quake 3 levels (IBSP version 46, as id Tech 3 and OpenArena ship them): the drawn surfaces as
// one-sided triangles, the light entities and the spawn points, in y-up metres. Reading is safe for
// untrusted bytes: every lump, count and index is checked before it is used, and a bad file throws
// Error(Status::scene) with a message naming the file and what is wrong.
//
// Units: Q3's z-up units become y-up metres, (x, y, z) -> (x, z, -y) / 32 (a rotation, so windings
// keep their sense): a player is 56 units tall, 1.75 m at 32 units a metre, and a standard
// 128-unit door is 4 m.
//
// Surfaces kept: polygons and meshes (their triangle lists) and Bezier patches (each biquadratic
// 3 x 3 piece of a patch's control grid cut into kQuake3PatchSegments x kQuake3PatchSegments quads,
// two triangles each), of the world and of every brush model (doors, platforms) where the map
// places them. Left out: billboards (flares), faces whose shader is sky (SURF_SKY) or not drawn
// (SURF_NODRAW), and faces whose contents are not solid (water, slime, lava, fog, and effect
// surfaces such as light beams marked nonsolid), so that sky and water let light through.
// A triangle's front (counter-clockwise) side is the side its stored vertex normals point to,
// the side Q3 draws and lights; where they do not decide (they sum to a vector perpendicular
// to the triangle), Q3's own winding decides (clockwise seen from the front).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tetprobe {

constexpr double kQuake3UnitsPerMetre = 32.0;
constexpr uint32_t kQuake3PatchSegments = 8;

// A Q3 `light` entity, converted to metres (the lighting conventions are in bake/quake3_scene.h).
struct Quake3Light {
    std::array<double, 3> position{};
    double light = 300;                    // the `light` (or `_light`) key: q3map's brightness
    std::array<float, 3> color{{1, 1, 1}};  // `_color`, scaled so its largest component is 1
    bool linear = false;                    // spawnflags 1: q3map's linear falloff
    bool spot = false;                      // aimed at a `target` entity
    std::array<double, 3> spot_direction{{0, -1, 0}};  // unit, the direction light travels
    double spot_cos_outer = 0;              // cosine of the cone's half angle (`radius` at the target)
};

struct Quake3Counts {
    uint32_t faces = 0;            // every face of the faces lump
    uint32_t polygons = 0, meshes = 0, patches = 0, billboards = 0;  // kept faces by type (billboards: left out)
    uint32_t brush_model_faces = 0;  // kept faces belonging to a brush model (model 1 and up)
    uint32_t sky = 0, nodraw = 0, liquid_or_fog = 0, nonsolid = 0;  // left-out faces by reason
    uint32_t winding_by_normals = 0, winding_by_q3 = 0;  // how each triangle's front was decided
};

struct Quake3Level {
    std::string name;                  // the file's name, for messages and reports
    std::vector<float> vertices;       // 3 per vertex, y-up metres
    std::vector<uint32_t> indices;     // 3 per triangle, counter-clockwise seen from the front
    std::vector<Quake3Light> lights;
    std::vector<float> spawn_points;   // 3 per point: info_player_* and the CTF team spawns, metres
    std::string worldspawn_message;    // the worldspawn's `message` (the level's title), if any
    Quake3Counts counts;

    size_t triangle_count() const { return indices.size() / 3; }
};

// Reads a level from the bytes of a .bsp file; `name` names it in messages.
Quake3Level parse_quake3_bsp(const uint8_t* data, size_t size, const std::string& name);

// Reads a .bsp file. A file that cannot be read throws Error(Status::io).
Quake3Level read_quake3_bsp(const std::string& path);

// True when the bytes start like a Q3 BSP (the magic "IBSP"), whatever the version.
bool looks_like_quake3_bsp(const uint8_t* data, size_t size);

}  // namespace tetprobe
