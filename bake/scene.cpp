#include "bake/scene.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tetprobe {

namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void scene_error(const std::string& where, const std::string& what) {
    throw Error(Status::scene, where + ": " + what);
}

bool finite3(const float v[3]) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

std::string triple(const float v[3]) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v[0]), double(v[1]), double(v[2]));
    return text;
}

// Twice the area of a triangle against the square of its longest edge: below this the triangle is
// a sliver or a point and is dropped (it cannot be hit reliably and has no stable normal).
constexpr double kDegenerateRatio = 1e-9;

}  // namespace

bool Mesh::emissive() const {
    for (uint32_t m : triangle_materials)
        if (materials[m].emissive()) return true;
    return false;
}

bool Mesh::reflective() const {
    for (uint32_t m : triangle_materials)
        if (materials[m].reflective()) return true;
    return false;
}

bool Sky::black() const {
    if (kind == SkyKind::none) return true;
    for (float c : sh)
        if (c != 0.0f) return false;
    return true;
}

void validate_material(const Material& material, const std::string& where) {
    for (int c = 0; c < 3; ++c) {
        float a = material.albedo[c], e = material.emission[c];
        if (!std::isfinite(a) || a < 0.0f || a > 1.0f)
            scene_error(where, "albedo " + triple(material.albedo.data()) + " is outside [0, 1]");
        if (!std::isfinite(e) || e < 0.0f)
            scene_error(where, "emission " + triple(material.emission.data()) + " is negative or not finite");
    }
}

uint32_t Scene::add_mesh(const float* vertices, size_t vertex_count, const uint32_t* indices,
                         size_t triangle_count, const std::vector<Material>& materials,
                         const uint32_t* triangle_materials, const std::string& label) {
    const uint32_t mesh_index = uint32_t(meshes_.size());
    Mesh mesh;
    mesh.label = label.empty() ? "mesh " + std::to_string(mesh_index) : label;
    const std::string& where = mesh.label;
    if (vertex_count == 0 || !vertices) scene_error(where, "has no vertices");
    if (triangle_count == 0 || !indices) scene_error(where, "has no triangles");
    if (vertex_count > UINT32_MAX) scene_error(where, "has more than 2^32 - 1 vertices");
    if (materials.empty()) scene_error(where, "has no material");
    for (size_t m = 0; m < materials.size(); ++m)
        validate_material(materials[m], where + ", material " + std::to_string(m));

    mesh.vertices.assign(vertices, vertices + 3 * vertex_count);
    mesh.materials = materials;
    for (size_t v = 0; v < vertex_count; ++v)
        if (!finite3(&vertices[3 * v]))
            scene_error(where, "vertex " + std::to_string(v) + " is not finite " + triple(&vertices[3 * v]));

    for (size_t t = 0; t < triangle_count; ++t) {
        const uint32_t* tri = &indices[3 * t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] >= vertex_count)
                scene_error(where, "triangle " + std::to_string(t) + " index " + std::to_string(tri[k]) +
                                       " is out of range (" + std::to_string(vertex_count) + " vertices)");
        uint32_t material = triangle_materials ? triangle_materials[t] : 0;
        if (material >= materials.size())
            scene_error(where, "triangle " + std::to_string(t) + " material " + std::to_string(material) +
                                   " is out of range (" + std::to_string(materials.size()) + " materials)");
        double p[3][3];
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) p[k][a] = vertices[3 * tri[k] + a];
        double e1[3], e2[3], e3[3];
        for (int a = 0; a < 3; ++a) e1[a] = p[1][a] - p[0][a], e2[a] = p[2][a] - p[0][a], e3[a] = p[2][a] - p[1][a];
        double cross[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double twice_area = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
        auto sq = [](const double* e) { return e[0] * e[0] + e[1] * e[1] + e[2] * e[2]; };
        double longest = std::max({sq(e1), sq(e2), sq(e3)});
        if (!(twice_area > kDegenerateRatio * longest)) {
            ++mesh.dropped_triangles;
            continue;
        }
        mesh.indices.insert(mesh.indices.end(), tri, tri + 3);
        mesh.triangle_materials.push_back(material);
    }
    if (mesh.indices.empty())
        scene_error(where, "all " + std::to_string(triangle_count) + " triangles have zero area");

    mesh.bounds_min = {INFINITY, INFINITY, INFINITY};
    mesh.bounds_max = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i : mesh.indices)
        for (int a = 0; a < 3; ++a) {
            mesh.bounds_min[a] = std::min(mesh.bounds_min[a], mesh.vertices[3 * i + a]);
            mesh.bounds_max[a] = std::max(mesh.bounds_max[a], mesh.vertices[3 * i + a]);
        }
    meshes_.push_back(std::move(mesh));
    return mesh_index;
}

