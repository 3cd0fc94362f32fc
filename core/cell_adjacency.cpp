#include "core/cell_adjacency.h"

#include "core/error.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace tetprobe {

namespace {

template <class Index>
constexpr uint32_t none_index() {
    return sizeof(Index) == 2 ? kNone16 : kNone32;
}

template <class Index>
constexpr uint32_t outer_index() {
    return sizeof(Index) == 2 ? kOuter16 : kOuter32;
}

struct FacetEntry {
    std::array<uint32_t, 3> key;  // the facet's vertex slots' values, sorted, padded with kNone32
    uint32_t cell;
    uint32_t slot;  // the slot opposite the facet
};

void sort3(std::array<uint32_t, 3>& k) {
    if (k[1] < k[0]) std::swap(k[0], k[1]);
    if (k[2] < k[1]) std::swap(k[1], k[2]);
    if (k[1] < k[0]) std::swap(k[0], k[1]);
}

}  // namespace

template <class Index>
void rebuild_neighbours(CellRecord<Index>* records, uint32_t count, uint32_t dimension) {
    const uint32_t d = dimension;
    std::vector<FacetEntry> facets;
    facets.reserve(size_t(count) * (d + 1));
    for (uint32_t c = 0; c < count; ++c) {
        CellRecord<Index>& r = records[c];
        for (uint32_t k = 0; k < 4; ++k) r.neighbours[k] = Index(none_index<Index>());
        for (uint32_t k = 0; k <= d && d > 0; ++k) {
            FacetEntry e{{kNone32, kNone32, kNone32}, c, k};
            uint32_t n = 0;
            bool only_outer = true;
            for (uint32_t j = 0; j <= d; ++j) {
                if (j == k) continue;
                e.key[n++] = r.vertices[j];
                only_outer &= r.vertices[j] == outer_index<Index>();
            }
            if (only_outer) continue;  // a line's outer cell: the far side has no neighbour
            sort3(e.key);  // unused places hold kNone32, the largest value
            facets.push_back(e);
        }
    }
    std::sort(facets.begin(), facets.end(), [](const FacetEntry& a, const FacetEntry& b) { return a.key < b.key; });
    for (size_t i = 0; i < facets.size();) {
        size_t j = i + 1;
        while (j < facets.size() && facets[j].key == facets[i].key) ++j;
        if (j - i > 2)
            throw Error(Status::invalid_blob, "invalid store blob: a facet of cell " + std::to_string(facets[i].cell) +
                                                  " is shared by " + std::to_string(j - i) + " cells");
        if (j - i == 2) {
            records[facets[i].cell].neighbours[facets[i].slot] = Index(facets[i + 1].cell);
            records[facets[i + 1].cell].neighbours[facets[i + 1].slot] = Index(facets[i].cell);
        }
        i = j;
    }
}

template void rebuild_neighbours<uint16_t>(CellRecord<uint16_t>*, uint32_t, uint32_t);
template void rebuild_neighbours<uint32_t>(CellRecord<uint32_t>*, uint32_t, uint32_t);

}  // namespace tetprobe
