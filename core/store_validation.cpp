// validate_store_blob and validate_cell_records: every rule of store_format.h, checked once so that
// queries can trust the data.
#include "core/store_validation.h"

#include "core/coordinate_limits.h"
#include "core/error.h"
#include "core/orientation.h"
#include "core/plane_projection.h"
#include "core/sh_encoding.h"
#include "core/store_format.h"
#include "core/start_grid.h"
#include "core/store_layout.h"
#include "core/store_rebuild.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace tetprobe {

namespace {

[[noreturn]] void reject(const std::string& what) { throw Error(Status::invalid_blob, "invalid store blob: " + what); }

std::string at(const char* section, uint64_t index) { return std::string(section) + "[" + std::to_string(index) + "]"; }

// Indices of either width, read as uint32 with the reserved values widened to kNone32 / kOuter32.
template <class Index>
uint32_t widen_index(Index value) {
    if (sizeof(Index) == 2) {
        if (value == kNone16) return kNone32;
        if (value == kOuter16) return kOuter32;
    }
    return uint32_t(value);
}

std::string describe(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

void check_finite_floats(const float* values, uint64_t count, const char* section) {
    for (uint64_t i = 0; i < count; ++i)
        if (!std::isfinite(values[i])) reject(at(section, i) + " is not finite");
}

// The header's bounds are the positions' bounding box, exactly (as the builder computes them), so
// every position is within the local coordinate limit the header check applied to the bounds.
void check_bounds(const float* positions, const StoreHeader& h) {
    for (uint32_t k = 0; k < 3; ++k) {
        float lo = positions[k], hi = positions[k];
        for (uint64_t p = 1; p < h.probe_count; ++p) {
            const float x = positions[3 * p + k];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        if (lo != h.bounds_min[k] || hi != h.bounds_max[k])
            reject("bounds along axis " + std::to_string(k) + " are [" + describe(h.bounds_min[k]) + ", " +
                   describe(h.bounds_max[k]) + "], the positions span [" + describe(lo) + ", " + describe(hi) + "]");
    }
}

// Normals are unit vectors (hull probes) or zero: every component within [-1, 1].
void check_normals(const float* normals, uint64_t count) {
    for (uint64_t i = 0; i < count; ++i)
        if (!(std::fabs(normals[i]) <= 1.0f)) reject(at("normals", i) + " is " + describe(normals[i]) + ", outside [-1, 1]");
}

void check_header(const StoreHeader& h, size_t size) {
    if (h.header_size != kHeaderSize)
        reject("header_size is " + std::to_string(h.header_size) + ", expected " + std::to_string(kHeaderSize));
    if (h.section_count != kSectionCount)
        reject("section_count is " + std::to_string(h.section_count) + ", expected " + std::to_string(kSectionCount));
    if (size < kHeaderSize) reject("truncated: " + std::to_string(size) + " bytes, the section table ends at " +
                                   std::to_string(kHeaderSize));
    if (h.reserved != 0) reject("reserved header field is not zero");
    if (h.layout >= kLayoutCount) reject("layout " + std::to_string(h.layout) + " is unknown (0 fast, 1 compact, 2 rebuilt)");
    if (h.sh_encoding >= kShEncodingCount)
        reject("sh_encoding " + std::to_string(h.sh_encoding) + " is unknown (0 half, 1 unorm8, 2 half_l1, 3 unorm8_l1)");
    if (h.position_encoding >= kPositionEncodingCount)
        reject("position_encoding " + std::to_string(h.position_encoding) + " is unknown (0 float32, 1 unorm16)");
    const bool occlusion = (h.flags & kFlagOcclusion) != 0;
    if (occlusion != (h.occlusion_lights != 0) || h.occlusion_lights > kOcclusionChannels)
        reject("occlusion_lights is " + std::to_string(h.occlusion_lights) + ", expected " +
               (occlusion ? "1 to 4 with the occlusion flag" : "0 without the occlusion flag"));
    if (!(h.flags & kFlagLeakControl) && h.leak_edge_count != 0)
        reject("leak_edge_count is " + std::to_string(h.leak_edge_count) + " without the leak-control flag");
    if (h.flags & ~kKnownFlags) reject("unknown flags " + std::to_string(h.flags));
    if (h.dimension > 3) reject("dimension " + std::to_string(h.dimension) + " is above 3");
    if (h.axis > 2 || ((h.dimension == 0 || h.dimension == 3) && h.axis != 0))
        reject("axis " + std::to_string(h.axis) + " does not fit dimension " + std::to_string(h.dimension));
    if (h.probe_count < 1) reject("probe_count is 0");
    if (h.input_probe_count < h.probe_count) reject("input_probe_count is below probe_count");
    if (h.inner_cell_count < 1) reject("inner_cell_count is 0");
    if (h.inner_cell_count > h.cell_count) reject("inner_cell_count exceeds cell_count");
    if (h.dimension == 0 && (h.cell_count != 1 || h.probe_count != 1))
        reject("a dimension-0 store must have exactly 1 probe and 1 cell");
    if ((h.flags & kFlagNoExtrapolation) && h.cell_count != h.inner_cell_count)
        reject("a store without extrapolation has outer cells");
    if (h.hull_probe_count > h.probe_count) reject("hull_probe_count exceeds probe_count");
    if (h.cell_count == h.inner_cell_count && h.hull_probe_count != 0)
        reject("hull_probe_count is " + std::to_string(h.hull_probe_count) + " in a store without outer cells");
    if (h.layout == kLayoutRebuilt) {
        // What the loader will rebuild, bounded before it starts (store_rebuild.h): the cells the probes
        // may make, and the start grid, which no section's size bounds in this layout.
        if (uint64_t(h.cell_count) > kMaxRebuiltCellsPerProbe * h.probe_count + kRebuiltCellSlack)
            reject("cell_count " + std::to_string(h.cell_count) + " exceeds the rebuilt layout's " +
                   std::to_string(kMaxRebuiltCellsPerProbe) + " cells a probe (+" + std::to_string(kRebuiltCellSlack) + ")");
        if (h.grid[0] > kMaxStartGridCells || h.grid[1] > kMaxStartGridCells || h.grid[2] > kMaxStartGridCells ||
            uint64_t(h.grid[0]) * h.grid[1] * h.grid[2] > kMaxStartGridCells)
            reject("the start grid has more than " + std::to_string(kMaxStartGridCells) + " cells");
        // Filling the grid walks once per entry, and no section's size pays for it here: a few bytes could
        // ask for millions of walks. The builder's finest dimensions for these bounds and cells (those of the
        // stored layouts, which rebuilt blobs of earlier builders have too) bound it; the margin (an eighth,
        // at least one, per axis) absorbs another platform's std::pow rounding.
        uint32_t builder[3];
        start_grid_dimensions(h.bounds_min, h.bounds_max, h.inner_cell_count, kStoredStartGridCellsPerEntry, builder);
        for (int a = 0; a < 3; ++a)
            if (h.grid[a] > builder[a] + std::max(1u, builder[a] / 8))
                reject("the start grid " + std::to_string(h.grid[0]) + " x " + std::to_string(h.grid[1]) + " x " +
                       std::to_string(h.grid[2]) + " is larger than the builder's finest " + std::to_string(builder[0]) + " x " +
                       std::to_string(builder[1]) + " x " + std::to_string(builder[2]) + " for these bounds and cells");
    }
    const uint32_t max_count = (h.flags & kFlagIndex32) ? kOuter32 - 1 : kMaxIndex16;
    if (h.probe_count > max_count || h.cell_count > max_count)
        reject("probe_count or cell_count does not fit the index width");
    for (int k = 0; k < 3; ++k) {
        if (h.grid[k] < 1) reject("grid has 0 cells along an axis");
        // What the builder writes: an origin within its coordinate limit, local bounds within the local one.
        if (!(std::fabs(h.origin[k]) <= kMaxCoordinate))
            reject("origin[" + std::to_string(k) + "] is " + describe(h.origin[k]) + ", beyond the builder's limit of 1e30");
        for (const float bound : {h.bounds_min[k], h.bounds_max[k]})
            if (!(std::fabs(double(bound)) <= kMaxLocalCoordinate))
                reject("bounds along axis " + std::to_string(k) + " reach " + describe(bound) +
                       ", beyond the builder's limit of 2e30 from the origin");
        if (!(h.bounds_min[k] <= h.bounds_max[k])) reject("bounds_min exceeds bounds_max");
    }
}

// Offsets, sizes, alignment, order, zero padding and no trailing bytes.
void check_sections(const uint8_t* data, size_t size, const StoreHeader& h, SectionEntry table[kSectionCount]) {
    uint64_t expected[kSectionCount];
    if (!expected_section_sizes(h, expected)) reject("section sizes implied by the counts overflow");
    std::memcpy(table, data + sizeof(StoreHeader), kSectionCount * sizeof(SectionEntry));
    uint64_t end = kHeaderSize;
    for (uint32_t s = 0; s < kSectionCount; ++s) {
        const SectionEntry& e = table[s];
        const std::string name = "section " + std::to_string(s);
        if (e.offset % kSectionAlignment != 0) reject(name + " is not 16-byte aligned");
        if (e.offset < end) reject(name + " overlaps the previous section or is out of order");
        if (e.offset - end >= kSectionAlignment) reject(name + " leaves a gap larger than its alignment padding");
        if (e.size != expected[s])
            reject(name + " has " + std::to_string(e.size) + " bytes, the counts imply " + std::to_string(expected[s]));
        if (e.offset > size || e.size > size - e.offset) reject(name + " extends past the end (truncated blob)");
        for (uint64_t i = end; i < e.offset; ++i)
            if (data[i] != 0) reject("non-zero padding before " + name);
        end = e.offset + e.size;
    }
    if (end != size) reject(std::to_string(size - end) + " trailing bytes after the last section");
}

// Vertex slots (and, in the fast layout, neighbour indices by range) of every cell; grid entries.
template <class Index>
void check_cell_indices(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    if (h.layout == kLayoutRebuilt) return;  // no cells and no grid stored
    const bool compact = h.layout == kLayoutCompact;
    const uint32_t stride = compact ? 4 : 8;
    const Index* cells = reinterpret_cast<const Index*>(data + table[kSectionCells].offset);
    const Index* grid = reinterpret_cast<const Index*>(data + table[kSectionGrid].offset);
    const uint32_t d = h.dimension;
    for (uint64_t c = 0; c < h.cell_count; ++c) {
        const bool is_inner = c < h.inner_cell_count;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint64_t i = stride * c + k;
            const uint32_t v = widen_index(cells[i]);
            if (k > d) {
                if (v != kNone32) reject(at("cells", i) + " is a vertex slot above the dimension and must be none");
            } else if (!is_inner && k == d) {
                if (v != kOuter32) reject(at("cells", i) + " of an outer cell must be the outer marker");
            } else if (v >= h.probe_count) {
                reject(at("cells", i) + " = " + std::to_string(v) + " is not a probe (probe_count " +
                       std::to_string(h.probe_count) + ")");
            }
            if (compact) continue;
            const uint32_t n = widen_index(cells[i + 4]);
            if (n != kNone32 && n >= h.cell_count) reject(at("cells", i + 4) + " = " + std::to_string(n) + " is not a cell");
        }
    }
    const uint64_t grid_count = uint64_t(h.grid[0]) * h.grid[1] * h.grid[2];
    for (uint64_t i = 0; i < grid_count; ++i)
        if (widen_index(grid[i]) >= h.cell_count) reject(at("grid", i) + " is not a cell");
}

// Float32 positions finite and spanning exactly the bounds, float32 hull normals within [-1, 1].
// Quantised positions decode inside the bounds (their quantisation box, checked in the header) and
// octahedral normals to unit vectors by construction.
void check_positions(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    if (h.position_encoding == kPositionsUnorm16) return;
    check_normals(reinterpret_cast<const float*>(data + table[kSectionNormals].offset), uint64_t(h.hull_probe_count) * 3);
    const float* positions = reinterpret_cast<const float*>(data + table[kSectionPositions].offset);
    check_finite_floats(positions, uint64_t(h.probe_count) * 3, "positions");
    check_bounds(positions, h);
}

// Every record's halves finite, the fast layout's padding zero.
void check_sh(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    const ShEncoding encoding = ShEncoding(h.sh_encoding);
    const uint64_t stride = sh_record_bytes(encoding, h.layout == kLayoutFast);
    const uint64_t used = sh_record_bytes(encoding, false);
    const uint8_t* sh = data + table[kSectionSh].offset;
    for (uint64_t p = 0; p < h.probe_count; ++p) {
        const uint8_t* record = sh + p * stride;
        const int bad = first_nonfinite_sh_half(encoding, record);
        if (bad >= 0) reject("sh of probe " + std::to_string(p) + ": half " + std::to_string(bad) + " is not finite");
        for (uint64_t i = used; i < stride; ++i)
            if (record[i] != 0) reject("sh of probe " + std::to_string(p) + ": byte " + std::to_string(i) + " is padding and must be zero");
    }
}

template <class Map>
void check_maps_of_width(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    const Map* source = reinterpret_cast<const Map*>(data + table[kSectionProbeSource].offset);
    const Map* remap = reinterpret_cast<const Map*>(data + table[kSectionInputRemap].offset);
    if (h.input_probe_count == h.probe_count) {
        // No remap stored: probe_source must be a permutation, which the loader inverts.
        std::vector<bool> seen(h.input_probe_count, false);
        for (uint64_t s = 0; s < h.probe_count; ++s) {
            if (source[s] >= h.input_probe_count) reject(at("probe_source", s) + " is not an input probe");
            if (seen[source[s]]) reject(at("probe_source", s) + " repeats an input probe (no probe was merged)");
            seen[source[s]] = true;
        }
        return;
    }
    for (uint64_t i = 0; i < h.input_probe_count; ++i)
        if (remap[i] >= h.probe_count) reject(at("input_remap", i) + " is not a stored probe");
    for (uint64_t s = 0; s < h.probe_count; ++s) {
        if (source[s] >= h.input_probe_count) reject(at("probe_source", s) + " is not an input probe");
        if (remap[source[s]] != s) reject(at("probe_source", s) + " does not map back to the probe through input_remap");
    }
}

void check_maps(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    if (store_map_bytes(h.input_probe_count) == 2)
        check_maps_of_width<uint16_t>(data, h, table);
    else
        check_maps_of_width<uint32_t>(data, h, table);
}

// Occlusion bytes of unused channels, and the leak lists: offsets spanning the edges, partners above
// their probe, increasing, in range; wall plane offsets finite, reaches above 0 (that the planes separate
// their pairs is checked once the positions are decoded, core/leak_control.h).
void check_scene_data(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    if (h.flags & kFlagOcclusion) {
        const uint8_t* occlusion = data + table[kSectionOcclusion].offset;
        for (uint64_t i = 0; i < uint64_t(h.probe_count) * kOcclusionChannels; ++i)
            if (i % kOcclusionChannels >= h.occlusion_lights && occlusion[i] != 255)
                reject(at("occlusion", i) + " belongs to no mixed light and must be 255");
    }
    if (!(h.flags & kFlagLeakControl)) return;
    const uint32_t* offsets = reinterpret_cast<const uint32_t*>(data + table[kSectionLeakOffsets].offset);
    const LeakEdge* edges = reinterpret_cast<const LeakEdge*>(data + table[kSectionLeakEdges].offset);
    if (offsets[0] != 0) reject("leak_offsets[0] is not 0");
    if (offsets[h.probe_count] != h.leak_edge_count) reject(at("leak_offsets", h.probe_count) + " is not leak_edge_count");
    for (uint64_t a = 0; a < h.probe_count; ++a) {
        if (offsets[a + 1] < offsets[a]) reject(at("leak_offsets", a + 1) + " decreases");
        if (offsets[a + 1] > h.leak_edge_count) reject(at("leak_offsets", a + 1) + " is beyond leak_edge_count");
        for (uint64_t i = offsets[a]; i < offsets[a + 1]; ++i) {
            const LeakEdge& e = edges[i];
            if (e.partner <= a || e.partner >= h.probe_count)
                reject(at("leak_edges", i) + " names partner " + std::to_string(e.partner) + " of probe " +
                       std::to_string(a) + " (must be above it and a probe)");
            if (i > offsets[a] && e.partner <= edges[i - 1].partner) reject(at("leak_edges", i) + " is out of order");
            for (int side = 0; side < 2; ++side) {
                if (!std::isfinite(e.offset[side]))
                    reject(at("leak_edges", i) + " has a wall plane offset that is not finite (side " + std::to_string(side) + ")");
                if (e.reach[side] == 0)
                    reject(at("leak_edges", i) + " has a wall plane at its probe (reach 0, side " + std::to_string(side) + ")");
            }
        }
    }
}

template <class Index>
void check_records(const Store::Impl& s) {
    const auto* records = static_cast<const CellRecord<Index>*>(s.cells);
    const uint32_t d = s.dimension;
    const uint32_t inner = s.inner_cell_count;
    const bool may_lack_neighbours = (s.header.flags & kFlagNoExtrapolation) || d == 0;
    for (uint64_t c = 0; c < s.cell_count; ++c) {
        const CellRecord<Index>& r = records[c];
        const bool is_inner = c < inner;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t n = widen_index(r.neighbours[k]);
            // Built only when a check fails (loading a large store must not build a string per slot).
            auto where = [&] { return "cell " + std::to_string(c) + " neighbour " + std::to_string(k); };
            if (k > d) {
                if (n != kNone32) reject(where() + " is above the dimension and must be none");
                continue;
            }
            if (n == kNone32) {
                // Without extrapolation the hull has no neighbours; a line's outer cell has no outer neighbour.
                const bool allowed = is_inner ? may_lack_neighbours : (d == 1 && k < d);
                if (!allowed) reject(where() + " is missing");
                continue;
            }
            if (n >= s.cell_count) reject(where() + " is not a cell");
            if (!is_inner && k == d && n >= inner) reject(where() + " of an outer cell must be the inner cell it rests on");
            if (!is_inner && k < d && n < inner) reject(where() + " of an outer cell must be an outer cell");
            // The neighbour lists c back and holds every vertex of the facet opposite slot k.
            const CellRecord<Index>& m = records[n];
            bool listed = false;
            for (uint32_t j = 0; j < 4; ++j) listed |= widen_index(m.neighbours[j]) == c;
            if (!listed) reject(where() + " = " + std::to_string(n) + " does not list cell " + std::to_string(c) + " back");
            for (uint32_t j = 0; j <= d; ++j) {
                if (j == k) continue;
                bool shared = false;
                for (uint32_t i = 0; i <= d; ++i) shared |= m.vertices[i] == r.vertices[j];
                if (!shared) reject(where() + " = " + std::to_string(n) + " does not share the facet opposite slot " +
                                    std::to_string(k));
            }
        }
        if (!is_inner || d < 1) continue;
        // Inner cells are positively oriented (or flat), exactly, on the stored positions.
        const float* p[4];
        for (uint32_t k = 0; k <= d; ++k) p[k] = s.positions + 3 * size_t(r.vertices[k]);
        int sign = 1;
        if (d == 3) {
            sign = orient3d(p[0], p[1], p[2], p[3]);
        } else if (d == 2) {
            float uv[3][2];
            for (uint32_t k = 0; k < 3; ++k) project_to_plane(p[k], s.axis, uv[k]);
            sign = orient2d(uv[0], uv[1], uv[2]);
        } else {
            sign = p[1][s.axis] > p[0][s.axis] ? 1 : (p[1][s.axis] == p[0][s.axis] ? 0 : -1);
        }
        if (sign < 0) reject("inner cell " + std::to_string(c) + " is negatively oriented");
        // A line's or a flat set's cells have length (area) in the coordinates the axis field names;
        // zero there means the axis does not match the positions (a tetrahedron may be flat: TetGen's).
        if (sign == 0 && d < 3)
            reject("inner cell " + std::to_string(c) + " has zero " + (d == 1 ? "length along" : "area across") +
                   " axis " + std::to_string(s.axis) + " (the axis does not match the positions)");
    }
}

}  // namespace

