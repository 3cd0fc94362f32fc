// The store blob, format version 3: one contiguous, position-independent, little-endian buffer.
// This file is the single description of the layout; the writer and the loader both follow it.
//
//   [header: 120 bytes][section table: kSectionCount x {uint64 offset, uint64 size}][sections...]
//
// Sections appear in table order, each at a 16-byte-aligned offset, with zero padding between
// them and nothing after the last. The checksum is FNV-1a 64 over the blob's little-endian 64-bit
// words, each step followed by hash ^= hash >> 29 (seeded with offset basis ^ size, the last word
// zero-padded), with the checksum field read as zero, so any changed byte (header included) is caught.
//
// Geometry (all positions are local: world minus header.origin, float32). Every decision of which
// cell holds a point is an orientation predicate on these float32 positions, evaluated exactly
// (core/orientation.h); there are no per-cell matrices: weights are ratios of those orientations.
// - dimension d of the probe set: 0 point, 1 line, 2 flat, 3 general.
// - axis: d = 1, the coordinate (0 x, 1 y, 2 z) along which the line's probes are ordered; d = 2, the
//   coordinate dropped to triangulate (the flat set is triangulated, and queries are projected, in
//   the other two coordinates, in increasing order); otherwise 0.
// - cells [0, inner_cell_count) are inner cells with d+1 probes in vertex slots 0..d, positively
//   oriented; cells [inner_cell_count, cell_count) are outer cells with d probes in slots 0..d-1
//   (the hull facet, wound so that its outward side is positive) and kOuter in slot d. Unused slots
//   hold kNone. Dimension 0 has exactly one inner cell {0}.
// - neighbour k is the cell across the facet opposite vertex slot k (k <= d), kNone where there is
//   none (the hull of a store built without extrapolation, and the far side of a line's end cell,
//   which holds every point beyond that end); slots above d are kNone. An outer cell's neighbour d
//   is the inner cell it rests on; its neighbours below d are outer cells.
// - an outer cell sweeps its facet along the probes' normals: vertex k at parameter t >= 0 sits at
//   position_k + t * normal_k, and the cell holds p where the moved facet passes through p.
// - layout (kFlagCompact): the fast layout stores per cell {vertices[4], neighbours[4]} side by
//   side (16 bytes with 16-bit indices, 32 with 32-bit: what one walk step reads, in one cache
//   line) and SH padded to 32 halves (64 bytes, one aligned line per probe); the compact layout
//   stores per cell only vertices[4] (neighbours are rebuilt when the blob is loaded) and 27 halves.
// - probes and cells are ordered along a space-filling curve (neighbours near each other in memory);
//   cell 0 is near the centre of the probe cloud.
// - normals: per probe, the hull vertex normal (unit) for probes on the hull, zero otherwise.
// - grid: gx*gy*gz start cells over [bounds_min, bounds_max] (x fastest) for queries without hint.
// - probe_source: stored probe -> index of the input probe it came from (the survivor of merges);
//   input_remap: input probe -> stored probe.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetprobe {

constexpr char kStoreMagic[8] = {'T', 'E', 'T', 'P', 'R', 'O', 'B', 'E'};
constexpr uint32_t kStoreFormatVersion = 3;
constexpr size_t kSectionAlignment = 16;

// Header flags. The C ABI's TP_BUILD_* bits are these same values (checked where it translates).
constexpr uint32_t kFlagNoExtrapolation = 1u;  // no outer cells
constexpr uint32_t kFlagIndex32 = 2u;          // indices are uint32, else uint16
constexpr uint32_t kFlagCompact = 4u;          // compact layout (see above), else fast
constexpr uint32_t kKnownFlags = kFlagNoExtrapolation | kFlagIndex32 | kFlagCompact;

enum Section : uint32_t {
    kSectionPositions = 0,      // float32 x 3 x probe_count
    kSectionNormals,            // float32 x 3 x probe_count
    kSectionSh,                 // binary16 x (fast 32 | compact 27) x probe_count, channel-major
    kSectionProbeSource,        // uint32 x probe_count
    kSectionInputRemap,         // uint32 x input_probe_count
    kSectionCells,              // index x (fast 8 | compact 4) x cell_count
    kSectionGrid,               // index x grid[0]*grid[1]*grid[2]
    kSectionCount
};

// Halves per probe in the SH section.
constexpr uint32_t kShHalvesFast = 32, kShHalvesCompact = 27;

// Reserved index values (the top of the index range).
constexpr uint32_t kNone16 = 0xFFFFu, kOuter16 = 0xFFFEu;
constexpr uint32_t kNone32 = 0xFFFFFFFFu, kOuter32 = 0xFFFFFFFEu;
constexpr uint32_t kMaxIndex16 = 0xFFFDu;  // largest count for which 16-bit indices are used

#pragma pack(push, 1)
struct StoreHeader {
    char magic[8];
    uint32_t format_version;
    uint32_t header_size;       // 120 + 16 * kSectionCount
    uint32_t flags;
    uint32_t dimension;
    uint32_t axis;
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

static_assert(sizeof(StoreHeader) == 120, "header layout");
constexpr size_t kHeaderSize = sizeof(StoreHeader) + kSectionCount * sizeof(SectionEntry);
constexpr size_t kChecksumOffset = offsetof(StoreHeader, checksum);
// Where the format version sits in every format (so an older blob is told apart from a corrupt one).
constexpr size_t kFormatVersionOffset = offsetof(StoreHeader, format_version);

// The checksum above, with the 8 bytes at kChecksumOffset read as zero.
uint64_t store_checksum(const uint8_t* data, size_t size);

}  // namespace tetprobe
