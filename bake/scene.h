// The scene a lighting bake reads: triangle meshes with materials, lights, a sky and probe positions.
// Everything is validated when added, so a bake never sees a NaN, an index out of range or a
// degenerate triangle; messages name what is wrong and where (mesh, triangle, vertex, light).
#pragma once

#include "bake/up_axis.h"
#include "core/option_defaults.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tetprobe {

// Occlusion probes have one byte per mixed light, four a probe.
constexpr uint32_t kMaxMixedLights = 4;

struct Material {
    std::array<float, 3> albedo{{kDefaultAlbedo, kDefaultAlbedo, kDefaultAlbedo}};  // Lambertian reflectance in [0, 1]
    std::array<float, 3> emission{{0.0f, 0.0f, 0.0f}};  // emitted radiance, >= 0
    bool two_sided = false;                              // one-sided faces are black from behind

    bool emissive() const { return emission[0] > 0 || emission[1] > 0 || emission[2] > 0; }
    bool reflective() const { return albedo[0] > 0 || albedo[1] > 0 || albedo[2] > 0; }
};

struct Mesh {
    std::string label;                         // "mesh 2 ('floor')": used in messages
    std::vector<float> vertices;               // 3 per vertex, world units
    std::vector<uint32_t> indices;             // 3 per kept triangle
    std::vector<uint32_t> triangle_materials;  // one per kept triangle, into materials
    std::vector<Material> materials;
    uint32_t dropped_triangles = 0;            // zero-area triangles left out
    std::array<float, 3> bounds_min{}, bounds_max{};

    size_t triangle_count() const { return indices.size() / 3; }
    bool emissive() const;    // some kept triangle emits
    bool reflective() const;  // some kept triangle has a non-zero albedo
};

enum class LightType : uint32_t { directional = 0, point = 1, spot = 2 };

// What the engine does with a light: baked (its direct and bounced light go into the probes),
// realtime (the engine draws its direct light: only the bounced light is baked) or mixed (realtime
// direct light with baked shadows: baked as realtime, plus an occlusion channel).
enum class LightMode : uint32_t { baked = 0, realtime = 1, mixed = 2 };

// A light as a caller describes it (the C ABI's tp_light, a scene file's light); Scene::add_light
// validates it and keeps it as a Light.
struct LightDescription {
    LightType type = LightType::point;
    LightMode mode = LightMode::baked;
    bool shadows = true;
    std::array<float, 3> color{{kDefaultLightColor, kDefaultLightColor, kDefaultLightColor}};
    float intensity = kDefaultLightIntensity;  // directional: irradiance; point, spot: radiant intensity
    std::array<float, 3> position{{0, 0, 0}};  // point, spot
    // Directional, spot: the direction light travels, of any non-zero length.
    std::array<float, 3> direction{{kDefaultLightDirection[0], kDefaultLightDirection[1], kDefaultLightDirection[2]}};
    float range = kDefaultLightRange;            // point, spot: no light beyond (infinity = unlimited)
    // Point, spot: closer than this the irradiance stays at its value at this distance instead of growing
    // without bound (0: pure inverse square). A light compiler's near-field clamp, e.g. q3map2's 16 units.
    float near_distance = 0;
    float inner_angle = kDefaultSpotInnerAngle;  // spot: full cone angle in degrees with full intensity
    float outer_angle = kDefaultSpotOuterAngle;  // spot: full cone angle in degrees beyond which there is no light
};

// A validated light, as the bake reads it.
struct Light {
    LightType type = LightType::point;
    bool realtime = false;  // only its bounced light is baked (mixed lights too)
    bool mixed = false;     // realtime direct light with baked shadows: one occlusion channel
    bool shadows = true;
    std::array<float, 3> color{{1, 1, 1}};
    float intensity = 1.0f;                     // directional: irradiance; point, spot: radiant intensity
    std::array<double, 3> position{{0, 0, 0}};  // point, spot
    std::array<double, 3> direction{{0, -1, 0}};// directional, spot: unit, the direction light travels
    double range = 0;                           // point, spot: no light beyond (infinity = unlimited)
    double near_distance = 0;                   // point, spot: inverse square evaluated at no less than this
    double cos_inner = 1, cos_outer = 0;        // spot: cosines of the half angles of the cones

    bool positional() const { return type != LightType::directional; }
};

enum class SkyKind { none, color, sh };

struct Sky {
    SkyKind kind = SkyKind::none;
    std::array<float, 27> sh{};  // radiance as SH (a colour is its constant term)

    bool black() const;
};

class Scene {
public:
    // Validates and adds a mesh; returns its index. label names the mesh in messages (for example
    // "scene.json: mesh 2 ('floor')"); empty means "mesh N". NaN vertices, indices or
    // triangle materials out of range, invalid materials and meshes without a single non-degenerate
    // triangle throw Error(Status::scene); zero-area triangles are dropped and counted.
    uint32_t add_mesh(const float* vertices, size_t vertex_count, const uint32_t* indices,
                      size_t triangle_count, const std::vector<Material>& materials,
                      const uint32_t* triangle_materials, const std::string& label = "");
    // Validates and adds a light (known type and mode, non-negative finite intensity and colour, a
    // non-zero direction, positive range, spot angles ordered, at most 4 mixed lights); returns its
    // index. label names it in messages ("light N" when empty). Throws Error(Status::scene).
    uint32_t add_light(const LightDescription& light, const std::string& label = "");
    void set_sky_color(const float rgb[3]);
    void set_sky_sh(const float sh[27]);
    void set_probes(const float* positions, size_t count, size_t stride_bytes = 0);
    // Points known to be in the playable space (a level's spawn points): automatic placement keeps only
    // candidates connected to them (bake/placement_candidates.h). 3 floats each, world; finite.
    void set_playable_seeds(const float* positions, size_t count, size_t stride_bytes = 0);
    // Which way is up (+y unless set): placement's walkable mode stands probes along it. Throws
    // Error(Status::invalid_argument) for anything but one of the six axis directions.
    void set_up(UpAxis up);
    // What an import from a file left out or converted (a camera, a texture, a unit), one line each.
    void add_note(const std::string& note) { notes_.push_back(note); }

    const std::vector<Mesh>& meshes() const { return meshes_; }
    const std::vector<Light>& lights() const { return lights_; }
    const Sky& sky() const { return sky_; }
    const std::vector<float>& probes() const { return probes_; }
    size_t probe_count() const { return probes_.size() / 3; }
    const std::vector<float>& playable_seeds() const { return playable_seeds_; }
    UpAxis up() const { return up_; }
    const std::vector<std::string>& notes() const { return notes_; }
    uint32_t dropped_triangles() const;
    uint32_t mixed_light_count() const;
    // True when there is nothing that emits light or occludes it: no mesh, no light, no sky.
    bool empty() const { return meshes_.empty() && lights_.empty() && sky_.kind == SkyKind::none; }
    // The same meshes turned exactly by `turn` (their bounds too), and up and the playable seeds turned with
    // them; no lights, sky, probes or notes: what geometric tests (placement's floors) read in another frame.
    Scene meshes_turned(const AxisTurn& turn) const;

private:
    std::vector<Mesh> meshes_;
    std::vector<Light> lights_;
    Sky sky_;
    std::vector<float> probes_;
    std::vector<float> playable_seeds_;
    UpAxis up_ = UpAxis::pos_y;
    std::vector<std::string> notes_;
};

// Checks a material, throwing Error(Status::scene) naming `where` when it is invalid.
void validate_material(const Material& material, const std::string& where);

}  // namespace tetprobe
