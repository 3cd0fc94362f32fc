// The default values of the build and bake settings, written once: the C ABI's tp_*_init
// (capi/struct_defaults.h) and the bake's own settings read them from here.
#pragma once

#include <cstdint>
#include <limits>

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
// Lights (tp_light, bake/scene.h's LightDescription): a white, baked, shadowing point light of
// intensity 1 and unlimited range, pointing down, with spot cones of 30 and 45 degrees.
constexpr float kDefaultLightColor = 1.0f;  // each channel
constexpr float kDefaultLightIntensity = 1.0f;
constexpr float kDefaultLightDirection[3] = {0.0f, -1.0f, 0.0f};
constexpr float kDefaultLightRange = std::numeric_limits<float>::infinity();
constexpr float kDefaultSpotInnerAngle = 30.0f, kDefaultSpotOuterAngle = 45.0f;  // full cone angles, degrees

// Loading a store file (tp_store_load_options): larger files are refused. A store takes about 200
// bytes per probe, cells included, so 1 GiB holds millions of probes, far beyond any level.
constexpr uint64_t kDefaultMaxStoreFileBytes = uint64_t(1) << 30;

}  // namespace tetprobe
