// The inside of a loaded Store: the aligned copy of the blob and typed views of its sections,
// shared by loading (store.cpp), the walk (walk.cpp) and the queries (store_queries.cpp).
#pragma once

#include "core/locate_kernel.h"
#include "core/sh_blend.h"
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
    LocateKernel locate{};               // the walk compiled for this store and CPU, chosen at load
    double origin[3] = {0, 0, 0};

    const float* positions = nullptr;        // 3 per probe (the blob's, or decoded)
    const float* normals = nullptr;          // 3 per probe, decoded (zero off the hull)
    ShEncoding sh_encoding = kShHalf;
    const uint8_t* sh = nullptr;             // one record of sh_stride bytes per probe
    size_t sh_stride = 0;
    ShBlendFunction blend_sh = nullptr;      // the encoding's blend for this CPU, chosen at load
    bool map16 = false;                      // probe maps are uint16 (else uint32)
    const void* probe_source = nullptr;      // per probe
    const void* input_remap = nullptr;       // per input probe (the blob's, or probe_source inverted)
    const void* cells = nullptr;             // CellRecord<Index> per cell (the blob's, or rebuilt)
    const void* grid_cells = nullptr;        // grid[0]*grid[1]*grid[2] indices
    AlignedBytes rebuilt_cells;              // compact and rebuilt layouts: the cell records rebuilt on load
    AlignedBytes rebuilt_grid;               // rebuilt layout: the start grid rebuilt on load
    AlignedBytes decoded_positions;          // quantised positions as floats
    AlignedBytes decoded_normals;            // the hull probes' normals, per probe
    AlignedBytes inverted_remap;             // input_remap when the blob stores none

    // Optional scene data (null / 0 when the blob has none).
    uint32_t occlusion_lights = 0;
    const uint8_t* occlusion = nullptr;      // 4 per probe
    const uint32_t* leak_offsets = nullptr;  // probe_count + 1; non-null = leak control on
    const LeakEdge* leak_edges = nullptr;
    AlignedBytes leak_cells;                 // per cell 1 if two of its probes cannot see each other (built on load)
    AlignedBytes leak_planes;                // per leak edge its two LeakPlanes, normals decoded (built on load)
};

}  // namespace tetprobe
