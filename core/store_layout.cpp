#include "core/store_layout.h"

#include "core/sh_encoding.h"

namespace tetprobe {

namespace {

bool multiply(uint64_t a, uint64_t b, uint64_t* out) { return !__builtin_mul_overflow(a, b, out); }

}  // namespace

bool expected_section_sizes(const StoreHeader& header, uint64_t sizes[kSectionCount]) {
    if (header.inner_cell_count > header.cell_count) return false;
    if (header.layout >= kLayoutCount || header.sh_encoding >= kShEncodingCount ||
        header.position_encoding >= kPositionEncodingCount)
        return false;
    const uint64_t probes = header.probe_count;
    const uint64_t cells = header.cell_count;
    const uint64_t index_bytes = store_index_bytes(header.flags);
    const uint64_t map_bytes = store_map_bytes(header.input_probe_count);
    uint64_t grid_cells = 0;
    if (!multiply(header.grid[0], header.grid[1], &grid_cells)) return false;
    if (!multiply(grid_cells, header.grid[2], &grid_cells)) return false;

    const StoreLayout layout = StoreLayout(header.layout);
    const uint64_t cell_indices = layout == kLayoutFast ? 8 : (layout == kLayoutCompact ? 4 : 0);
    const bool quantized = header.position_encoding == kPositionsUnorm16;
    sizes[kSectionPositions] = probes * 3 * (quantized ? 2 : 4);
    sizes[kSectionNormals] = uint64_t(header.hull_probe_count) * (quantized ? 2 * sizeof(int16_t) : 3 * sizeof(float));
    sizes[kSectionSh] = probes * sh_record_bytes(ShEncoding(header.sh_encoding), layout == kLayoutFast);
    sizes[kSectionProbeSource] = probes * map_bytes;
    sizes[kSectionInputRemap] = header.input_probe_count == header.probe_count ? 0 : header.input_probe_count * map_bytes;
    sizes[kSectionCells] = cells * cell_indices * index_bytes;
    sizes[kSectionOcclusion] = (header.flags & kFlagOcclusion) ? probes * kOcclusionChannels : 0;
    const bool leak = (header.flags & kFlagLeakControl) != 0;
    sizes[kSectionLeakOffsets] = leak ? (probes + 1) * sizeof(uint32_t) : 0;
    sizes[kSectionLeakEdges] = uint64_t(header.leak_edge_count) * sizeof(LeakEdge);
    if (layout == kLayoutRebuilt) grid_cells = 0;
    return multiply(grid_cells, index_bytes, &sizes[kSectionGrid]);
}

}  // namespace tetprobe