uint32_t Scene::mixed_light_count() const {
    uint32_t count = 0;
    for (const Light& light : lights_) count += light.mixed ? 1u : 0u;
    return count;
}

uint32_t Scene::add_light(const LightDescription& in, const std::string& label) {
    const std::string where = label.empty() ? "light " + std::to_string(lights_.size()) : label;
    Light light;
    switch (in.type) {
        case LightType::directional:
        case LightType::point:
        case LightType::spot: light.type = in.type; break;
        default: scene_error(where, "unknown type " + std::to_string(uint32_t(in.type)));
    }
    if (in.mode != LightMode::baked && in.mode != LightMode::realtime && in.mode != LightMode::mixed)
        scene_error(where, "unknown mode " + std::to_string(uint32_t(in.mode)));
    // A mixed light is baked as a realtime one (bounced light only) and gets an occlusion channel.
    light.mixed = in.mode == LightMode::mixed;
    light.realtime = in.mode != LightMode::baked;
    if (light.mixed && mixed_light_count() >= kMaxMixedLights)
        scene_error(where, "a fifth mixed light: occlusion probes hold at most 4 (make it baked or realtime)");
    light.shadows = in.shadows;
    if (!finite3(in.color.data()) || in.color[0] < 0 || in.color[1] < 0 || in.color[2] < 0)
        scene_error(where, "colour " + triple(in.color.data()) + " is negative or not finite");
    if (!std::isfinite(in.intensity) || in.intensity < 0)
        scene_error(where, "intensity " + std::to_string(in.intensity) + " is negative or not finite");
    light.color = in.color;
    light.intensity = in.intensity;

    if (light.type != LightType::point) {
        if (!finite3(in.direction.data())) scene_error(where, "direction is not finite");
        double length = std::sqrt(double(in.direction[0]) * in.direction[0] +
                                  double(in.direction[1]) * in.direction[1] +
                                  double(in.direction[2]) * in.direction[2]);
        if (!(length > 1e-30)) scene_error(where, "direction is zero");
        for (int a = 0; a < 3; ++a) light.direction[a] = in.direction[a] / length;
    }
    if (light.positional()) {
        if (!finite3(in.position.data())) scene_error(where, "position " + triple(in.position.data()) + " is not finite");
        for (int a = 0; a < 3; ++a) light.position[a] = in.position[a];
        if (std::isnan(in.range) || !(in.range > 0))
            scene_error(where, "range " + std::to_string(in.range) + " must be positive (INFINITY = unlimited)");
        light.range = in.range;
        if (!std::isfinite(in.near_distance) || in.near_distance < 0)
            scene_error(where, "near distance " + std::to_string(in.near_distance) + " must be zero or positive and finite");
        light.near_distance = in.near_distance;
    }
    if (light.type == LightType::spot) {
        float inner = in.inner_angle, outer = in.outer_angle;
        if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0 || outer <= 0 || inner > outer ||
            outer > 360)
            scene_error(where, "spot angles must satisfy 0 <= inner <= outer <= 360 degrees (inner " +
                                   std::to_string(inner) + ", outer " + std::to_string(outer) + ")");
        const double half_radians = kPi / 360.0;
        light.cos_inner = std::cos(inner * half_radians);
        light.cos_outer = std::cos(outer * half_radians);
    }
    lights_.push_back(light);
    return uint32_t(lights_.size() - 1);
}

