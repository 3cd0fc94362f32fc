// The one metric of the real-level benchmark, used by every part and every method. Irradiance is the
// Rec. 709 luminance of E(n) for the 6 axis normals n (tp_sh_eval_irradiance). At each evaluation point
// of the level (level_reference.h) and each normal, the error is |E_method - E_reference| divided by the
// level's mean (the reference's mean over the same points and normals); "rms" and "p95" are the root
// mean square and the 95th percentile of that over points x normals. "worst_jump" is the largest change
// of E between consecutive frames along the walking paths, over the 6 normals, divided by the same mean
// (the popping a moving object shows).
#pragma once

#include "level_reference.h"

#include <cstddef>
#include <vector>

namespace bench {

struct LevelError {
    double rms = 0, p95 = 0, max = 0;
    double worst_jump = 0;
};

// Luminance irradiance of the 6 axis normals for `count` SH (27 floats each): 6 floats each.
std::vector<float> luminance6(const float* sh, size_t count);

// The error of a method's SH at the level's evaluation points (27 floats each, in order) and along its
// paths (27 floats per frame, in order; may be empty: worst_jump 0).
LevelError level_error(const Level& level, const std::vector<float>& sh_at_points, const std::vector<float>& sh_on_paths);

// RMS and 95th percentile of |a - b| / mean over two luminance arrays (the reference noise uses it).
void relative_error(const std::vector<float>& a, const std::vector<float>& b, double mean, double* rms, double* p95,
                    double* max = nullptr);

}  // namespace bench
