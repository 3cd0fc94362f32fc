// The peers on a real level, each built as its engine ships it and measured with the level's metric
// (level_eval.h): the dilated uniform grid (half or APV 8-bit SH) and the adaptive brick grid at a byte
// budget, over the playable space's box; 4-nearest probes (with or without damping) on a given probe set.
// Their probes are baked with the level's probe settings, like tetprobe's.
#pragma once

#include "dilated_grid.h"
#include "level_eval.h"

#include <vector>

namespace bench {

// Exponential damping of the 4-nearest blend: a time constant of 6 frames (0.1 s at 60 frames a second).
constexpr double kLevelDampingFrames = 6.0;

LevelResult evaluate_grid(const Level& level, size_t budget_bytes, GridEncoding encoding, const LevelSettings& settings,
                          uint32_t threads);
LevelResult evaluate_bricks(const Level& level, size_t budget_bytes, const LevelSettings& settings, uint32_t threads);
LevelResult evaluate_knn(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh,
                         bool damped);

}  // namespace bench
