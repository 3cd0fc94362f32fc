// StoreData: the store as plain arrays, between the builder (bake/) and the blob writer (core/).
// The meaning of every field is the blob's (see store_format.h); here indices are uint32 with
// kNone32 / kOuter32 as reserved values, SH, positions and normals are float, and nothing is
// validated. The writer chooses the index and map widths, encodes the SH, and lays out the layout.
// Geometry must already be what the blob stores: quantised positions on their grid with hull normals
// on the octahedral grid (core/octahedral_normal.h); every normal off the hull zero.
#pragma once

#include "core/store_format.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

struct StoreData {
    uint32_t flags = 0;                 // kFlagNoExtrapolation; kFlagIndex32 forces 32-bit
    StoreLayout layout = kLayoutFast;
    ShEncoding sh_encoding = kShHalf;
    PositionEncoding position_encoding = kPositionsFloat32;  // unorm16: over [bounds_min, bounds_max]
    uint32_t dimension = 3;
    uint32_t axis = 0;                  // see store_format.h
    double origin[3] = {0, 0, 0};
    uint32_t input_probe_count = 0;
    std::vector<float> positions;       // 3 per stored probe, local
    std::vector<float> normals;         // 3 per stored probe (zero but on the hull of a store with outer cells)
    std::vector<float> sh;              // 27 per stored probe
    std::vector<uint32_t> probe_source; // per stored probe
    std::vector<uint32_t> input_remap;  // per input probe (the blob omits it when nothing was merged)
    uint32_t inner_cell_count = 0;
    std::vector<uint32_t> cell_vertices;   // 4 per cell
    std::vector<uint32_t> cell_neighbours; // 4 per cell (the compact layout drops them from the blob)
    uint32_t grid[3] = {1, 1, 1};
    std::vector<uint32_t> grid_cells;      // grid[0]*grid[1]*grid[2]
    float bounds_min[3] = {0, 0, 0};       // local; holding every position
    float bounds_max[3] = {0, 0, 0};
    // Optional scene data: occlusion_lights > 0 writes the occlusion section (4 bytes per stored
    // probe); non-empty leak_offsets (probe_count + 1) writes the leak sections.
    uint32_t occlusion_lights = 0;
    std::vector<uint8_t> occlusion;
    std::vector<uint32_t> leak_offsets;
    std::vector<LeakEdge> leak_edges;

    uint32_t probe_count() const { return uint32_t(probe_source.size()); }
    uint32_t cell_count() const { return uint32_t(cell_vertices.size() / 4); }
};

}  // namespace tetprobe
