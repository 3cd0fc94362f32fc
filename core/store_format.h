// The store blob, format version 6: one contiguous, position-independent, little-endian buffer.
// This file is the single description of the layout; the writer and the loader both follow it
// (docs/store_format.md says the same for users).
//
//   [header: 144 bytes][section table: kSectionCount x {uint64 offset, uint64 size}][sections...]
//
// Sections appear in table order, each at a 16-byte-aligned offset, with zero padding between
// them and nothing after the last. Every section's size is implied by the header's counts and
// encodings (store_layout.h); a section a store does not use is empty (size 0). The checksum is
// FNV-1a 64 over the blob's little-endian 64-bit words, each step followed by hash ^= hash >> 29
// (seeded with offset basis ^ size, the last word zero-padded), with the checksum field read as
// zero, so any changed byte (header included) is caught.
//
// Geometry (all positions are local: world minus header.origin, float32 once decoded). Every decision
// of which cell holds a point is an orientation predicate on these float32 positions, evaluated exactly
// (core/orientation.h); there are no per-cell matrices: weights are ratios of those orientations.
// - dimension d of the probe set: 0 point, 1 line, 2 flat, 3 general.
// - axis: d = 1, the coordinate (0 x, 1 y, 2 z) along which the line's probes are ordered; d = 2, the
//   coordinate dropped to triangulate (the flat set is triangulated, and queries are projected, in
//   the other two coordinates, in increasing order); otherwise 0.
// - bounds_min/max (local, finite, min <= max per axis): a box holding every stored probe. Float
//   positions: their exact bounds. Quantised positions: the quantisation box.
// - positions and normals (position_encoding):
//   kPositionsFloat32: positions float32 x 3 per probe; normals float32 x 3 per hull probe.
//   kPositionsUnorm16: positions uint16 x 3 per probe, q on axis k decoded (core/position_quantization.h)
//     as float(lo + (q / 65535) * (hi - lo)) evaluated in double, clamped to [lo, hi] = [bounds_min[k],
//     bounds_max[k]]: the same float on every platform. The builder quantises first and tessellates the
//     decoded positions, so the cells are exactly Delaunay for them; it makes hi - lo 65535 times a power
//     of two with lo (and the origin) on a multiple of it, so codes decode to multiples of that step and
//     coordinates already on it stay exact. Normals int16 x 2 per hull probe,
//     octahedral (core/octahedral_normal.h: u = max(q0 / 32767, -1), v likewise, folded below the
//     equator, normalised in double, rounded to float): within 6e-5 radians of the builder's normal.
// - cells [0, inner_cell_count) are inner cells with d+1 probes in vertex slots 0..d, positively
//   oriented; cells [inner_cell_count, cell_count) are outer cells with d probes in slots 0..d-1
//   (the hull facet, wound so that its outward side is positive) and kOuter in slot d. Unused slots
//   hold kNone. Dimension 0 has exactly one inner cell {0}.
// - neighbour k is the cell across the facet opposite vertex slot k (k <= d), kNone where there is
//   none (the hull of a store built without extrapolation, and the far side of a line's end cell,
//   which holds every point beyond that end); slots above d are kNone. An outer cell's neighbour d
//   is the inner cell it rests on; its neighbours below d are outer cells.
// - layout: how the cells are stored (and whether SH records are padded).
//   kLayoutFast: per cell {vertices[4], neighbours[4]} side by side (16 bytes with 16-bit indices, 32
//     with 32-bit: what one walk step reads, in one cache line); SH records padded (see below).
//   kLayoutCompact: per cell vertices[4] only; neighbours are rebuilt when the blob is loaded
//     (core/cell_adjacency.h). SH records packed.
//   kLayoutRebuilt: no cells and no grid are stored (both sections empty); the loader rebuilds them
//     from the decoded positions (core/store_rebuild.h, core/cell_rebuild.h): the inner cells are the
//     exact Delaunay tessellation (TetGen's, ties broken as the builder breaks them), the outer cells
//     those of its hull, in the builder's cell order, with the header's cell_count and
//     inner_cell_count (a rebuild that disagrees refuses the blob), the grid of header.grid cells.
//     cell_count <= 16 probe_count + 64, grid cells <= kMaxStartGridCells and each grid axis at most
//     max(1, n / 8) above the builder's n at 4 inner cells an entry (the work is bounded by the header;
//     the builder gives this layout a coarser grid, start_grid.h). Normals as in other layouts. SH packed.
// - an outer cell sweeps its facet along the probes' normals: vertex k at parameter t >= 0 sits at
//   position_k + t * normal_k, and the cell holds p where the moved facet passes through p.
// - normals: one per hull probe (a probe of some outer cell), in increasing probe order,
//   hull_probe_count of them (0 without extrapolation: no outer cell, no normal), encoded as the
//   positions say (above); finite. Every other probe's normal is zero.
// - sh (sh_encoding): channel-major records, one per probe, of these bytes (fast layout: padded with
//   zeros to the size in brackets, so that no record straddles a cache line):
//   kShHalf      54 [64]: binary16 x 27, [r0..r8, g0..g8, b0..b8].
//   kShHalfL1    24 [32]: binary16 x 12, [r0..r3, g0..g3, b0..b3]; band 2 reads as zero.
//   kShUnorm8    30 [32]: binary16 x 3 (L0 of r, g, b), then uint8 x 24 (coefficients 1..8 of r, g, b).
//   kShUnorm8L1  15 [16]: binary16 x 3 (L0 of r, g, b), then uint8 x 9 (coefficients 1..3 of r, g, b).
//   Every stored half is finite. An 8-bit coefficient i of a channel whose L0 half decodes to L is
//   step_i * (L * float(q - zero_i)) in float (core/sh_encoding.h: the ratio c_i / c_0 a non-negative
//   radiance can reach, quantised over that range with 0 exact).
// - probes and cells are ordered along a space-filling curve (neighbours near each other in memory);
//   cell 0 is near the centre of the probe cloud.
// - grid: gx*gy*gz start cells over [bounds_min, bounds_max] (x fastest) for queries without hint.
// - probe maps, uint16 when input_probe_count <= 65536, else uint32 (store_map_bytes):
//   probe_source: stored probe -> index of the input probe it came from (the survivor of merges);
//   input_remap: input probe -> stored probe; empty when no probe was merged (input_probe_count ==
//   probe_count), when probe_source is a permutation and the loader inverts it.
// - optional scene data (format 4 on). A section a flag does not announce is empty (size 0).
//   occlusion (kFlagOcclusion): per probe 4 bytes, byte i = round(255 * fraction of mixed light i the
//   probe sees) for i < header.occlusion_lights (1..4); the unused bytes are 255 (unshadowed).
//   leak control (kFlagLeakControl, format 6 on): probe pairs of a cell edge that cannot see each other
//   (geometry crosses the segment between them), as lists per probe: leak_offsets[probe_count + 1]
//   (uint32, leak_offsets[0] = 0, non-decreasing, leak_offsets[probe_count] = header.leak_edge_count) and
//   leak_edges (LeakEdge). The edges of probe a are leak_edges[leak_offsets[a], leak_offsets[a+1]), each
//   naming a partner b > a (strictly increasing within a list) and, for each of its two probes (side 0:
//   a, side 1: b), the plane of the first surface the segment meets from that probe: the octahedral code
//   of an integer normal N facing the probe (core/leak_plane.h) and an offset (finite float32), the plane
//   being N . x = offset in local coordinates, with the probe strictly in front (N . p > offset) and its
//   partner strictly behind, exactly; and reach (uint16, 1..65535): where that plane crosses the segment,
//   as reach / 65535 of the way from the probe to its partner (see core/leak_control.h).
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetprobe {

constexpr char kStoreMagic[8] = {'T', 'E', 'T', 'P', 'R', 'O', 'B', 'E'};
constexpr uint32_t kStoreFormatVersion = 6;
constexpr size_t kSectionAlignment = 16;

// Header flags. The C ABI's TP_BUILD_* bits are these same values where they share a meaning (checked
// where it translates); bit 4 was format 4's compact flag, now header.layout.
constexpr uint32_t kFlagNoExtrapolation = 1u;  // no outer cells
constexpr uint32_t kFlagIndex32 = 2u;          // indices are uint32, else uint16
constexpr uint32_t kFlagOcclusion = 8u;        // the occlusion section holds mixed lights' visibility
constexpr uint32_t kFlagLeakControl = 16u;     // the leak sections list probe pairs that cannot see each other
constexpr uint32_t kKnownFlags = kFlagNoExtrapolation | kFlagIndex32 | kFlagOcclusion | kFlagLeakControl;

// header.layout: how the cells are stored (see above). The C ABI's TP_LAYOUT_* are these values.
enum StoreLayout : uint32_t {
    kLayoutFast = 0,     // vertices and neighbours per cell, SH records padded
    kLayoutCompact = 1,  // vertices per cell (neighbours rebuilt on load), SH packed
    kLayoutRebuilt = 2,  // no cells, neighbours or grid: all rebuilt on load
    kLayoutCount
};

// header.sh_encoding (see above). The C ABI's TP_SH_ENCODING_* are these values.
enum ShEncoding : uint32_t {
    kShHalf = 0,
    kShUnorm8 = 1,
    kShHalfL1 = 2,
    kShUnorm8L1 = 3,
    kShEncodingCount
};

// header.position_encoding: of the positions and the normals (see above).
enum PositionEncoding : uint32_t {
    kPositionsFloat32 = 0,
    kPositionsUnorm16 = 1,
    kPositionEncodingCount
};

// Occlusion: bytes per probe (one per mixed light, at most four).
constexpr uint32_t kOcclusionChannels = 4;

enum Section : uint32_t {
    kSectionPositions = 0,      // float32 x 3 | uint16 x 3, x probe_count
    kSectionNormals,            // float32 x 3 | int16 x 2 (octahedral), x hull_probe_count
    kSectionSh,                 // one record per probe (sh_encoding, layout)
    kSectionProbeSource,        // map x probe_count
    kSectionInputRemap,         // map x input_probe_count, or empty when input_probe_count == probe_count
    kSectionCells,              // index x (fast 8 | compact 4 | rebuilt 0) x cell_count
    kSectionGrid,               // index x grid[0]*grid[1]*grid[2] (empty in the rebuilt layout)
    kSectionOcclusion,          // uint8 x 4 x probe_count (kFlagOcclusion), else empty
    kSectionLeakOffsets,        // uint32 x (probe_count + 1) (kFlagLeakControl), else empty
    kSectionLeakEdges,          // LeakEdge x leak_edge_count (kFlagLeakControl), else empty
    kSectionCount
};

// Reserved index values (the top of the index range).
constexpr uint32_t kNone16 = 0xFFFFu, kOuter16 = 0xFFFEu;
constexpr uint32_t kNone32 = 0xFFFFFFFFu, kOuter32 = 0xFFFFFFFEu;
constexpr uint32_t kMaxIndex16 = 0xFFFDu;  // largest count for which 16-bit indices are used
// Probe maps are 16-bit up to this many input probes (every value fits below it).
constexpr uint32_t kMaxMapCount16 = 0x10000u;

#pragma pack(push, 1)
struct StoreHeader {
    char magic[8];
    uint32_t format_version;
    uint32_t header_size;       // 144 + 16 * kSectionCount
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
    uint32_t layout;            // StoreLayout
    uint32_t sh_encoding;       // ShEncoding
    uint32_t position_encoding; // PositionEncoding
    uint32_t hull_probe_count;  // probes with a stored normal (those of the outer cells)
    uint32_t reserved;          // 0
};
// One probe pair that cannot see each other (in the list of the lower probe, a); side 0 is a's wall
// plane, side 1 b's (see above).
struct LeakEdge {
    uint32_t partner;           // b > a
    int16_t normal[2][2];       // octahedral code of each side's integer plane normal, facing its probe
    float offset[2];            // each side's plane: N . x = offset (local)
    uint16_t reach[2];          // where each side's plane crosses the segment, from its probe, / 65535
};
struct SectionEntry {
    uint64_t offset;
    uint64_t size;
};
#pragma pack(pop)

static_assert(sizeof(StoreHeader) == 144, "header layout");
static_assert(sizeof(LeakEdge) == 24, "leak edge layout");
constexpr size_t kHeaderSize = sizeof(StoreHeader) + kSectionCount * sizeof(SectionEntry);
constexpr size_t kChecksumOffset = offsetof(StoreHeader, checksum);
// Where the format version sits in every format (so an older blob is told apart from a corrupt one).
constexpr size_t kFormatVersionOffset = offsetof(StoreHeader, format_version);

// The checksum above, with the 8 bytes at kChecksumOffset read as zero.
uint64_t store_checksum(const uint8_t* data, size_t size);

}  // namespace tetprobe
