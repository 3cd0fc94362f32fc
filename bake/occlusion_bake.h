// Occlusion probes: per probe and mixed light, the fraction of the light the probe sees, quantised to
// a byte (what a store built with occlusion keeps, and what Unity's occlusion probes return beside
// the SH, so that an engine shadows a mixed light's real-time direct light with its baked shadow).
#pragma once

#include "bake/lighting_bake.h"
#include "bake/scene.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

// 4 bytes per probe at `positions` (3 floats each, world units): byte i = 255 * the visibility of the
// scene's i-th mixed light (in the order the lights were added), 255 for channels without a light.
// The lights are points (directional: a direction): one shadow ray per probe and light decides, so
// the fraction is 0 or 1 (a light without shadows is always seen; range and spot cones are left to
// the engine's real-time light, which attenuates them itself). *mixed_lights receives the count
// (0 to 4). Honours settings.progress (cancel throws Error(Status::cancelled)).
std::vector<uint8_t> bake_occlusion(const Scene& scene, const std::vector<float>& positions,
                                    const BakeSettings& settings, uint32_t* mixed_lights);

}  // namespace tetprobe
