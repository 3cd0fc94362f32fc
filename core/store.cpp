// Store: loading (copy into aligned memory, validate once, choose the query kernels) and the
// accessors. The queries are in store_queries.cpp.
#include "core/store.h"

#include "core/error.h"
#include "core/cell_adjacency.h"
#include "core/leak_control.h"
#include "core/locate.h"
#include "core/octahedral_normal.h"
#include "core/position_quantization.h"
#include "core/sh_encoding.h"
#include "core/store_impl.h"
#include "core/store_layout.h"
#include "core/store_rebuild.h"
#include "core/store_validation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>

namespace tetprobe {

AlignedBytes aligned_bytes(size_t size) {
    // No object is larger than PTRDIFF_MAX; refusing those also keeps the rounding up from wrapping.
    if (size > size_t(PTRDIFF_MAX)) throw std::bad_alloc();
    // At least one line, so an empty blob still gets a valid pointer; zero past size (the caller fills the rest).
    const size_t capacity = (std::max(size, size_t(64)) + 63) & ~size_t(63);
    AlignedBytes bytes(static_cast<uint8_t*>(::operator new(capacity, std::align_val_t(64))));
    std::memset(bytes.get() + size, 0, capacity - size);
    return bytes;
}

namespace {

// The walk's cell records: the blob's own (fast layout), or rebuilt from its vertices (compact).
template <class Index>
void set_cell_records(Store::Impl& s, const uint8_t* section) {
    if (s.header.layout == kLayoutFast) {
        s.cells = section;
        return;
    }
    s.rebuilt_cells = aligned_bytes(size_t(s.cell_count) * sizeof(CellRecord<Index>));
    auto* records = reinterpret_cast<CellRecord<Index>*>(s.rebuilt_cells.get());
    const Index* vertices = reinterpret_cast<const Index*>(section);
    for (uint32_t c = 0; c < s.cell_count; ++c)
        std::memcpy(records[c].vertices, vertices + 4 * size_t(c), sizeof records[c].vertices);
    rebuild_neighbours(records, s.cell_count, s.dimension);
    s.cells = records;
}

// Quantised positions decoded to the floats every query decides on (and one float of zeros after them:
// the AVX2 orientations read 16 bytes at a position, see tetrahedron_orientations.h).
void decode_positions(Store::Impl& s, const uint8_t* section) {
    s.decoded_positions = aligned_bytes((size_t(s.probe_count) * 3 + 1) * sizeof(float));
    float* out = reinterpret_cast<float*>(s.decoded_positions.get());
    for (size_t i = 0; i < size_t(s.probe_count) * 3; ++i) {
        uint16_t q;
        std::memcpy(&q, section + 2 * i, sizeof q);
        out[i] = decode_position(q, s.header.bounds_min[i % 3], s.header.bounds_max[i % 3]);
    }
    s.positions = out;
}

// Per probe normals: the hull probes' (decoded), zero elsewhere.
void decode_normals(Store::Impl& s, const uint8_t* section) {
    const size_t bytes = size_t(s.probe_count) * 3 * sizeof(float);
    s.decoded_normals = aligned_bytes(bytes);
    float* out = reinterpret_cast<float*>(s.decoded_normals.get());
    std::memset(out, 0, bytes);
    const std::vector<uint32_t> hull = hull_probes(s);
    const bool quantized = s.header.position_encoding == kPositionsUnorm16;
    for (size_t i = 0; i < hull.size(); ++i) {
        float* normal = out + 3 * size_t(hull[i]);
        if (quantized) {
            int16_t code[2];
            std::memcpy(code, section + 4 * i, sizeof code);
            decode_normal(code, normal);
        } else {
            std::memcpy(normal, section + 12 * i, 3 * sizeof(float));
        }
    }
    s.normals = out;
}

// input_remap, when the blob stores none, as probe_source inverted (a permutation, validated).
template <class Map>
void invert_probe_source(Store::Impl& s) {
    s.inverted_remap = aligned_bytes(size_t(s.probe_count) * sizeof(Map));
    Map* remap = reinterpret_cast<Map*>(s.inverted_remap.get());
    const Map* source = static_cast<const Map*>(s.probe_source);
    for (uint32_t j = 0; j < s.probe_count; ++j) remap[source[j]] = Map(j);
    s.input_remap = remap;
}

template <class Map>
uint32_t map_entry(const void* map, uint32_t i) {
    return static_cast<const Map*>(map)[i];
}

}  // namespace

Store::Store() : impl_(new Impl) {}
Store::~Store() = default;

std::unique_ptr<Store> Store::load(const void* data, size_t size) {
    if (!data && size) throw Error(Status::invalid_argument, "blob data is NULL");
    std::unique_ptr<Store> store(new Store);
    Impl& s = *store->impl_;
    s.bytes = aligned_bytes(size);
    if (size) std::memcpy(s.bytes.get(), data, size);
    s.size = size;
    const uint8_t* base = s.bytes.get();
    validate_store_blob(base, size);

    std::memcpy(&s.header, base, sizeof s.header);
    SectionEntry table[kSectionCount];
    std::memcpy(table, base + sizeof(StoreHeader), sizeof table);
    const StoreHeader& h = s.header;
    s.index32 = (h.flags & kFlagIndex32) != 0;
    s.dimension = h.dimension;
    s.axis = h.axis;
    s.probe_count = h.probe_count;
    s.cell_count = h.cell_count;
    s.inner_cell_count = h.inner_cell_count;
    for (int k = 0; k < 3; ++k) s.origin[k] = h.origin[k];
    auto section = [&](Section id) { return base + table[id].offset; };
    if (h.position_encoding == kPositionsUnorm16)
        decode_positions(s, section(kSectionPositions));
    else
        s.positions = reinterpret_cast<const float*>(section(kSectionPositions));
    s.sh_encoding = ShEncoding(h.sh_encoding);
    s.sh = section(kSectionSh);
    s.sh_stride = sh_record_bytes(s.sh_encoding, h.layout == kLayoutFast);
    s.map16 = store_map_bytes(h.input_probe_count) == 2;
    s.probe_source = section(kSectionProbeSource);
    s.input_remap = section(kSectionInputRemap);
    if (h.input_probe_count == h.probe_count) {
        if (s.map16)
            invert_probe_source<uint16_t>(s);
        else
            invert_probe_source<uint32_t>(s);
    }
    if (h.flags & kFlagOcclusion) {
        s.occlusion_lights = h.occlusion_lights;
        s.occlusion = section(kSectionOcclusion);
    }
    if (h.flags & kFlagLeakControl) {
        s.leak_offsets = reinterpret_cast<const uint32_t*>(section(kSectionLeakOffsets));
        s.leak_edges = reinterpret_cast<const LeakEdge*>(section(kSectionLeakEdges));
    }
    if (h.layout == kLayoutRebuilt) {
        rebuild_store_cells(s);  // cells, neighbours and start grid from the probes (store_rebuild.h)
    } else {
        s.grid_cells = section(kSectionGrid);
        if (s.index32)
            set_cell_records<uint32_t>(s, section(kSectionCells));
        else
            set_cell_records<uint16_t>(s, section(kSectionCells));
    }
    // Rebuilt tetrahedra need no check: core made them from the validated positions with exact
    // predicates, and the rebuild already refused counts that differ from the header's. Rebuilt flat
    // and line cells are checked, since there a forged axis is caught only by their zero area or
    // length (check_records).
    if (h.layout != kLayoutRebuilt || s.dimension < 3) validate_cell_records(s);
    decode_normals(s, section(kSectionNormals));
    if (s.leak_offsets) {
        decode_leak_planes(s);
        check_leak_planes(s);
        mark_blocked_cells(s);
    }
    // The query kernels for this store and CPU, once (store_queries.cpp calls only these).
    const InstructionSet instruction_set = detect_instruction_set();
    s.locate = choose_locate_kernel(s, instruction_set);
    s.blend_sh = sh_blend_function(s.sh_encoding, instruction_set == InstructionSet::avx2);
    return store;
}

const uint8_t* Store::blob_data() const { return impl_->bytes.get(); }
size_t Store::blob_size() const { return impl_->size; }
const StoreHeader& Store::header() const { return impl_->header; }

uint32_t Store::probe_source(uint32_t stored) const {
    if (stored >= impl_->probe_count) return kNone32;
    return impl_->map16 ? map_entry<uint16_t>(impl_->probe_source, stored) : map_entry<uint32_t>(impl_->probe_source, stored);
}

uint32_t Store::input_to_stored(uint32_t input) const {
    if (input >= impl_->header.input_probe_count) return kNone32;
    return impl_->map16 ? map_entry<uint16_t>(impl_->input_remap, input) : map_entry<uint32_t>(impl_->input_remap, input);
}

void Store::probe_sh(uint32_t stored, float out[27]) const {
    if (stored >= impl_->probe_count) {
        std::fill(out, out + 27, 0.0f);
        return;
    }
    decode_sh_record(impl_->sh_encoding, impl_->sh + size_t(stored) * impl_->sh_stride, out);
}

void Store::probe_occlusion(uint32_t stored, uint8_t out[4]) const {
    for (uint32_t i = 0; i < kOcclusionChannels; ++i)
        out[i] = impl_->occlusion && stored < impl_->probe_count ? impl_->occlusion[size_t(stored) * kOcclusionChannels + i]
                                                                 : 255;
}

const float* Store::probe_position(uint32_t stored) const {
    return impl_->positions + 3 * size_t(stored < impl_->probe_count ? stored : 0);
}

namespace {
template <class Index>
void widen_cell(const Store::Impl& s, uint32_t cell, uint32_t vertices[4], uint32_t neighbours[4]) {
    const CellRecord<Index>& r = static_cast<const CellRecord<Index>*>(s.cells)[cell];
    for (int k = 0; k < 4; ++k) {
        vertices[k] = r.vertices[k];
        neighbours[k] = r.neighbours[k];
        if (sizeof(Index) == 2) {
            if (vertices[k] == kOuter16) vertices[k] = kOuter32;
            if (vertices[k] == kNone16) vertices[k] = kNone32;
            if (neighbours[k] == kNone16) neighbours[k] = kNone32;
        }
    }
}
}  // namespace

void Store::cell(uint32_t cell, uint32_t vertices[4], uint32_t neighbours[4]) const {
    if (cell >= impl_->cell_count) cell = 0;
    if (impl_->index32)
        widen_cell<uint32_t>(*impl_, cell, vertices, neighbours);
    else
        widen_cell<uint16_t>(*impl_, cell, vertices, neighbours);
}

}  // namespace tetprobe
