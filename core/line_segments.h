// The inner cells of a collinear probe set: consecutive probes along the line joined as segments.
#pragma once

#include "core/simplex_mesh.h"

#include <cstdint>

namespace tetprobe {

// Orders count probes (3 floats each) by their coordinate along axis, ties by index, and returns a
// dimension-1 mesh (at least 2 probes): segment i joins the i-th and (i+1)-th probe, slot 0 the lower
// one; neighbour 0 (opposite slot 0) is the next segment, neighbour 1 the previous one.
SimplexMesh line_segments(const float* positions, uint32_t count, uint32_t axis);

}  // namespace tetprobe
