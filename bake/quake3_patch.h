// Quake 3 curved surfaces: a patch is a grid of control points, width x height (both odd, at least
// 3), made of biquadratic Bezier pieces of 3 x 3 control points that share their edge rows.
// Tessellation evaluates every piece on a uniform (segments + 1)^2 grid of parameters, so
// neighbouring pieces meet exactly on their shared edge.
#pragma once

#include <cstdint>
#include <vector>

namespace tetprobe {

struct PatchTessellation {
    std::vector<double> positions;    // 3 per vertex
    std::vector<double> normals;      // 3 per vertex: the control normals evaluated the same way (not unit)
    std::vector<uint32_t> triangles;  // 3 per triangle, two per quad of each piece's parameter grid
};

// Tessellates the patch whose control points (3 doubles each, row-major: point (column c, row r)
// at r * width + c) and control normals are given. The caller has checked width and height.
PatchTessellation tessellate_quake3_patch(const double* positions, const double* normals, int width, int height,
                                          uint32_t segments);

}  // namespace tetprobe
