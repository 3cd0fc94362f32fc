// A Quake 3 level as a scene to bake, with stated lighting conventions (the BSP holds geometry and
// light entities; its textures and shaders are in other packages, so materials, sun and sky are
// constants here).
//
// - Surfaces: one mesh, one-sided (as Q3 draws them), Lambertian albedo kQuake3Albedo.
// - Light entities: point lights (spot lights when aimed at a target) of radiant intensity
//   light * kQuake3IntensityPerLight and their `_color`, inverse-square falloff. The scale is q3map's:
//   a face lit head-on by `light` L at d units gets lightmap value L * 7500 / d^2 (255 = full
//   texture brightness); reading full brightness as the radiance of a white Lambertian surface
//   lit by irradiance pi gives I = L * 7500 * pi / (255 * 32^2) W/sr in metres. A light ends where
//   its irradiance falls to pi / 255 (one lightmap step), q3map's light envelope. Linear-falloff
//   lights (spawnflags 1) are given the same inverse-square falloff. Closer than kQuake3LightNearDistance
//   (16 units) the falloff is held at its value there, as q3map2 clamps the distance for both lightmaps
//   and the light grid so that surfaces next to a light get no hot spot. Spot lights: the cone's half
//   angle is atan(radius / distance to the target) (radius 64 units by default), full intensity
//   inside 0.8 of that angle.
// - Sun: a directional light of irradiance kQuake3SunIrradiance and colour kQuake3SunColor, from
//   kQuake3SunElevationDegrees above the horizon; sky: constant radiance kQuake3SkyRadiance. They
//   reach the level only through the left-out sky faces.
// - Spawn points: the scene's playable seeds (automatic placement stays in the space they reach).
#pragma once

#include "bake/quake3_bsp.h"
#include "bake/scene.h"

#include <string>

namespace tetprobe {

constexpr float kQuake3Albedo = 0.5f;
constexpr double kQuake3IntensityPerLight = 7500.0 * 3.14159265358979323846 / (255.0 * 32.0 * 32.0);
constexpr float kQuake3SunIrradiance = 3.0f;
constexpr float kQuake3SunColor[3] = {1.0f, 0.95f, 0.85f};
constexpr double kQuake3SunElevationDegrees = 55.0, kQuake3SunAzimuthDegrees = 30.0;
constexpr float kQuake3SkyRadiance[3] = {0.25f, 0.32f, 0.45f};
constexpr double kQuake3SpotInnerFraction = 0.8;
constexpr double kQuake3LightNearDistance = 16.0 / kQuake3UnitsPerMetre;

// Adds the level's mesh, lights, sun and sky to the scene (see above).
void add_quake3_level(Scene& scene, const Quake3Level& level);

// Reads a .bsp file into a new scene (read_quake3_bsp, then add_quake3_level).
Scene load_quake3_scene(const std::string& path);

}  // namespace tetprobe
