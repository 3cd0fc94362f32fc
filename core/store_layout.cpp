#include "core/store_layout.h"

namespace tetprobe {

namespace {

bool multiply(uint64_t a, uint64_t b, uint64_t* out) { return !__builtin_mul_overflow(a, b, out); }

}  // namespace

bool expected_section_sizes(const StoreHeader& header, uint64_t sizes[kSectionCount]) {
    if (header.inner_cell_count > header.cell_count) return false;
    const uint64_t probes = header.probe_count;
    const uint64_t cells = header.cell_count;
    const uint64_t index_bytes = store_index_bytes(header.flags);
    uint64_t grid_cells = 0;
    if (!multiply(header.grid[0], header.grid[1], &grid_cells)) return false;
    if (!multiply(grid_cells, header.grid[2], &grid_cells)) return false;

    const bool compact = (header.flags & kFlagCompact) != 0;
    sizes[kSectionPositions] = probes * 3 * sizeof(float);
    sizes[kSectionNormals] = probes * 3 * sizeof(float);
    sizes[kSectionSh] = probes * (compact ? kShHalvesCompact : kShHalvesFast) * sizeof(uint16_t);
    sizes[kSectionProbeSource] = probes * sizeof(uint32_t);
    sizes[kSectionInputRemap] = uint64_t(header.input_probe_count) * sizeof(uint32_t);
    sizes[kSectionCells] = cells * (compact ? 4 : 8) * index_bytes;
    sizes[kSectionOcclusion] = (header.flags & kFlagOcclusion) ? probes * kOcclusionChannels : 0;
    const bool leak = (header.flags & kFlagLeakControl) != 0;
    sizes[kSectionLeakOffsets] = leak ? (probes + 1) * sizeof(uint32_t) : 0;
    sizes[kSectionLeakEdges] = uint64_t(header.leak_edge_count) * sizeof(LeakEdge);
    return multiply(grid_cells, index_bytes, &sizes[kSectionGrid]);
}

}  // namespace tetprobe
