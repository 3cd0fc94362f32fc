// StoreData: the store as plain arrays, between the builder (bake/) and the blob writer (core/).
// The meaning of every field is the blob's (see store_format.h); here indices are uint32 with
// kNone32 / kOuter32 as reserved values, SH are float, and nothing is validated. The writer
// chooses the index width and lays out the flags' layout (fast or compact).
#pragma once

#include "core/store_format.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

struct StoreData {
    uint32_t flags = 0;                 // kFlagNoExtrapolation, kFlagCompact; kFlagIndex32 forces 32-bit
    uint32_t dimension = 3;
    uint32_t axis = 0;                  // see store_format.h
    double origin[3] = {0, 0, 0};
    uint32_t input_probe_count = 0;
    std::vector<float> positions;       // 3 per stored probe, local
    std::vector<float> normals;         // 3 per stored probe
    std::vector<float> sh;              // 27 per stored probe
    std::vector<uint32_t> probe_source; // per stored probe
    std::vector<uint32_t> input_remap;  // per input probe
    uint32_t inner_cell_count = 0;
    std::vector<uint32_t> cell_vertices;   // 4 per cell
    std::vector<uint32_t> cell_neighbours; // 4 per cell (the compact layout drops them from the blob)
    uint32_t grid[3] = {1, 1, 1};
    std::vector<uint32_t> grid_cells;      // grid[0]*grid[1]*grid[2]
    float bounds_min[3] = {0, 0, 0};       // local
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
