// validate_store_blob: every rule of store_format.h, checked once so that queries can trust the data.
#include "core/store_validation.h"

#include "core/error.h"
#include "core/store_format.h"
#include "core/store_layout.h"

#include <cmath>
#include <cstring>
#include <string>

namespace tetprobe {

namespace {

[[noreturn]] void reject(const std::string& what) { throw Error(TP_ERROR_INVALID_BLOB, "invalid store blob: " + what); }

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

void check_finite_floats(const float* values, uint64_t count, const char* section) {
    for (uint64_t i = 0; i < count; ++i)
        if (!std::isfinite(values[i])) reject(at(section, i) + " is not finite");
}

void check_header(const StoreHeader& h, size_t size) {
    if (h.header_size != kHeaderSize)
        reject("header_size is " + std::to_string(h.header_size) + ", expected " + std::to_string(kHeaderSize));
    if (h.section_count != kSectionCount)
        reject("section_count is " + std::to_string(h.section_count) + ", expected " + std::to_string(kSectionCount));
    if (size < kHeaderSize) reject("truncated: " + std::to_string(size) + " bytes, the section table ends at " +
                                   std::to_string(kHeaderSize));
    if (h.reserved != 0) reject("reserved header field is not zero");
    if (h.flags & ~(kFlagIndex32 | kFlagNoExtrapolation)) reject("unknown flags " + std::to_string(h.flags));
    if (h.dimension > 3) reject("dimension " + std::to_string(h.dimension) + " is above 3");
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
        if (!std::isfinite(h.origin[k])) reject("origin is not finite");
        if (!std::isfinite(h.bounds_min[k]) || !std::isfinite(h.bounds_max[k])) reject("bounds are not finite");
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

template <class Index>
void check_cells(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    const Index* vertices = reinterpret_cast<const Index*>(data + table[kSectionCellVertices].offset);
    const Index* neighbours = reinterpret_cast<const Index*>(data + table[kSectionCellNeighbours].offset);
    const Index* grid = reinterpret_cast<const Index*>(data + table[kSectionGrid].offset);
    const uint32_t d = h.dimension;
    const uint32_t inner = h.inner_cell_count;
    const bool may_lack_neighbours = (h.flags & kFlagNoExtrapolation) || d == 0;

    for (uint64_t c = 0; c < h.cell_count; ++c) {
        const bool is_inner = c < inner;
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t v = widen_index(vertices[4 * c + k]);
            if (k > d) {
                if (v != kNone32) reject(at("cell_vertices", 4 * c + k) + " is above the dimension and must be none");
            } else if (!is_inner && k == d) {
                if (v != kOuter32) reject(at("cell_vertices", 4 * c + k) + " of an outer cell must be the outer marker");
            } else if (v >= h.probe_count) {
                reject(at("cell_vertices", 4 * c + k) + " = " + std::to_string(v) + " is not a probe (probe_count " +
                       std::to_string(h.probe_count) + ")");
            }

            const uint32_t n = widen_index(neighbours[4 * c + k]);
            if (k > d) {
                if (n != kNone32) reject(at("cell_neighbours", 4 * c + k) + " is above the dimension and must be none");
            } else if (is_inner) {
                if (n == kNone32 ? !may_lack_neighbours : n >= h.cell_count)
                    reject(at("cell_neighbours", 4 * c + k) + " is not a cell");
            } else if (k == d) {
                if (n >= inner) reject(at("cell_neighbours", 4 * c + k) + " of an outer cell must be the inner cell it rests on");
            } else if (n == kNone32 ? d != 1 : (n < inner || n >= h.cell_count)) {
                reject(at("cell_neighbours", 4 * c + k) + " of an outer cell must be an outer cell");
            }
        }
    }
    // Adjacency is symmetric: a neighbour lists the cell back.
    for (uint64_t c = 0; c < h.cell_count; ++c) {
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t n = widen_index(neighbours[4 * c + k]);
            if (n == kNone32) continue;
            bool listed = false;
            for (uint32_t j = 0; j < 4; ++j) listed |= widen_index(neighbours[4 * uint64_t(n) + j]) == c;
            if (!listed) reject(at("cell_neighbours", 4 * c + k) + " = " + std::to_string(n) + " does not list cell " +
                                std::to_string(c) + " back");
        }
    }
    const uint64_t grid_count = uint64_t(h.grid[0]) * h.grid[1] * h.grid[2];
    for (uint64_t i = 0; i < grid_count; ++i)
        if (widen_index(grid[i]) >= h.cell_count) reject(at("grid", i) + " is not a cell");
}

void check_probes(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    const uint64_t probes = h.probe_count;
    check_finite_floats(reinterpret_cast<const float*>(data + table[kSectionPositions].offset), probes * 3, "positions");
    check_finite_floats(reinterpret_cast<const float*>(data + table[kSectionNormals].offset), probes * 3, "normals");
    const uint16_t* sh = reinterpret_cast<const uint16_t*>(data + table[kSectionSh].offset);
    for (uint64_t i = 0; i < probes * 27; ++i)
        if ((sh[i] & 0x7C00u) == 0x7C00u) reject(at("sh", i) + " is not a finite half");

    const uint32_t* source = reinterpret_cast<const uint32_t*>(data + table[kSectionProbeSource].offset);
    const uint32_t* remap = reinterpret_cast<const uint32_t*>(data + table[kSectionInputRemap].offset);
    for (uint64_t i = 0; i < h.input_probe_count; ++i)
        if (remap[i] >= h.probe_count) reject(at("input_remap", i) + " is not a stored probe");
    for (uint64_t s = 0; s < probes; ++s) {
        if (source[s] >= h.input_probe_count) reject(at("probe_source", s) + " is not an input probe");
        if (remap[source[s]] != s) reject(at("probe_source", s) + " does not map back to the probe through input_remap");
    }
}

// Finite entries, and zero rows where the dimension leaves a matrix unused.
void check_matrices(const uint8_t* data, const StoreHeader& h, const SectionEntry table[kSectionCount]) {
    const float* inner = reinterpret_cast<const float*>(data + table[kSectionInnerMatrices].offset);
    const float* outer = reinterpret_cast<const float*>(data + table[kSectionOuterMatrices].offset);
    const uint64_t inner_count = h.inner_cell_count;
    const uint64_t outer_count = uint64_t(h.cell_count) - h.inner_cell_count;
    check_finite_floats(inner, inner_count * 12, "inner_matrices");
    check_finite_floats(outer, outer_count * 16, "outer_matrices");
    for (uint64_t c = 0; c < inner_count; ++c)
        for (uint32_t r = h.dimension; r < 3; ++r)
            for (int j = 0; j < 4; ++j)
                if (inner[12 * c + 4 * r + j] != 0.0f) reject(at("inner_matrices", 12 * c + 4 * r + j) + " must be zero");
    const uint32_t zero_rows = h.dimension == 1 ? 3 : (h.dimension == 2 ? 1 : 0);
    for (uint64_t c = 0; c < outer_count; ++c)
        for (uint32_t r = 0; r < zero_rows; ++r)
            for (int j = 0; j < 4; ++j)
                if (outer[16 * c + 4 * r + j] != 0.0f) reject(at("outer_matrices", 16 * c + 4 * r + j) + " must be zero");
}

}  // namespace

void validate_store_blob(const uint8_t* data, size_t size) {
    StoreHeader h;
    if (size < sizeof h)
        reject("truncated: " + std::to_string(size) + " bytes, the header alone is " + std::to_string(sizeof h));
    std::memcpy(&h, data, sizeof h);
    if (std::memcmp(h.magic, kStoreMagic, sizeof h.magic) != 0) reject("bad magic (not a tetprobe store)");
    if (h.format_version != kStoreFormatVersion)
        throw Error(TP_ERROR_VERSION, "store blob has format version " + std::to_string(h.format_version) +
                                          "; this library reads version " + std::to_string(kStoreFormatVersion));
    check_header(h, size);
    SectionEntry table[kSectionCount];
    check_sections(data, size, h, table);
    const uint64_t stored = h.checksum;
    const uint64_t computed = store_checksum(data, size);
    if (stored != computed) reject("checksum mismatch (the blob is corrupt)");
    check_probes(data, h, table);
    check_matrices(data, h, table);
    if (h.flags & kFlagIndex32)
        check_cells<uint32_t>(data, h, table);
    else
        check_cells<uint16_t>(data, h, table);
}

}  // namespace tetprobe
