// The inside of a loaded Store: the aligned copy of the blob and typed views of its sections,
// shared by loading (store.cpp), the walk (locate.cpp) and the blend (interpolate.cpp).
#pragma once

#include <vector>

#include "core/store.h"

#include <cstdint>
#include <memory>
#include <new>

namespace tetprobe {

struct AlignedFree {
    void operator()(uint8_t* p) const { ::operator delete(p, std::align_val_t(kSectionAlignment)); }
};
using AlignedBytes = std::unique_ptr<uint8_t, AlignedFree>;

using LocateFunction = Location (*)(const Store::Impl& store, const float world_position[3], int32_t hint);

struct Store::Impl {
    AlignedBytes bytes;   // the blob, 16-byte aligned so that every section is aligned for its type
    size_t size = 0;
    StoreHeader header{};

    bool index32 = false;
    uint32_t dimension = 0;
    uint32_t probe_count = 0;
    uint32_t cell_count = 0;
    uint32_t inner_cell_count = 0;
    uint32_t step_cap = 0;          // walk steps before the exhaustive double-precision decision
    double origin[3] = {0, 0, 0};

    const float* positions = nullptr;        // 3 per probe
    const float* normals = nullptr;          // 3 per probe
    const uint16_t* sh = nullptr;            // 27 halves per probe
    const uint32_t* probe_source = nullptr;  // per probe
    const uint32_t* input_remap = nullptr;   // per input probe
    const void* cell_vertices = nullptr;     // 4 indices per cell (uint16 or uint32)
    const void* cell_neighbours = nullptr;   // 4 indices per cell
    const float* inner_matrices = nullptr;   // 12 per inner cell
    const float* outer_matrices = nullptr;   // 16 per outer cell
    const void* grid_cells = nullptr;        // grid[0]*grid[1]*grid[2] indices

    LocateFunction locate = nullptr;         // the walk for this index width
    // Per inner cell of a 3D store, 1 where the cell has zero volume (found once at load): the walk
    // passes through such cells but never answers with them.
    std::vector<uint8_t> zero_volume;
};

}  // namespace tetprobe
