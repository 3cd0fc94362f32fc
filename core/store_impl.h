// The inside of a loaded Store: the aligned copy of the blob and typed views of its sections,
// shared by loading (store.cpp), the walk (locate.cpp) and the blend (interpolate.cpp).
#pragma once

#include "core/store.h"

#include <cstdint>
#include <memory>
#include <new>

namespace tetprobe {

struct AlignedFree {
    void operator()(uint8_t* p) const { ::operator delete(p, std::align_val_t(64)); }
};
using AlignedBytes = std::unique_ptr<uint8_t, AlignedFree>;
// size bytes (at least 64) aligned to a cache line, zero-filled past size; std::bad_alloc when size
// cannot be rounded up to a whole line (or allocated).
AlignedBytes aligned_bytes(size_t size);

// One cell as the walk reads it: what a step needs, side by side (16 bytes at 16-bit indices).
template <class Index>
struct CellRecord {
    Index vertices[4];
    Index neighbours[4];
};

struct Store::Impl {
    AlignedBytes bytes;   // the blob, cache-line aligned so that every section is aligned for its type
    size_t size = 0;
    StoreHeader header{};

    bool index32 = false;
    uint32_t dimension = 0;
    uint32_t axis = 0;
    uint32_t probe_count = 0;
    uint32_t cell_count = 0;
    uint32_t inner_cell_count = 0;
    uint32_t sh_halves = kShHalvesFast;  // halves per probe in the SH section
    bool avx2 = false;                   // the walk's AVX2 kernel runs on this CPU
    double origin[3] = {0, 0, 0};

    const float* positions = nullptr;        // 3 per probe
    const float* normals = nullptr;          // 3 per probe
    const uint16_t* sh = nullptr;            // sh_halves per probe
    const uint32_t* probe_source = nullptr;  // per probe
    const uint32_t* input_remap = nullptr;   // per input probe
    const void* cells = nullptr;             // CellRecord<Index> per cell (the blob's, or rebuilt)
    const void* grid_cells = nullptr;        // grid[0]*grid[1]*grid[2] indices
    AlignedBytes rebuilt_cells;              // compact layout: the cell records rebuilt on load

    // Optional scene data (null / 0 when the blob has none).
    uint32_t occlusion_lights = 0;
    const uint8_t* occlusion = nullptr;      // 4 per probe
    const uint32_t* leak_offsets = nullptr;  // probe_count + 1; non-null = leak control on
    const LeakEdge* leak_edges = nullptr;
    AlignedBytes leak_cells;                 // per cell 1 if two of its probes cannot see each other (built on load)
};

}  // namespace tetprobe
