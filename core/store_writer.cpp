// write_store_blob: StoreData -> the format-5 blob laid out as store_format.h describes.
#include "core/error.h"
#include "core/octahedral_normal.h"
#include "core/position_quantization.h"
#include "core/sh_encoding.h"
#include "core/store.h"
#include "core/store_data.h"
#include "core/store_layout.h"

#include <cmath>
#include <cstring>
#include <string>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the store blob is little-endian; this writer copies host memory as is"
#endif

namespace tetprobe {

namespace {


// The message is built only when the condition fails (the per-value checks below run millions of times).
template <class Message>
void require(bool condition, Message&& message) {
    if (!condition) throw Error(Status::invalid_argument, "store data: " + std::string(message()));
}

void require_size(size_t actual, uint64_t expected, const char* what) {
    require(actual == expected, [&] { return std::string(what) + " has " + std::to_string(actual) + " values, expected " +
                                    std::to_string(expected); });
}

void require_finite(const std::vector<float>& values, const char* what) {
    for (size_t i = 0; i < values.size(); ++i)
        require(std::isfinite(values[i]), [&] { return std::string(what) + "[" + std::to_string(i) + "] is not finite"; });
}

// Copies indices at the blob's width: 32-bit as is, 16-bit with the reserved values remapped.
void write_indices(uint8_t* out, const std::vector<uint32_t>& indices, bool index32, const char* what) {
    if (index32) {
        if (!indices.empty()) std::memcpy(out, indices.data(), indices.size() * sizeof(uint32_t));
        return;
    }
    for (size_t i = 0; i < indices.size(); ++i) {
        const uint32_t value = indices[i];
        uint16_t narrow;
        if (value == kNone32)
            narrow = uint16_t(kNone16);
        else if (value == kOuter32)
            narrow = uint16_t(kOuter16);
        else {
            require(value <= kMaxIndex16, [&] { return std::string(what) + "[" + std::to_string(i) + "] = " +
                                              std::to_string(value) + " does not fit a 16-bit index"; });
            narrow = uint16_t(value);
        }
        std::memcpy(out + i * sizeof narrow, &narrow, sizeof narrow);
    }
}

// Probe maps at the blob's width (16 or 32 bits).
void write_map(uint8_t* out, const std::vector<uint32_t>& map, uint64_t width) {
    for (size_t i = 0; i < map.size(); ++i) {
        if (width == 4) {
            std::memcpy(out + 4 * i, &map[i], 4);
        } else {
            const uint16_t narrow = uint16_t(map[i]);
            std::memcpy(out + 2 * i, &narrow, 2);
        }
    }
}

// Probes of the outer cells (the hull probes whose normals are stored), ascending.
std::vector<uint32_t> hull_probes(const StoreData& data) {
    std::vector<bool> on_hull(data.probe_count(), false);
    for (size_t c = data.inner_cell_count; c < data.cell_count(); ++c)
        for (uint32_t k = 0; k < data.dimension; ++k) {
            const uint32_t v = data.cell_vertices[4 * c + k];
            require(v < data.probe_count(), [&] { return "cell " + std::to_string(c) + " names no probe"; });
            on_hull[v] = true;
        }
    std::vector<uint32_t> hull;
    for (uint32_t p = 0; p < data.probe_count(); ++p)
        if (on_hull[p]) hull.push_back(p);
    return hull;
}

// Hull normals non-zero (and with quantised positions on the octahedral grid), every other normal
// zero (what the blob can hold).
void require_storable_normals(const StoreData& data, const std::vector<uint32_t>& hull) {
    std::vector<bool> on_hull(data.probe_count(), false);
    for (uint32_t p : hull) on_hull[p] = true;
    for (uint32_t p = 0; p < data.probe_count(); ++p) {
        const float* n = &data.normals[3 * size_t(p)];
        if (!on_hull[p]) {
            require(n[0] == 0 && n[1] == 0 && n[2] == 0,
                    [&] { return "normal of probe " + std::to_string(p) + ", not on the hull, is not zero"; });
            continue;
        }
        require(n[0] != 0 || n[1] != 0 || n[2] != 0, [&] { return "normal of hull probe " + std::to_string(p) + " is zero"; });
        if (data.position_encoding != kPositionsUnorm16) continue;
        const double wide[3] = {n[0], n[1], n[2]};
        float stored[3];
        quantize_normal(wide, stored);
        require(stored[0] == n[0] && stored[1] == n[1] && stored[2] == n[2], [&] {
            return "normal of hull probe " + std::to_string(p) + " is not on the octahedral grid (quantize_normal)";
        });
    }
}

// Positions inside the bounds, and for quantised positions on their grid.
void require_storable_positions(const StoreData& data) {
    for (size_t i = 0; i < data.positions.size(); ++i) {
        const float p = data.positions[i], lo = data.bounds_min[i % 3], hi = data.bounds_max[i % 3];
        require(p >= lo && p <= hi, [&] { return "positions[" + std::to_string(i) + "] lies outside the bounds"; });
        if (data.position_encoding == kPositionsUnorm16)
            require(quantize_position(p, lo, hi) == p,
                    [&] { return "positions[" + std::to_string(i) + "] is not on the quantisation grid of the bounds"; });
    }
}

}  // namespace

std::vector<uint8_t> write_store_blob(const StoreData& data) {
    const uint64_t probes = data.probe_source.size();
    const uint64_t cells = data.cell_vertices.size() / 4;
    require(probes >= 1, [&] { return "no probes"; });
    require(probes < kOuter32 && cells < kOuter32 && data.input_probe_count < kOuter32, [&] { return "counts do not fit 32-bit indices"; });
    require(data.cell_vertices.size() % 4 == 0, [&] { return "cell_vertices is not 4 per cell"; });
    require(data.dimension <= 3, [&] { return "dimension " + std::to_string(data.dimension) + " is above 3"; });
    require(data.axis <= 2, [&] { return "axis " + std::to_string(data.axis) + " is above 2"; });
    require(data.inner_cell_count <= cells, [&] { return "inner_cell_count exceeds the cell count"; });
    require(data.layout < kLayoutCount && data.sh_encoding < kShEncodingCount &&
                data.position_encoding < kPositionEncodingCount,
            [&] { return "unknown layout or encoding"; });
    require_size(data.positions.size(), probes * 3, "positions");
    require_size(data.normals.size(), probes * 3, "normals");
    require_size(data.sh.size(), probes * 27, "sh");
    require_size(data.input_remap.size(), data.input_probe_count, "input_remap");
    require_size(data.cell_neighbours.size(), cells * 4, "cell_neighbours");
    require_size(data.grid_cells.size(), uint64_t(data.grid[0]) * data.grid[1] * data.grid[2], "grid_cells");
    require_finite(data.positions, "positions");
    require_finite(data.normals, "normals");
    for (int k = 0; k < 3; ++k)
        require(std::isfinite(data.origin[k]) && std::isfinite(data.bounds_min[k]) &&
                    std::isfinite(data.bounds_max[k]) && data.bounds_min[k] <= data.bounds_max[k],
                [&] { return "origin or bounds not finite, or bounds not ordered"; });
    for (size_t i = 0; i < data.sh.size(); ++i)
        require(std::isfinite(data.sh[i]), [&] { return "sh[" + std::to_string(i) + "] is not finite"; });
    require_storable_positions(data);
    const std::vector<uint32_t> hull = hull_probes(data);
    require_storable_normals(data, hull);
    for (size_t j = 0; j < probes; ++j)
        require(data.probe_source[j] < data.input_probe_count,
                [&] { return "probe_source[" + std::to_string(j) + "] is not an input probe"; });
    for (size_t i = 0; i < data.input_remap.size(); ++i)
        require(data.input_remap[i] < probes, [&] { return "input_remap[" + std::to_string(i) + "] is not a stored probe"; });
    const bool remap_stored = data.input_probe_count != probes;
    if (!remap_stored)
        for (uint32_t i = 0; i < probes; ++i)
            require(data.probe_source[data.input_remap[i]] == i,
                    [&] { return "no probe was merged, but input_remap is not probe_source inverted"; });

    require(data.occlusion_lights <= kOcclusionChannels, [&] { return "more than 4 occlusion lights"; });
    if (data.occlusion_lights > 0) {
        require_size(data.occlusion.size(), probes * kOcclusionChannels, "occlusion");
        for (size_t i = 0; i < data.occlusion.size(); ++i)
            require(i % kOcclusionChannels < data.occlusion_lights || data.occlusion[i] == 255,
                    [&] { return "occlusion[" + std::to_string(i) + "] of an unused channel is not 255"; });
    }
    const bool leak = !data.leak_offsets.empty();
    if (leak) {
        require_size(data.leak_offsets.size(), probes + 1, "leak_offsets");
        require(data.leak_offsets[0] == 0 && data.leak_offsets.back() == data.leak_edges.size(),
                [&] { return "leak_offsets do not span leak_edges"; });
    } else {
        require(data.leak_edges.empty(), [&] { return "leak_edges without leak_offsets"; });
    }

    const bool index32 =
        (data.flags & kFlagIndex32) || probes > kMaxIndex16 || cells > kMaxIndex16;

    StoreHeader header;
    std::memset(&header, 0, sizeof header);
    std::memcpy(header.magic, kStoreMagic, sizeof header.magic);
    header.format_version = kStoreFormatVersion;
    header.header_size = uint32_t(kHeaderSize);
    header.flags = (data.flags & kFlagNoExtrapolation) | (index32 ? kFlagIndex32 : 0u) |
                   (data.occlusion_lights > 0 ? kFlagOcclusion : 0u) | (leak ? kFlagLeakControl : 0u);
    header.occlusion_lights = data.occlusion_lights;
    header.leak_edge_count = uint32_t(data.leak_edges.size());
    header.layout = data.layout;
    header.sh_encoding = data.sh_encoding;
    header.position_encoding = data.position_encoding;
    header.hull_probe_count = uint32_t(hull.size());
    header.dimension = data.dimension;
    header.axis = data.dimension == 1 || data.dimension == 2 ? data.axis : 0;
    header.probe_count = uint32_t(probes);
    header.input_probe_count = data.input_probe_count;
    header.cell_count = uint32_t(cells);
    header.inner_cell_count = data.inner_cell_count;
    for (int k = 0; k < 3; ++k) {
        header.grid[k] = data.grid[k];
        header.origin[k] = data.origin[k];
        header.bounds_min[k] = data.bounds_min[k];
        header.bounds_max[k] = data.bounds_max[k];
    }
    header.section_count = kSectionCount;

    uint64_t sizes[kSectionCount];
    require(expected_section_sizes(header, sizes), [&] { return "section sizes overflow"; });
    SectionEntry table[kSectionCount];
    uint64_t end = kHeaderSize;
    for (uint32_t s = 0; s < kSectionCount; ++s) {
        table[s].offset = align_section_offset(end);
        table[s].size = sizes[s];
        end = table[s].offset + sizes[s];
    }

    std::vector<uint8_t> blob(end, 0);  // zero fill is the padding between sections
    uint8_t* base = blob.data();
    std::memcpy(base, &header, sizeof header);
    std::memcpy(base + sizeof header, table, sizeof table);
    auto copy_floats = [&](Section s, const std::vector<float>& v) {
        if (!v.empty()) std::memcpy(base + table[s].offset, v.data(), v.size() * sizeof(float));
    };
    auto copy_words = [&](Section s, const std::vector<uint32_t>& v) {
        if (!v.empty()) std::memcpy(base + table[s].offset, v.data(), v.size() * sizeof(uint32_t));
    };
    uint8_t* positions = base + table[kSectionPositions].offset;
    if (data.position_encoding == kPositionsUnorm16) {
        for (size_t i = 0; i < data.positions.size(); ++i) {
            const uint16_t q = encode_position(data.positions[i], data.bounds_min[i % 3], data.bounds_max[i % 3]);
            std::memcpy(positions + 2 * i, &q, sizeof q);
        }
    } else {
        copy_floats(kSectionPositions, data.positions);
    }
    for (size_t i = 0; i < hull.size(); ++i) {
        const float* n = &data.normals[3 * size_t(hull[i])];
        if (data.position_encoding != kPositionsUnorm16) {
            std::memcpy(base + table[kSectionNormals].offset + 12 * i, n, 3 * sizeof(float));
            continue;
        }
        const double wide[3] = {n[0], n[1], n[2]};
        int16_t code[2];
        encode_normal(wide, code);
        std::memcpy(base + table[kSectionNormals].offset + 4 * i, code, sizeof code);
    }
    const uint32_t record = sh_record_bytes(data.sh_encoding, data.layout == kLayoutFast);
    for (size_t p = 0; p < probes; ++p)
        encode_sh_record(data.sh_encoding, &data.sh[27 * p], base + table[kSectionSh].offset + p * record);
    const uint64_t map_bytes = store_map_bytes(data.input_probe_count);
    write_map(base + table[kSectionProbeSource].offset, data.probe_source, map_bytes);
    if (remap_stored) write_map(base + table[kSectionInputRemap].offset, data.input_remap, map_bytes);
    // Fast: {vertices[4], neighbours[4]} per cell; compact: vertices[4] only; rebuilt: nothing.
    const bool fast = data.layout == kLayoutFast;
    std::vector<uint32_t> cell_indices;
    if (data.layout != kLayoutRebuilt) {
        cell_indices.reserve(cells * (fast ? 8 : 4));
        for (size_t c = 0; c < cells; ++c) {
            cell_indices.insert(cell_indices.end(), &data.cell_vertices[4 * c], &data.cell_vertices[4 * c] + 4);
            if (fast)
                cell_indices.insert(cell_indices.end(), &data.cell_neighbours[4 * c], &data.cell_neighbours[4 * c] + 4);
        }
    }
    write_indices(base + table[kSectionCells].offset, cell_indices, index32, "cells");
    if (data.layout != kLayoutRebuilt) write_indices(base + table[kSectionGrid].offset, data.grid_cells, index32, "grid_cells");
    if (data.occlusion_lights > 0)
        std::memcpy(base + table[kSectionOcclusion].offset, data.occlusion.data(), data.occlusion.size());
    if (leak) {
        copy_words(kSectionLeakOffsets, data.leak_offsets);
        if (!data.leak_edges.empty())
            std::memcpy(base + table[kSectionLeakEdges].offset, data.leak_edges.data(),
                        data.leak_edges.size() * sizeof(LeakEdge));
    }

    const uint64_t checksum = store_checksum(base, blob.size());
    std::memcpy(base + kChecksumOffset, &checksum, sizeof checksum);
    return blob;
}

}  // namespace tetprobe
