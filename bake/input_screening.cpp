#include "bake/input_screening.h"

#include "core/error.h"
#include "core/store_format.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

namespace tetprobe {

namespace {

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

std::string describe(float value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(value));
    return text;
}

// Reads float i of a strided record (the caller's buffers need not be aligned).
float read_float(const float* base, size_t stride, size_t record, size_t i) {
    float value;
    std::memcpy(&value, reinterpret_cast<const unsigned char*>(base) + record * stride + i * sizeof(float),
                sizeof value);
    return value;
}

}  // namespace

ScreenedProbes screen_probe_input(const float* positions, size_t position_stride, const float* sh,
                                  size_t sh_stride, size_t count) {
    if (count == 0) throw Error(Status::degenerate, "no probes: a store needs at least one probe");
    // Stored probe indices must stay below the reserved values of 32-bit indices, and cells number
    // several times the probes.
    if (count > size_t(kMaxIndex16) * 1024) {
        throw Error(Status::invalid_argument, "too many probes: " + std::to_string(count));
    }
    if (!positions) throw Error(Status::invalid_argument, "positions is NULL");

    ScreenedProbes out;
    out.positions.resize(count);
    out.sh.assign(count * 27, 0.0f);
    for (size_t i = 0; i < count; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            const float value = read_float(positions, position_stride, i, size_t(axis));
            if (!std::isfinite(value) || std::fabs(double(value)) > kMaxCoordinate) {
                throw Error(Status::invalid_argument,
                            "probe " + std::to_string(i) + ": position " + axis_name(axis) + " is " +
                                describe(value) + (std::isfinite(value) ? " (magnitude above 1e30)" : ""));
            }
            out.positions[i][axis] = double(value);
        }
        if (!sh) continue;
        for (size_t c = 0; c < 27; ++c) {
            const float value = read_float(sh, sh_stride, i, c);
            if (!std::isfinite(value)) {
                throw Error(Status::invalid_argument, "probe " + std::to_string(i) + ": SH coefficient " +
                                                           std::to_string(c) + " is " + describe(value));
            }
            out.sh[i * 27 + c] = value;
        }
    }
    Eigen::Vector3d lo = out.positions[0], hi = lo;
    for (const Eigen::Vector3d& p : out.positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double extent = (hi - lo).norm();
    if (extent > 0 && extent < kMinSetExtent) {
        throw Error(Status::degenerate, "the probes span only " + describe(float(extent)) +
                                             " units: a set with distinct probes must span at least 1e-9");
    }
    return out;
}

}  // namespace tetprobe
