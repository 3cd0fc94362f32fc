// SimplexMesh: the inner cells of a probe set of dimension d (0..3) as plain arrays, in the store's
// slot convention: vertices in slots 0..d, neighbour k across the facet opposite vertex k, kNone32
// where there is none, unused slots kNone32. It is what every triangulation path (TetGen's at bake
// time, core's exact ones) hands to the hull, outer-cell and ordering stages.
#pragma once

#include "core/store_format.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tetprobe {

using CellSlots = std::array<uint32_t, 4>;

struct SimplexMesh {
    uint32_t dimension = 3;
    std::vector<CellSlots> vertices;
    std::vector<CellSlots> neighbours;

    size_t cell_count() const { return vertices.size(); }
    void add_cell(const CellSlots& cell_vertices, const CellSlots& cell_neighbours) {
        vertices.push_back(cell_vertices);
        neighbours.push_back(cell_neighbours);
    }
};

constexpr CellSlots kNoSlots = {kNone32, kNone32, kNone32, kNone32};

}  // namespace tetprobe
