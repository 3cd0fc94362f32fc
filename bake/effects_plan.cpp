#include "bake/effects_plan.h"

#include "bake/inside_test.h"
#include "core/error.h"
#include "core/shadow_caster_volume.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tetprobe {

namespace {

double distance_to_box(const std::array<double, 3>& p, const std::array<float, 3>& lo, const std::array<float, 3>& hi) {
    double sum = 0.0;
    for (int a = 0; a < 3; ++a) {
        double d = std::max({double(lo[a]) - p[a], 0.0, p[a] - double(hi[a])});
        sum += d * d;
    }
    return std::sqrt(sum);
}

// Whether a light can light some mesh at all (a positional light's range may end before any).
bool reaches_a_mesh(const Light& light, const Scene& scene) {
    if (!light.positional()) return !scene.meshes().empty();
    for (const Mesh& mesh : scene.meshes())
        if (distance_to_box(light.position, mesh.bounds_min, mesh.bounds_max) <= light.range) return true;
    return false;
}

bool reaches_a_probe(const Light& light, const std::vector<float>& positions) {
    if (!light.positional() || std::isinf(light.range)) return !positions.empty();
    for (size_t i = 0; i + 2 < positions.size(); i += 3) {
        double dx = positions[i] - light.position[0], dy = positions[i + 1] - light.position[1],
               dz = positions[i + 2] - light.position[2];
        if (dx * dx + dy * dy + dz * dz <= light.range * light.range) return true;
    }
    return false;
}

std::string count_of(uint32_t n, const char* singular, const char* plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

}  // namespace

std::vector<std::array<double, 4>> probe_region_planes(const std::vector<float>& positions) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double magnitude = 0.0;
    for (size_t i = 0; i < positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], double(positions[i]));
        hi[i % 3] = std::max(hi[i % 3], double(positions[i]));
        magnitude = std::max(magnitude, std::abs(double(positions[i])));
    }
    double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
    // Wide enough for a flat set to bound a volume and for the float rounding of the positions.
    double pad = std::max(1e-4 * diagonal, 1e-6 * (1.0 + magnitude));
    std::vector<std::array<double, 4>> planes;
    for (int a = 0; a < 3; ++a) {
        std::array<double, 4> low{{0, 0, 0, -(lo[a] - pad)}}, high{{0, 0, 0, hi[a] + pad}};
        low[a] = 1.0;    // x_a >= lo - pad
        high[a] = -1.0;  // x_a <= hi + pad
        planes.push_back(low);
        planes.push_back(high);
    }
    return planes;
}

EffectsPlan derive_effects_plan(const Scene& scene, const std::vector<float>& positions, uint32_t bounces,
                                bool culling) {
    EffectsPlan plan;
    const std::vector<Light>& lights = scene.lights();
    plan.lights = uint32_t(lights.size());
    plan.meshes = uint32_t(scene.meshes().size());
    plan.sky = !scene.sky().black();
    bool reflective = false;
    for (uint32_t m = 0; m < plan.meshes; ++m) {
        if (scene.meshes()[m].emissive()) plan.emissive_meshes.push_back(m);
        reflective = reflective || scene.meshes()[m].reflective();
    }

    bool light_reaches_a_mesh = false;
    for (uint32_t l = 0; l < plan.lights; ++l) {
        const Light& light = lights[l];
        light_reaches_a_mesh = light_reaches_a_mesh || reaches_a_mesh(light, scene);
        if (light.realtime) ++plan.realtime_lights;
        else if (reaches_a_probe(light, positions)) plan.direct_lights.push_back(l);
        else ++plan.out_of_range_lights;
    }
    const bool something_to_bounce = plan.sky || !plan.emissive_meshes.empty() || light_reaches_a_mesh;
    plan.bounces = bounces > 0 && reflective && something_to_bounce ? bounces : 0;
    if (plan.bounces > 0)
        for (uint32_t l = 0; l < plan.lights; ++l)
            if (reaches_a_mesh(lights[l], scene)) plan.bounce_lights.push_back(l);

    plan.occluders.resize(lights.size());
    for (uint32_t l : plan.bounce_lights) plan.shadows = plan.shadows || lights[l].shadows;
    std::vector<Plane> region;
    for (const std::array<double, 4>& p : probe_region_planes(positions)) region.emplace_back(p[0], p[1], p[2], p[3]);
    for (uint32_t l : plan.direct_lights) {
        const Light& light = lights[l];
        if (!light.shadows || plan.meshes == 0) continue;
        plan.shadows = true;
        plan.shadow_caster_candidates += plan.meshes;
        std::vector<float> volume;
        if (culling) {
            const bool directional = light.type == LightType::directional;
            const std::array<double, 3>& v = directional ? light.direction : light.position;
            for (const Plane& p : shadow_caster_volume(region, directional ? CasterLight::directional : CasterLight::point,
                                                       Eigen::Vector3d(v[0], v[1], v[2])))
                for (int c = 0; c < 4; ++c) volume.push_back(float(p[c]));
        }
        for (uint32_t m = 0; m < plan.meshes; ++m) {
            const Mesh& mesh = scene.meshes()[m];
            if (!culling || volume_may_intersect_aabb(volume.data(), volume.size() / 4, mesh.bounds_min.data(),
                                                      mesh.bounds_max.data()))
                plan.occluders[l].push_back(m);
        }
        plan.shadow_casters += uint32_t(plan.occluders[l].size());
    }
    if (plan.meshes == 0) plan.shadows = false;
    return plan;
}

void add_inside_probes(EffectsPlan& plan, const Scene& scene, const std::vector<float>& positions, uint32_t threads) {
    plan.inside_probes.clear();
    plan.inside_decided = true;
    if (scene.meshes().empty() || positions.empty()) return;
    plan.inside_probes = find_inside_probes(scene, positions, threads, &plan.inside_decided);
}

std::string EffectsPlan::summary() const {
    std::string text = "direct: " + count_of(uint32_t(direct_lights.size()), "light", "lights");
    if (out_of_range_lights > 0) text += " (" + std::to_string(out_of_range_lights) + " out of range)";
    if (realtime_lights > 0) text += "; realtime: " + count_of(realtime_lights, "light", "lights") + " (bounced only)";
    text += std::string("; sky: ") + (sky ? "on" : "off");
    text += "; emissive: " + count_of(uint32_t(emissive_meshes.size()), "mesh", "meshes");
    text += "; bounces: " + std::to_string(bounces);
    text += "; shadow casters: " + std::to_string(shadow_casters) + "/" + std::to_string(shadow_caster_candidates) +
            " meshes";
    if (!inside_decided) {
        text += "; inside geometry: undecided (no mesh has an inside)";
    } else if (!inside_probes.empty()) {
        text += "; inside geometry: " + count_of(uint32_t(inside_probes.size()), "probe", "probes") + " (";
        for (size_t i = 0; i < inside_probes.size() && i < 8; ++i)
            text += (i ? ", " : "") + std::to_string(inside_probes[i]);
        text += inside_probes.size() > 8 ? ", ...)" : ")";
    }
    return text;
}

}  // namespace tetprobe
