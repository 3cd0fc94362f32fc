#include "bake/line_segments.h"

#include "core/error.h"

#include <algorithm>
#include <numeric>

namespace tetprobe {

SimplexMesh line_segments(const std::vector<double>& along) {
    if (along.size() < 2) throw Error(Status::internal, "a line needs at least 2 points");
    std::vector<uint32_t> order(along.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return along[a] < along[b]; });
    // A point at the same coordinate as the one before it would make a segment of zero length (which
    // holds no point and which the loader refuses): it is left out of every cell, as TetGen leaves out
    // a coincident point, and the builder merges it into its nearest neighbour.
    order.erase(std::unique(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return along[a] == along[b]; }),
                order.end());
    if (order.size() < 2) throw Error(Status::internal, "a line needs at least 2 distinct points");

    SimplexMesh mesh;
    mesh.dimension = 1;
    const uint32_t segments = uint32_t(order.size() - 1);
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
