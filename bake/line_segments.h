// The inner cells of a collinear probe set: consecutive probes along the line joined as segments.
#pragma once

#include "bake/simplex_mesh.h"

#include <vector>

namespace tetprobe {

// Sorts points by their coordinate along the line (at least 2 distinct) and returns a dimension-1
// mesh: segment i joins the i-th and (i+1)-th distinct coordinate, slot 0 the lower one; neighbour 0
// (opposite slot 0) is the next segment, neighbour 1 the previous one. A point whose coordinate an
// earlier point already has is in no segment (the builder merges it into its nearest neighbour).
SimplexMesh line_segments(const std::vector<double>& along);

}  // namespace tetprobe