void Scene::set_sky_color(const float rgb[3]) {
    if (!finite3(rgb) || rgb[0] < 0 || rgb[1] < 0 || rgb[2] < 0)
        scene_error("sky", "colour " + triple(rgb) + " is negative or not finite");
    sky_ = Sky();
    sky_.kind = SkyKind::color;
    // Constant radiance c projects onto Y00 = 1 / (2 sqrt(pi)) as c * 2 sqrt(pi).
    const double constant = 2.0 * std::sqrt(kPi);
    for (int c = 0; c < 3; ++c) sky_.sh[9 * c] = float(rgb[c] * constant);
}

void Scene::set_sky_sh(const float sh[27]) {
    for (int i = 0; i < 27; ++i)
        if (!std::isfinite(sh[i])) scene_error("sky", "SH coefficient " + std::to_string(i) + " is not finite");
    sky_ = Sky();
    sky_.kind = SkyKind::sh;
    std::copy(sh, sh + 27, sky_.sh.begin());
}

void Scene::set_probes(const float* positions, size_t count, size_t stride_bytes) {
    if (stride_bytes == 0) stride_bytes = 3 * sizeof(float);
    std::vector<float> probes(3 * count);
    for (size_t i = 0; i < count; ++i) {
        const float* p = reinterpret_cast<const float*>(reinterpret_cast<const char*>(positions) + i * stride_bytes);
        if (!finite3(p)) scene_error("probe " + std::to_string(i), "position " + triple(p) + " is not finite");
        std::copy(p, p + 3, &probes[3 * i]);
    }
    probes_ = std::move(probes);
}

void Scene::set_playable_seeds(const float* positions, size_t count, size_t stride_bytes) {
    if (stride_bytes == 0) stride_bytes = 3 * sizeof(float);
    std::vector<float> seeds(3 * count);
    for (size_t i = 0; i < count; ++i) {
        const float* p = reinterpret_cast<const float*>(reinterpret_cast<const char*>(positions) + i * stride_bytes);
        if (!finite3(p)) scene_error("playable seed " + std::to_string(i), "position " + triple(p) + " is not finite");
        std::copy(p, p + 3, &seeds[3 * i]);
    }
    playable_seeds_ = std::move(seeds);
}

void Scene::set_up(UpAxis up) {
    if (!is_axis(up))
        throw Error(Status::invalid_argument, "up must be one of the six axis directions (TP_UP_POS_X ... TP_UP_NEG_Z), got " +
                                                  std::to_string(uint32_t(up)));
    up_ = up;
}

Scene Scene::meshes_turned(const AxisTurn& turn) const {
    Scene turned;
    turned.meshes_ = meshes_;
    for (Mesh& mesh : turned.meshes_) {
        for (size_t v = 0; v < mesh.vertices.size(); v += 3) turn.apply(&mesh.vertices[v], &mesh.vertices[v]);
        float lo[3], hi[3];
        turn.apply(mesh.bounds_min.data(), lo);
        turn.apply(mesh.bounds_max.data(), hi);
        for (int a = 0; a < 3; ++a) {
            mesh.bounds_min[a] = std::min(lo[a], hi[a]);
            mesh.bounds_max[a] = std::max(lo[a], hi[a]);
        }
    }
    turned.up_ = turn.apply(up_);
    turned.playable_seeds_ = playable_seeds_;
    for (size_t s = 0; s < turned.playable_seeds_.size(); s += 3) turn.apply(&turned.playable_seeds_[s], &turned.playable_seeds_[s]);
    return turned;
}

uint32_t Scene::dropped_triangles() const {
    uint32_t dropped = 0;
    for (const Mesh& m : meshes_) dropped += m.dropped_triangles;
    return dropped;
}

}  // namespace tetprobe
