// The store blob, format version 4: one contiguous, position-independent, little-endian buffer.
// This file is the single description of the layout; the writer and the loader both follow it.
//
//   [header: 128 bytes][section table: kSectionCount x {uint64 offset, uint64 size}][sections...]
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
// - optional scene data (format 4). A section a flag does not announce is empty (size 0), so a store
//   built without a scene costs only its table entries and alignment.
//   occlusion (kFlagOcclusion): per probe 4 bytes, byte i = round(255 * fraction of mixed light i the
//   probe sees) for i < header.occlusion_lights (1..4); the unused bytes are 255 (unshadowed).
//   leak control (kFlagLeakControl): probe pairs of a cell edge that cannot see each other (geometry
//   crosses the segment between them), as lists per probe: leak_offsets[probe_count + 1] (uint32,
//   leak_offsets[0] = 0, non-decreasing, leak_offsets[probe_count] = header.leak_edge_count) and
//   leak_edges (LeakEdge). The edges of probe a are leak_edges[leak_offsets[a], leak_offsets[a+1]),
//   each naming a partner b > a (strictly increasing within a list) and the ramp [start, end] with
//   0 <= start < end <= 1: the stretch of the segment a->b (0 at a, 1 at b) over which visibility
//   passes from a to b (the wall crossing widened; see core/leak_control.h).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetprobe {

constexpr char kStoreMagic[8] = {'T', 'E', 'T', 'P', 'R', 'O', 'B', 'E'};
constexpr uint32_t kStoreFormatVersion = 4;
constexpr size_t kSectionAlignment = 16;

// Header flags. The C ABI's TP_BUILD_* bits are these same values (checked where it translates).
constexpr uint32_t kFlagNoExtrapolation = 1u;  // no outer cells
constexpr uint32_t kFlagIndex32 = 2u;          // indices are uint32, else uint16
constexpr uint32_t kFlagCompact = 4u;          // compact layout (see above), else fast
constexpr uint32_t kFlagOcclusion = 8u;        // the occlusion section holds mixed lights' visibility
constexpr uint32_t kFlagLeakControl = 16u;     // the leak sections list probe pairs that cannot see each other
constexpr uint32_t kKnownFlags = kFlagNoExtrapolation | kFlagIndex32 | kFlagCompact | kFlagOcclusion | kFlagLeakControl;

// Occlusion: bytes per probe (one per mixed light, at most four).
constexpr uint32_t kOcclusionChannels = 4;

enum Section : uint32_t {
    kSectionPositions = 0,      // float32 x 3 x probe_count
    kSectionNormals,            // float32 x 3 x probe_count
    kSectionSh,                 // binary16 x (fast 32 | compact 27) x probe_count, channel-major
    kSectionProbeSource,        // uint32 x probe_count
    kSectionInputRemap,         // uint32 x input_probe_count
    kSectionCells,              // index x (fast 8 | compact 4) x cell_count
    kSectionGrid,               // index x grid[0]*grid[1]*grid[2]
    kSectionOcclusion,          // uint8 x 4 x probe_count (kFlagOcclusion), else empty
    kSectionLeakOffsets,        // uint32 x (probe_count + 1) (kFlagLeakControl), else empty
    kSectionLeakEdges,          // LeakEdge x leak_edge_count (kFlagLeakControl), else empty
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
    uint32_t header_size;       // 128 + 16 * kSectionCount
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
    uint32_t occlusion_lights;  // 1..4 with kFlagOcclusion, else 0
    uint32_t leak_edge_count;   // entries of the leak_edges section (0 without kFlagLeakControl)
    uint32_t reserved;          // 0
};
// One probe pair that cannot see each other (in the list of the lower probe, a).
struct LeakEdge {
    uint32_t partner;           // b > a
    float start, end;           // ramp along a->b, 0 <= start < end <= 1
};
struct SectionEntry {
    uint64_t offset;
    uint64_t size;
};
#pragma pack(pop)

static_assert(sizeof(StoreHeader) == 128, "header layout");
static_assert(sizeof(LeakEdge) == 12, "leak edge layout");
constexpr size_t kHeaderSize = sizeof(StoreHeader) + kSectionCount * sizeof(SectionEntry);
constexpr size_t kChecksumOffset = offsetof(StoreHeader, checksum);
// Where the format version sits in every format (so an older blob is told apart from a corrupt one).
constexpr size_t kFormatVersionOffset = offsetof(StoreHeader, format_version);

// The checksum above, with the 8 bytes at kChecksumOffset read as zero.
uint64_t store_checksum(const uint8_t* data, size_t size);

}  // namespace tetprobe
