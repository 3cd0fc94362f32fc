// rebuild_store_cells: the rebuilt layout's cells, neighbours and start grid, from the stored probes.
#include "core/store_rebuild.h"

#include "core/cell_rebuild.h"
#include "core/error.h"
#include "core/store_format.h"

#include <cstring>
#include <new>
#include <string>

namespace tetprobe {

namespace {

[[noreturn]] void reject(const std::string& what) { throw Error(Status::invalid_blob, "invalid store blob: " + what); }

template <class Index>
Index narrow_index(uint32_t value) {
    if (sizeof(Index) == 2) {
        if (value == kNone32) return Index(kNone16);
        if (value == kOuter32) return Index(kOuter16);
    }
    return Index(value);
}

// The walk's records and the start grid in the blob's index width, as the other layouts hold them.
template <class Index>
void set_records(Store::Impl& s, const RebuiltCells& r) {
    s.rebuilt_cells = aligned_bytes(size_t(s.cell_count) * sizeof(CellRecord<Index>));
    auto* records = reinterpret_cast<CellRecord<Index>*>(s.rebuilt_cells.get());
    for (size_t c = 0; c < s.cell_count; ++c)
        for (size_t k = 0; k < 4; ++k) {
            records[c].vertices[k] = narrow_index<Index>(r.cell_vertices[4 * c + k]);
            records[c].neighbours[k] = narrow_index<Index>(r.cell_neighbours[4 * c + k]);
        }
    s.cells = records;
    s.rebuilt_grid = aligned_bytes(r.grid_cells.size() * sizeof(Index));
    auto* grid = reinterpret_cast<Index*>(s.rebuilt_grid.get());
    for (size_t i = 0; i < r.grid_cells.size(); ++i) grid[i] = narrow_index<Index>(r.grid_cells[i]);
    s.grid_cells = grid;
}

}  // namespace

void rebuild_store_cells(Store::Impl& s) {
    const StoreHeader& h = s.header;
    RebuiltCells r;
    try {
        r = rebuild_cells(s.positions, h.probe_count, h.dimension, h.axis, !(h.flags & kFlagNoExtrapolation), h.bounds_min,
                          h.bounds_max, h.grid, rebuilt_cell_budget(h.cell_count));
    } catch (const Error& e) {
        reject("its probes cannot be tessellated again (" + std::string(e.what()) + ")");
    }
    const uint64_t cells = r.cell_vertices.size() / 4;
    if (r.inner_cell_count != h.inner_cell_count || cells != h.cell_count)
        reject("its probes tessellate into " + std::to_string(r.inner_cell_count) + " inner and " +
               std::to_string(cells - r.inner_cell_count) + " outer cells, the header says " +
               std::to_string(h.inner_cell_count) + " and " + std::to_string(h.cell_count - h.inner_cell_count));
    if (s.index32)
        set_records<uint32_t>(s, r);
    else
        set_records<uint16_t>(s, r);
}

}  // namespace tetprobe
