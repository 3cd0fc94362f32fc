// Builds a store's arrays from probe positions and SH: input screening, merging of duplicates,
// dimension detection (point, line, flat, general), Delaunay (TetGen) on the probes in a canonical
// order, exact orientation of the cells, hull and outer cells, cell ordering and the cold-start grid.
// The result depends on the probe set, not on the order it was given in, except for which probe of
// a merged group survives (the first given) and, within the merge tolerance, greedy merge chains.
#pragma once

#include "bake/progress.h"
#include "bake/scene.h"
#include "core/option_defaults.h"
#include "core/store_data.h"
#include "core/store_format.h"

#include <cstddef>

namespace tetprobe {

// The store flags a build takes (the C ABI's TP_BUILD_* have the same values).
constexpr uint32_t kBuildFlags = kFlagNoExtrapolation | kFlagIndex32 | kFlagCompact;

struct BuildSettings {
    uint32_t flags = 0;              // kBuildFlags bits
    double merge_tolerance = kDefaultMergeTolerance;  // fraction of the bounding-box diagonal
    double flat_tolerance = kDefaultFlatTolerance;    // fraction of the bounding-box diagonal
    uint32_t threads = 0;            // leak control's rays (0 = all cores); the result does not depend on it
    Progress progress;
    // Optional scene data. occlusion: 4 bytes per input probe at occlusion_stride bytes (channels at
    // and above occlusion_lights are ignored); a merged probe stores the rounded mean of its group.
    const uint8_t* occlusion = nullptr;
    size_t occlusion_stride = 4;
    uint32_t occlusion_lights = 0;   // 1..4 with occlusion
    const Scene* scene = nullptr;    // leak control: cell edges crossing its geometry are stored
};

// Throws tetprobe::Error (Status::invalid_argument, degenerate, tetgen,
// cancelled) on failure. positions: 3 floats per probe at position_stride bytes;
// sh: 27 floats per probe at sh_stride bytes, or nullptr for zeros. Strides are already resolved (> 0).
StoreData build_store_data(const float* positions, size_t position_stride, const float* sh, size_t sh_stride,
                           size_t count, const BuildSettings& settings);

}  // namespace tetprobe
