// The two coordinates a flat probe set is triangulated in, and its queries projected to: every
// coordinate but the dropped axis, in increasing axis order. Pure selection, no arithmetic, so
// orientations on the projection are exact on the stored floats.
#pragma once

#include <cstdint>

namespace tetprobe {

inline void project_to_plane(const float p[3], uint32_t dropped_axis, float uv[2]) {
    uv[0] = p[dropped_axis == 0 ? 1 : 0];
    uv[1] = p[dropped_axis == 2 ? 1 : 2];
}

}  // namespace tetprobe
