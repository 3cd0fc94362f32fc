// The store blob, format version 2: one contiguous, position-independent, little-endian buffer.
// This file is the single description of the layout; the writer and the loader both follow it.
//
//   [header: 116 bytes][section table: kSectionCount x {uint64 offset, uint64 size}][sections...]
//
// Sections appear in table order, each at a 16-byte-aligned offset, with zero padding between
// them and nothing after the last. The checksum is FNV-1a 64 of the whole blob with the checksum
// field read as zero, so any changed byte (header included) is caught.
//
// Geometry (all positions are local: world minus header.origin, float32):
// - dimension d of the probe set: 0 point, 1 line, 2 flat, 3 general.
// - cells [0, inner_cell_count) are inner cells with d+1 probes in vertex slots 0..d;
//   cells [inner_cell_count, cell_count) are outer cells with d probes in slots 0..d-1 and
//   kOuter in slot d. Unused slots hold kNone. Dimension 0 has exactly one inner cell {0}.
// - neighbour k is the cell across the facet opposite vertex slot k (k <= d), kNone where there
//   is none (the hull of a store built without extrapolation, and the far side of a line's end
//   cell, which holds every point beyond that end); slots above d are kNone. An outer
//   cell's neighbour d is the inner cell it rests on; its neighbours below d are outer cells.
// - inner matrix (12 floats, row-major 3x4, per inner cell): barycentric b_k = M[k].xyz . (p - P_d)
//   + M[k].w for k < d, b_d = 1 - sum, with P_d the position of the cell's probe in slot d; rows >= d
//   are zero. Relative to a vertex, not to the origin, so that a small cell far from the origin keeps
//   float precision (format 1 used p itself: half-metre cells 400 units from the origin could miss a probe).
// - outer matrix (16 floats, row-major 4x4, per outer cell): coefficient r of the polynomial
//   f(t) = c0 t^3 + c1 t^2 + c2 t + c3 is c_r = M[r].xyz . (p - P_0) + M[r].w, with P_0 the position
//   of the cell's probe in slot 0. The rows are scaled by a
//   positive factor; f(0) = c3 > 0 exactly when p is strictly outside the hull facet. The cell's
//   vertex k at parameter t sits at position_k + t * normal_k; f(t) = 0 where p lies in the plane
//   (d = 3) or on the line (d = 2, measured across the flat set's plane) of those moved vertices.
//   d = 2: c0 = 0 (quadratic). d = 1: rows 0..2 are zero and c3 is p's distance beyond the end.
// - normals: per probe, the hull vertex normal (unit) for probes on the hull, zero otherwise.
// - grid: gx*gy*gz start cells over [bounds_min, bounds_max] (x fastest) for queries without hint.
// - probe_source: stored probe -> index of the input probe it came from (the survivor of merges);
//   input_remap: input probe -> stored probe.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetprobe {

constexpr char kStoreMagic[8] = {'T', 'E', 'T', 'P', 'R', 'O', 'B', 'E'};
constexpr uint32_t kStoreFormatVersion = 2;
constexpr size_t kSectionAlignment = 16;

constexpr uint32_t kFlagIndex32 = 1u;          // indices are uint32, else uint16
constexpr uint32_t kFlagNoExtrapolation = 2u;  // no outer cells

enum Section : uint32_t {
    kSectionPositions = 0,      // float32 x 3 x probe_count
    kSectionNormals,            // float32 x 3 x probe_count
    kSectionSh,                 // binary16 x 27 x probe_count, channel-major
    kSectionProbeSource,        // uint32 x probe_count
    kSectionInputRemap,         // uint32 x input_probe_count
    kSectionCellVertices,       // index x 4 x cell_count
    kSectionCellNeighbours,     // index x 4 x cell_count
    kSectionInnerMatrices,      // float32 x 12 x inner_cell_count
    kSectionOuterMatrices,      // float32 x 16 x (cell_count - inner_cell_count)
    kSectionGrid,               // index x grid[0]*grid[1]*grid[2]
    kSectionCount
};

// Reserved index values (the top of the index range).
constexpr uint32_t kNone16 = 0xFFFFu, kOuter16 = 0xFFFEu;
constexpr uint32_t kNone32 = 0xFFFFFFFFu, kOuter32 = 0xFFFFFFFEu;
constexpr uint32_t kMaxIndex16 = 0xFFFDu;  // largest count for which 16-bit indices are used

#pragma pack(push, 1)
struct StoreHeader {
    char magic[8];
    uint32_t format_version;
    uint32_t header_size;       // 116 + 16 * kSectionCount
    uint32_t flags;
    uint32_t dimension;
    uint32_t probe_count;
    uint32_t input_probe_count;
    uint32_t cell_count;
    uint32_t inner_cell_count;
    uint32_t grid[3];
    double origin[3];
    float bounds_min[3];        // local
    float bounds_max[3];
    uint64_t checksum;
    uint32_t section_count;     // kSectionCount
    uint32_t reserved;          // 0
};
struct SectionEntry {
    uint64_t offset;
    uint64_t size;
};
#pragma pack(pop)

static_assert(sizeof(StoreHeader) == 116, "header layout");
constexpr size_t kHeaderSize = sizeof(StoreHeader) + kSectionCount * sizeof(SectionEntry);
constexpr size_t kChecksumOffset = offsetof(StoreHeader, checksum);

// FNV-1a 64 over bytes, with the 8 bytes at kChecksumOffset read as zero.
uint64_t store_checksum(const uint8_t* data, size_t size);

}  // namespace tetprobe
