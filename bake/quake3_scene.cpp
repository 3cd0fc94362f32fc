#include "bake/quake3_scene.h"

#include "core/error.h"

#include <cmath>

namespace tetprobe {

void add_quake3_level(Scene& scene, const Quake3Level& level) {
    if (level.indices.empty()) throw Error(Status::scene, level.name + ": no drawn surface to bake");
    Material material;
    material.albedo = {kQuake3Albedo, kQuake3Albedo, kQuake3Albedo};
    material.two_sided = false;
    scene.add_mesh(level.vertices.data(), level.vertices.size() / 3, level.indices.data(), level.triangle_count(),
                   {material}, nullptr, level.name + ": drawn surfaces");
    constexpr double kDegrees = 3.14159265358979323846 / 180.0;
    for (size_t i = 0; i < level.lights.size(); ++i) {
        const Quake3Light& q = level.lights[i];
        if (!(q.light > 0)) continue;  // a dark or negative light adds nothing here
        LightDescription light;
        light.type = q.spot ? LightType::spot : LightType::point;
        light.intensity = float(q.light * kQuake3IntensityPerLight);
        for (int k = 0; k < 3; ++k) light.color[k] = q.color[k], light.position[k] = float(q.position[k]);
        // Irradiance I / d^2 falls to pi / 255 at d = sqrt(255 I / pi).
        light.range = float(std::sqrt(255.0 * light.intensity / 3.14159265358979323846));
        light.near_distance = float(kQuake3LightNearDistance);
        if (q.spot) {
            const double outer = std::acos(q.spot_cos_outer);
            for (int k = 0; k < 3; ++k) light.direction[k] = float(q.spot_direction[k]);
            light.outer_angle = float(2 * outer / kDegrees);
            light.inner_angle = float(2 * kQuake3SpotInnerFraction * outer / kDegrees);
        }
        scene.add_light(light, level.name + ": light " + std::to_string(i));
    }
    LightDescription sun;
    sun.type = LightType::directional;
    sun.intensity = kQuake3SunIrradiance;
    const double elevation = kQuake3SunElevationDegrees * kDegrees, azimuth = kQuake3SunAzimuthDegrees * kDegrees;
    const double toward_sun[3] = {std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                                  std::cos(elevation) * std::sin(azimuth)};
    for (int k = 0; k < 3; ++k) sun.color[k] = kQuake3SunColor[k], sun.direction[k] = float(-toward_sun[k]);
    scene.add_light(sun, level.name + ": sun");
    scene.set_sky_color(kQuake3SkyRadiance);
    // Spawn points are where players stand: automatic placement keeps to the space they reach.
    if (!level.spawn_points.empty()) scene.set_playable_seeds(level.spawn_points.data(), level.spawn_points.size() / 3);
}

Scene load_quake3_scene(const std::string& path) {
    Scene scene;
    add_quake3_level(scene, read_quake3_bsp(path));
    return scene;
}

}  // namespace tetprobe
