// Store: loading (copy into aligned memory, validate once) and the accessors.
#include "core/store.h"

#include "core/error.h"
#include "core/half.h"
#include "core/locate.h"
#include "core/store_impl.h"
#include "core/store_validation.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tetprobe {

namespace {

AlignedBytes aligned_copy(const void* data, size_t size) {
    // At least one alignment unit, so an empty blob still gets a valid pointer.
    const size_t capacity = std::max(size, kSectionAlignment);
    AlignedBytes bytes(static_cast<uint8_t*>(::operator new(capacity, std::align_val_t(kSectionAlignment))));
    if (size) std::memcpy(bytes.get(), data, size);
    return bytes;
}

// Steps a walk may take before it is considered lost: generous next to the ~N^(1/d) steps of a
// walk across the whole tessellation, so that only a numerical cycle ever reaches it.
uint32_t walk_step_cap(uint32_t cell_count, uint32_t dimension) {
    const double across = std::ceil(std::pow(double(cell_count), 1.0 / double(std::max(dimension, 1u))));
    return uint32_t(std::min(256.0 + 16.0 * across, 1e9));
}

}  // namespace

Store::Store() : impl_(new Impl) {}
Store::~Store() = default;

std::unique_ptr<Store> Store::load(const void* data, size_t size) {
    if (!data && size) throw Error(TP_ERROR_INVALID_ARGUMENT, "blob data is NULL");
    std::unique_ptr<Store> store(new Store);
    Impl& s = *store->impl_;
    s.bytes = aligned_copy(data, size);
    s.size = size;
    const uint8_t* base = s.bytes.get();
    validate_store_blob(base, size);

    std::memcpy(&s.header, base, sizeof s.header);
    SectionEntry table[kSectionCount];
    std::memcpy(table, base + sizeof(StoreHeader), sizeof table);
    const StoreHeader& h = s.header;
    s.index32 = (h.flags & kFlagIndex32) != 0;
    s.dimension = h.dimension;
    s.probe_count = h.probe_count;
    s.cell_count = h.cell_count;
    s.inner_cell_count = h.inner_cell_count;
    s.step_cap = walk_step_cap(h.cell_count, h.dimension);
    for (int k = 0; k < 3; ++k) s.origin[k] = h.origin[k];
    auto section = [&](Section id) { return base + table[id].offset; };
    s.positions = reinterpret_cast<const float*>(section(kSectionPositions));
    s.normals = reinterpret_cast<const float*>(section(kSectionNormals));
    s.sh = reinterpret_cast<const uint16_t*>(section(kSectionSh));
    s.probe_source = reinterpret_cast<const uint32_t*>(section(kSectionProbeSource));
    s.input_remap = reinterpret_cast<const uint32_t*>(section(kSectionInputRemap));
    s.cell_vertices = section(kSectionCellVertices);
    s.cell_neighbours = section(kSectionCellNeighbours);
    s.inner_matrices = reinterpret_cast<const float*>(section(kSectionInnerMatrices));
    s.outer_matrices = reinterpret_cast<const float*>(section(kSectionOuterMatrices));
    s.grid_cells = section(kSectionGrid);
    s.locate = locate_function(s.index32);
    mark_zero_volume_cells(s);
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
    halves_to_floats(impl_->sh + size_t(stored) * 27, out, 27);
}

Location Store::locate(const float world_position[3], int32_t hint) const {
    return impl_->locate(*impl_, world_position, hint);
}

Location Store::locate_exhaustive(const float world_position[3], Cells cells) const {
    double local[3];
    for (int k = 0; k < 3; ++k) local[k] = double(world_position[k]) - impl_->origin[k];
    Location loc;
    if (cells == Cells::all) return tetprobe::locate_exhaustive(*impl_, local);
    if (!locate_exhaustive_outer(*impl_, local, loc)) loc.cell = -1;
    return loc;
}

}  // namespace tetprobe
