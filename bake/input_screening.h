// Input screening: the first stage of a build, so that nothing downstream (least of all TetGen,
// which aborts the process on NaN, Inf or degenerate input) ever sees a value it cannot handle.
#pragma once

#include "core/coordinate_limits.h"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace tetprobe {

// Smallest extent (bounding-box diagonal) of a probe set with more than one distinct position. Far
// below any world's detail; below about 1e-15 the outer cells' float rows lose the set (walks there
// fall back), so a set this small is refused rather than answered badly.
constexpr double kMinSetExtent = 1e-9;

struct ScreenedProbes {
    std::vector<Eigen::Vector3d> positions;  // world, as given
    std::vector<float> sh;                   // 27 per probe (zeros when no SH was given)
};

// Copies strided positions and SH, throwing Error(Status::degenerate) for zero probes or a set
// whose extent is positive but below kMinSetExtent, and
// Error(Status::invalid_argument) naming the probe and coordinate for NaN, Inf, |x| > kMaxCoordinate,
// a non-finite SH coefficient, or a count no index width can hold.
ScreenedProbes screen_probe_input(const float* positions, size_t position_stride, const float* sh,
                                  size_t sh_stride, size_t count);

}  // namespace tetprobe
