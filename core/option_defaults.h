// The default values of the build and bake settings, written once: the C ABI's tp_*_init
// (capi/struct_defaults.h) and the bake's own settings read them from here.
#pragma once

#include <cstdint>

namespace tetprobe {

constexpr double kDefaultMergeTolerance = 1e-6;  // fraction of the probe set's bounding-box diagonal
constexpr double kDefaultFlatTolerance = 1e-4;   // fraction of the probe set's bounding-box diagonal
constexpr uint32_t kDefaultBakeRays = 256;
constexpr uint32_t kDefaultBakeBounces = 2;
constexpr float kDefaultAlbedo = 0.8f;
// Automatic probe placement (tp_placement_options).
constexpr float kDefaultPlacementSpacing = 1.0f;  // world units
constexpr float kDefaultPlacementMargin = 0.1f;   // world units
constexpr float kDefaultWalkMinHeight = 0.0f, kDefaultWalkMaxHeight = 2.0f;
constexpr float kDefaultPlacementErrorBound = 0.25f;
constexpr float kDefaultPlacementLightClearance = 1.0f;  // world units
constexpr uint32_t kDefaultPlacementRays = 128;

}  // namespace tetprobe
