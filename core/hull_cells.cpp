#include "core/hull_cells.h"

#include "core/error.h"

#include <algorithm>

namespace tetprobe {

CellSlots hull_facet_probes(const uint32_t* v, uint32_t slot, uint32_t dimension) {
    // 3D: ordered so that orient3d(facet, v[slot]) = -orient3d(v0, v1, v2, v3), outward for a
    // positive cell. 2D: orient2d(v[k+1], v[k+2], v[k]) = orient2d(v0, v1, v2) > 0, so the reversed
    // edge has the cell on its negative side. 1D: the end probe.
    static const int kOthers[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    CellSlots probes = kNoSlots;
    switch (dimension) {
        case 3:
            for (int j = 0; j < 3; ++j) probes[size_t(j)] = v[kOthers[slot][j]];
            break;
        case 2:
            probes[0] = v[(slot + 2) % 3];
            probes[1] = v[(slot + 1) % 3];
            break;
        case 1: probes[0] = v[1 - slot]; break;
        default: break;
    }
    return probes;
}

std::vector<HullFacet> find_hull_facets(const SimplexMesh& mesh) {
    std::vector<HullFacet> facets;
    const uint32_t d = mesh.dimension;
    if (d == 0) return facets;
    for (uint32_t c = 0; c < mesh.cell_count(); ++c)
        for (uint32_t k = 0; k <= d; ++k) {
            if (mesh.neighbours[c][k] != kNone32) continue;
            HullFacet facet;
            facet.probes = hull_facet_probes(mesh.vertices[c].data(), k, d);
            facet.inner_cell = c;
            facet.inner_slot = k;
            facets.push_back(facet);
        }
    return facets;
}

OuterCells build_outer_cells(SimplexMesh& inner, const std::vector<HullFacet>& facets) {
    OuterCells outer;
    const uint32_t d = inner.dimension;
    const uint32_t first = uint32_t(inner.cell_count());
    const uint32_t count = uint32_t(facets.size());
    outer.vertices.assign(count, kNoSlots);
    outer.neighbours.assign(count, kNoSlots);
    for (uint32_t i = 0; i < count; ++i) {
        const HullFacet& facet = facets[i];
        for (uint32_t k = 0; k < d; ++k) outer.vertices[i][k] = facet.probes[k];
        outer.vertices[i][d] = kOuter32;
        outer.neighbours[i][d] = facet.inner_cell;
        inner.neighbours[facet.inner_cell][facet.inner_slot] = first + i;
    }
    if (d < 2) return outer;

    // Across the rays: outer cell i's side opposite its slot k holds the facet's probes other than
    // slot k (3D an edge, 2D one probe); every such side is shared by exactly two facets of a closed
    // hull. Matched by sorting the sides' keys.
    struct Side {
        uint64_t key;
        uint32_t cell, slot;
    };
    std::vector<Side> sides;
    sides.reserve(size_t(count) * d);
    for (uint32_t i = 0; i < count; ++i)
        for (uint32_t k = 0; k < d; ++k) {
            uint64_t key;
            if (d == 3) {
                uint32_t a = outer.vertices[i][(k + 1) % 3], b = outer.vertices[i][(k + 2) % 3];
                if (a > b) std::swap(a, b);
                key = uint64_t(a) << 32 | b;
            } else {
                key = outer.vertices[i][1 - k];
            }
            sides.push_back(Side{key, i, k});
        }
    std::sort(sides.begin(), sides.end(), [](const Side& a, const Side& b) {
        return a.key != b.key ? a.key < b.key : a.cell != b.cell ? a.cell < b.cell : a.slot < b.slot;
    });
    for (size_t s = 0; s < sides.size(); s += 2) {
        if (s + 1 >= sides.size() || sides[s].key != sides[s + 1].key || (s + 2 < sides.size() && sides[s + 2].key == sides[s].key))
            throw Error(Status::internal, "hull is not closed");
        outer.neighbours[sides[s].cell][sides[s].slot] = first + sides[s + 1].cell;
        outer.neighbours[sides[s + 1].cell][sides[s + 1].slot] = first + sides[s].cell;
    }
    return outer;
}

}  // namespace tetprobe
