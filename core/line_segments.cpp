#include "core/line_segments.h"

#include "core/error.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace tetprobe {

SimplexMesh line_segments(const float* positions, uint32_t count, uint32_t axis) {
    if (count < 2) throw Error(Status::degenerate, "a line needs at least 2 probes");
    std::vector<uint32_t> order(count);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        return positions[size_t(a) * 3 + axis] < positions[size_t(b) * 3 + axis];
    });
    // Equal coordinates would make a segment of zero length, which holds no point: the builder merges
    // such probes first, so a blob that has them is refused here.
    for (uint32_t s = 1; s < count; ++s)
        if (positions[size_t(order[s]) * 3 + axis] == positions[size_t(order[s - 1]) * 3 + axis])
            throw Error(Status::degenerate, "two probes of a line share their coordinate along its axis");

    SimplexMesh mesh;
    mesh.dimension = 1;
    const uint32_t segments = count - 1;
    mesh.vertices.reserve(segments);
    mesh.neighbours.reserve(segments);
    for (uint32_t s = 0; s < segments; ++s) {
        CellSlots vertices = kNoSlots, neighbours = kNoSlots;
        vertices[0] = order[s];
        vertices[1] = order[s + 1];
        neighbours[0] = s + 1 < segments ? s + 1 : kNone32;
        neighbours[1] = s > 0 ? s - 1 : kNone32;
        mesh.add_cell(vertices, neighbours);
    }
    return mesh;
}

}  // namespace tetprobe
