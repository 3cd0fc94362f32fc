// Store: loading (copy into aligned memory, validate once) and the accessors.
#include "core/store.h"

#include "core/error.h"
#include "core/cell_adjacency.h"
#include "core/half.h"
#include "core/leak_control.h"
#include "core/locate.h"
#include "core/store_impl.h"
#include "core/store_validation.h"
#include "core/tetrahedron_orientations.h"

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
    if (!(s.header.flags & kFlagCompact)) {
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
    s.sh_halves = (h.flags & kFlagCompact) ? kShHalvesCompact : kShHalvesFast;
    s.avx2 = cpu_has_avx2() && !getenv("TP_NO_AVX2");
    for (int k = 0; k < 3; ++k) s.origin[k] = h.origin[k];
    auto section = [&](Section id) { return base + table[id].offset; };
    s.positions = reinterpret_cast<const float*>(section(kSectionPositions));
    s.normals = reinterpret_cast<const float*>(section(kSectionNormals));
    s.sh = reinterpret_cast<const uint16_t*>(section(kSectionSh));
    s.probe_source = reinterpret_cast<const uint32_t*>(section(kSectionProbeSource));
    s.input_remap = reinterpret_cast<const uint32_t*>(section(kSectionInputRemap));
    s.grid_cells = section(kSectionGrid);
    if (h.flags & kFlagOcclusion) {
        s.occlusion_lights = h.occlusion_lights;
        s.occlusion = section(kSectionOcclusion);
    }
    if (h.flags & kFlagLeakControl) {
        s.leak_offsets = reinterpret_cast<const uint32_t*>(section(kSectionLeakOffsets));
        s.leak_edges = reinterpret_cast<const LeakEdge*>(section(kSectionLeakEdges));
    }
    if (s.index32)
        set_cell_records<uint32_t>(s, section(kSectionCells));
    else
        set_cell_records<uint16_t>(s, section(kSectionCells));
    validate_cell_records(s);
    if (s.leak_offsets) mark_blocked_cells(s);
    return store;
}

const uint8_t* Store::blob_data() const { return impl_->bytes.get(); }
size_t Store::blob_size() const { return impl_->size; }
const StoreHeader& Store::header() const { return impl_->header; }

uint32_t Store::probe_source(uint32_t stored) const {
    return stored < impl_->probe_count ? impl_->probe_source[stored] : kNone32;
}

uint32_t Store::input_to_stored(uint32_t input) const {
    return input < impl_->header.input_probe_count ? impl_->input_remap[input] : kNone32;
}

void Store::probe_sh(uint32_t stored, float out[27]) const {
    if (stored >= impl_->probe_count) {
        std::fill(out, out + 27, 0.0f);
        return;
    }
    halves_to_floats(impl_->sh + size_t(stored) * impl_->sh_halves, out, 27);
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

Location Store::locate(const float world_position[3], int32_t hint) const {
    float q[3];
    local_position(*impl_, world_position, q);
    Location loc = locate_local(*impl_, q, hint);
    if (impl_->leak_offsets && loc.status == Status::ok) weigh_by_visibility(*impl_, loc);
    return loc;
}

Location Store::locate_exhaustive(const float world_position[3], Cells cells) const {
    float q[3];
    local_position(*impl_, world_position, q);
    return tetprobe::locate_exhaustive(*impl_, q, cells == Cells::outer);
}

}  // namespace tetprobe