void validate_store_blob(const uint8_t* data, size_t size) {
    if (size >= kFormatVersionOffset + sizeof(uint32_t) && std::memcmp(data, kStoreMagic, sizeof kStoreMagic) == 0) {
        uint32_t version;
        std::memcpy(&version, data + kFormatVersionOffset, sizeof version);
        if (version != kStoreFormatVersion)
            throw Error(Status::version, "store blob has format version " + std::to_string(version) +
                                             "; this library reads version " + std::to_string(kStoreFormatVersion) +
                                             ": rebuild the store from its probes with this library");
    }
    StoreHeader h;
    if (size < sizeof h)
        reject("truncated: " + std::to_string(size) + " bytes, the header alone is " + std::to_string(sizeof h));
    std::memcpy(&h, data, sizeof h);
    if (std::memcmp(h.magic, kStoreMagic, sizeof h.magic) != 0) reject("bad magic (not a tetprobe store)");
    check_header(h, size);
    SectionEntry table[kSectionCount];
    check_sections(data, size, h, table);
    const uint64_t stored = h.checksum;
    const uint64_t computed = store_checksum(data, size);
    if (stored != computed) reject("checksum mismatch (the blob is corrupt)");
    check_positions(data, h, table);
    check_sh(data, h, table);
    check_maps(data, h, table);
    check_scene_data(data, h, table);
    if (h.flags & kFlagIndex32)
        check_cell_indices<uint32_t>(data, h, table);
    else
        check_cell_indices<uint16_t>(data, h, table);
}

void validate_cell_records(const Store::Impl& store) {
    if (store.index32)
        check_records<uint32_t>(store);
    else
        check_records<uint16_t>(store);
}

std::vector<uint32_t> hull_probes(const Store::Impl& store) {
    std::vector<bool> on_hull(store.probe_count, false);
    for (uint32_t c = store.inner_cell_count; c < store.cell_count; ++c) {
        for (uint32_t k = 0; k < store.dimension; ++k) {
            const uint32_t v = store.index32 ? static_cast<const CellRecord<uint32_t>*>(store.cells)[c].vertices[k]
                                             : static_cast<const CellRecord<uint16_t>*>(store.cells)[c].vertices[k];
            on_hull[v] = true;
        }
    }
    std::vector<uint32_t> hull;
    for (uint32_t p = 0; p < store.probe_count; ++p)
        if (on_hull[p]) hull.push_back(p);
    if (hull.size() != store.header.hull_probe_count)
        reject("hull_probe_count is " + std::to_string(store.header.hull_probe_count) + " but the outer cells have " +
               std::to_string(hull.size()) + " probes");
    return hull;
}

}  // namespace tetprobe
