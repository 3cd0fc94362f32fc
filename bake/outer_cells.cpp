#include "bake/outer_cells.h"

#include "core/error.h"

#include <algorithm>
#include <unordered_map>
#include <utility>

namespace tetprobe {

namespace {

uint64_t edge_key(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    return (uint64_t(a) << 32) | b;
}

}  // namespace

OuterCells build_outer_cells(SimplexMesh& inner, const Hull& hull) {
    OuterCells outer;
    const uint32_t d = inner.dimension;
    const uint32_t first = uint32_t(inner.cell_count());
    const size_t count = hull.facets.size();
    outer.vertices.resize(count, kNoSlots);
    outer.neighbours.resize(count, kNoSlots);

    for (size_t i = 0; i < count; ++i) {
        const HullFacet& facet = hull.facets[i];
        for (uint32_t k = 0; k < d; ++k) outer.vertices[i][k] = facet.probes[k];
        outer.vertices[i][d] = kOuter32;
        outer.neighbours[i][d] = facet.inner_cell;
        inner.neighbours[facet.inner_cell][facet.inner_slot] = first + uint32_t(i);
    }

    // Neighbours across the rays: two outer cells are adjacent where their facets share d-1 probes.
    if (d == 3) {
        std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> edges;  // edge -> (cell, slot) seen first
        edges.reserve(count * 2);
        for (uint32_t i = 0; i < count; ++i) {
            for (uint32_t k = 0; k < 3; ++k) {
                const uint64_t key = edge_key(outer.vertices[i][(k + 1) % 3], outer.vertices[i][(k + 2) % 3]);
                auto it = edges.find(key);
                if (it == edges.end()) {
                    edges.emplace(key, std::make_pair(i, k));
                } else {
                    outer.neighbours[i][k] = first + it->second.first;
                    outer.neighbours[it->second.first][it->second.second] = first + i;
                }
            }
        }
    } else if (d == 2) {
        std::unordered_map<uint32_t, std::pair<uint32_t, uint32_t>> ends;  // probe -> (cell, slot) seen first
        ends.reserve(count);
        for (uint32_t i = 0; i < count; ++i) {
            for (uint32_t k = 0; k < 2; ++k) {
                const uint32_t shared = outer.vertices[i][1 - k];
                auto it = ends.find(shared);
                if (it == ends.end()) {
                    ends.emplace(shared, std::make_pair(i, k));
                } else {
                    outer.neighbours[i][k] = first + it->second.first;
                    outer.neighbours[it->second.first][it->second.second] = first + i;
                }
            }
        }
    }
    for (uint32_t i = 0; i < count; ++i) {
        for (uint32_t k = 0; k < d && d >= 2; ++k) {
            if (outer.neighbours[i][k] == kNone32) throw Error(Status::internal, "hull is not closed");
        }
    }
    return outer;
}

}  // namespace tetprobe
