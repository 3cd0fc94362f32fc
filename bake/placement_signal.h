// What placement measures at a point: the Rec. 709 luminance of the irradiance for the 6 axis normals
// (the quantity the real-level benchmark judges, level_metric.h), and the variance of its Monte Carlo
// noise. The points are baked twice, each time with half the rays and its own seed: the mean of the two
// is the value, and their difference, whose expected square is four times the variance of the mean,
// measures the noise at every point without asking the lighting bake for more than SH.
#pragma once

#include "bake/lighting_bake.h"
#include "bake/progress.h"
#include "bake/scene.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

// The 6 axis normals' luminance irradiance: +x, -x, +y, -y, +z, -z.
constexpr int kSignalSize = 6;

struct PointSignal {
    std::vector<float> value;  // kSignalSize per point: the mean of the two half bakes
    std::vector<float> noise;  // per point: the variance of value's noise, summed over the kSignalSize
};

// The luminance irradiance for the 6 axis normals of one probe's SH (27 floats).
void luminance6(const float sh[27], double out[kSignalSize]);

// Bakes positions (3 floats each, world) twice with rays / 2 and rays - rays / 2 rays (rays >= 2) and
// the settings' bounces and threads, seeds derived from settings.seed, and returns their signal.
// Progress: the two bakes, one after the other. Throws as bake_lighting.
PointSignal measure_signal(const Scene& scene, const std::vector<float>& positions, const BakeSettings& settings,
                           const Progress& progress);

}  // namespace tetprobe
