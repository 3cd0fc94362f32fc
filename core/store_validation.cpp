// validate_store_blob and validate_cell_records: every rule of store_format.h, checked once so that
// queries can trust the data.
#include "core/store_validation.h"

#include "core/coordinate_limits.h"
#include "core/error.h"
#include "core/orientation.h"
#include "core/plane_projection.h"
#include "core/store_format.h"
#include "core/store_layout.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

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
    const bool compact = (h.flags & kFlagCompact) != 0;
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

void check_probes(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    const uint64_t probes = h.probe_count;
    const float* positions = reinterpret_cast<const float*>(data + table[kSectionPositions].offset);
    check_finite_floats(positions, probes * 3, "positions");
    check_bounds(positions, h);
    check_normals(reinterpret_cast<const float*>(data + table[kSectionNormals].offset), probes * 3);
    const uint64_t halves = (h.flags & kFlagCompact) ? kShHalvesCompact : kShHalvesFast;
    const uint16_t* sh = reinterpret_cast<const uint16_t*>(data + table[kSectionSh].offset);
    for (uint64_t p = 0; p < probes; ++p) {
        for (uint64_t i = 0; i < halves; ++i) {
            const uint16_t value = sh[p * halves + i];
            if (i >= 27 && value != 0) reject(at("sh", p * halves + i) + " is padding and must be zero");
            if ((value & 0x7C00u) == 0x7C00u) reject(at("sh", p * halves + i) + " is not a finite half");
        }
    }
    const uint32_t* source = reinterpret_cast<const uint32_t*>(data + table[kSectionProbeSource].offset);
    const uint32_t* remap = reinterpret_cast<const uint32_t*>(data + table[kSectionInputRemap].offset);
    for (uint64_t i = 0; i < h.input_probe_count; ++i)
        if (remap[i] >= h.probe_count) reject(at("input_remap", i) + " is not a stored probe");
    for (uint64_t s = 0; s < probes; ++s) {
        if (source[s] >= h.input_probe_count) reject(at("probe_source", s) + " is not an input probe");
        if (remap[source[s]] != s) reject(at("probe_source", s) + " does not map back to the probe through input_remap");
    }
}

// Occlusion bytes of unused channels, and the leak lists: offsets spanning the edges, partners above
// their probe, increasing, in range; ramps inside [0, 1] and not empty.
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
            if (!(e.start >= 0.0f && e.start < e.end && e.end <= 1.0f))
                reject(at("leak_edges", i) + " has a ramp outside 0 <= start < end <= 1");
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
    check_probes(data, h, table);
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

}  // namespace tetprobe
