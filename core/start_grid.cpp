#include "core/start_grid.h"

#include "core/error.h"
#include "core/integer_predicates.h"
#include "core/orientation.h"
#include "core/store_format.h"
#include "core/tetrahedron_orientations.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace tetprobe {

namespace {

// Walks the inner cells towards local point p from `cell`, stepping across the first facet (in slot
// order) that has p strictly on its far side, decided by the exact orientation predicates the run
// time uses; stops in a cell that holds p, at the hull, or after a step cap (with exact signs a
// visibility walk on a Delaunay tessellation terminates; the cap only guards flat cells, and any
// inner cell is a valid start). 3D: the four orientations of a cell at once (Kernel, with its filter
// bound; the exact predicate where the filter cannot tell), from positions padded to 4 floats.
template <class Kernel>
uint32_t walk_inner_cells_3d(const StoreData& data, const float* padded, const float p[3], uint32_t cell) {
    const uint32_t inner = data.inner_cell_count;
    const size_t last = data.cell_vertices.size() / 4 - 1;
    for (uint32_t step = 0; step < 4096; ++step) {
        const uint32_t* slots = &data.cell_vertices[size_t(cell) * 4];
        const float* const x[4] = {padded + size_t(slots[0]) * 4, padded + size_t(slots[1]) * 4,
                                   padded + size_t(slots[2]) * 4, padded + size_t(slots[3]) * 4};
        // The walk's next cell is one of these four: fetch their slots while the kernel runs (on a
        // large set each step would otherwise wait on a cache and TLB miss). A missing link (kNone32,
        // a store without outer cells) is clamped to the last cell, so every address is in the arrays.
        const uint32_t* links = &data.cell_neighbours[size_t(cell) * 4];
        for (uint32_t k = 0; k < 4; ++k) {
            const size_t to = std::min<size_t>(links[k], last);
            __builtin_prefetch(data.cell_vertices.data() + to * 4);
            __builtin_prefetch(data.cell_neighbours.data() + to * 4);
        }
        const Orientations o = Kernel::of(x, p);
        uint32_t beyond = 4;  // a slot whose facet has p on its far side
        for (uint32_t k = 0; k < 4 && beyond == 4; ++k) {
            if (o.D[k] > o.bound) continue;
            if (o.D[k] < -o.bound) {
                beyond = k;
            } else {
                const float* z[4] = {x[0], x[1], x[2], x[3]};
                z[k] = p;
                if (orient3d_exact_fast(z[0], z[1], z[2], z[3]) < 0) beyond = k;
            }
        }
        if (beyond == 4) return cell;
        const uint32_t next = data.cell_neighbours[size_t(cell) * 4 + beyond];
        if (next >= inner) return cell;
        cell = next;
    }
    return cell;
}

// The same for lines (along axis) and flat sets (orient2d in the plane coordinates).
uint32_t walk_inner_cells_low(const StoreData& data, const float p[3], uint32_t cell) {
    const uint32_t d = data.dimension, inner = data.inner_cell_count;
    if (d == 0) return 0;
    const uint32_t u = data.axis == 0 ? 1 : 0, v = data.axis == 2 ? 1 : 2;  // 2D plane coordinates
    const float q2[2] = {p[u], p[v]};
    for (uint32_t step = 0; step < 4096; ++step) {
        const uint32_t* slots = &data.cell_vertices[size_t(cell) * 4];
        const float* x[3];
        for (uint32_t k = 0; k <= d; ++k) x[k] = &data.positions[size_t(slots[k]) * 3];
        uint32_t beyond = 4;
        if (d == 1) {
            const uint32_t a = data.axis;
            if (p[a] < x[0][a]) beyond = 1;
            else if (p[a] > x[1][a]) beyond = 0;
        } else {
            float y[3][2];
            for (uint32_t k = 0; k < 3; ++k) {
                y[k][0] = x[k][u];
                y[k][1] = x[k][v];
            }
            for (uint32_t k = 0; k < 3 && beyond == 4; ++k) {
                const float* z[3] = {y[0], y[1], y[2]};
                z[k] = q2;
                if (orient2d_fast(z[0], z[1], z[2]) < 0) beyond = k;
            }
        }
        if (beyond == 4) return cell;
        const uint32_t next = data.cell_neighbours[size_t(cell) * 4 + beyond];
        if (next >= inner) return cell;
        cell = next;
    }
    return cell;
}

template <class Walk>
void fill_grid(StoreData& data, Walk&& walk) {
    const uint32_t gx = data.grid[0], gy = data.grid[1], gz = data.grid[2];
    data.grid_cells.assign(size_t(gx) * gy * gz, 0);
    double step[3];
    for (int a = 0; a < 3; ++a) step[a] = (double(data.bounds_max[a]) - double(data.bounds_min[a])) / double(data.grid[a]);
    uint32_t cell = 0;
    for (uint32_t z = 0; z < gz; ++z) {
        for (uint32_t y = 0; y < gy; ++y) {
            // Serpentine rows keep consecutive centres adjacent, so each walk is a step or two.
            const bool backwards = ((y + z * gy) & 1u) != 0;
            for (uint32_t i = 0; i < gx; ++i) {
                const uint32_t x = backwards ? gx - 1 - i : i;
                // The centre rounded to float, as a query would give it.
                const float p[3] = {float(data.bounds_min[0] + (x + 0.5) * step[0]), float(data.bounds_min[1] + (y + 0.5) * step[1]),
                                    float(data.bounds_min[2] + (z + 0.5) * step[2])};
                cell = walk(p, cell);
                data.grid_cells[(size_t(z) * gy + y) * gx + x] = cell;
            }
        }
    }
}

#ifdef TETPROBE_X86_64
// The AVX2 fill compiled for that target and flattened: the walk and its orientation kernel are
// inlined into it (GCC does not inline the target("avx2") kernel into the generic walk template).
__attribute__((target("avx2"), flatten)) void fill_grid_avx2(StoreData& data, const float* padded) {
    fill_grid(data, [&](const float p[3], uint32_t cell) { return walk_inner_cells_3d<Avx2Orientations>(data, padded, p, cell); });
}
#endif

}  // namespace

void start_grid_dimensions(const float lo[3], const float hi[3], uint32_t inner_cells, uint32_t cells_per_entry,
                           uint32_t out[3]) {
    double extent[3], largest = 0;
    for (int a = 0; a < 3; ++a) {
        extent[a] = std::max(0.0, double(hi[a]) - double(lo[a]));
        largest = std::max(largest, extent[a]);
    }
    const double target = std::min(double(kMaxStartGridCells), std::max(1.0, double(inner_cells) / std::max(1u, cells_per_entry)));
    // Axes thinner than a millionth of the largest extent (flat and line sets) get one cell.
    double volume = 1;
    int active = 0;
    for (int a = 0; a < 3; ++a) {
        if (extent[a] > largest * 1e-6) {
            volume *= extent[a];
            ++active;
        }
    }
    out[0] = out[1] = out[2] = 1;
    if (active == 0) return;
    double cell = std::pow(volume / target, 1.0 / active);
    for (;;) {
        double total = 1;
        for (int a = 0; a < 3; ++a) {
            const double n = extent[a] > largest * 1e-6 ? std::round(extent[a] / cell) : 1.0;
            out[a] = uint32_t(std::min(std::max(n, 1.0), double(kMaxStartGridCells)));
            total *= out[a];
        }
        if (total <= kMaxStartGridCells) return;
        cell *= 1.05;
    }
}

void fill_start_grid(StoreData& data) {
    const uint64_t entries = uint64_t(data.grid[0]) * data.grid[1] * data.grid[2];
    if (data.grid[0] == 0 || data.grid[1] == 0 || data.grid[2] == 0 || entries > kMaxStartGridCells)
        throw Error(Status::invalid_argument, "start grid dimensions out of range");
    if (data.inner_cell_count == 0) throw Error(Status::invalid_argument, "a start grid needs inner cells");
    if (data.dimension != 3) {
        fill_grid(data, [&](const float p[3], uint32_t cell) { return walk_inner_cells_low(data, p, cell); });
        return;
    }
    std::vector<float> padded(size_t(data.positions.size() / 3) * 4 + 4, 0.0f);
    for (size_t j = 0; j < data.positions.size() / 3; ++j) std::copy_n(&data.positions[3 * j], 3, &padded[4 * j]);
#ifdef TETPROBE_X86_64
    if (cpu_has_avx2() && !std::getenv("TP_NO_AVX2")) {
        fill_grid_avx2(data, padded.data());
        return;
    }
#endif
    fill_grid(data, [&](const float p[3], uint32_t cell) {
        return walk_inner_cells_3d<ScalarOrientations>(data, padded.data(), p, cell);
    });
}

void build_start_grid(StoreData& data) {
    const uint32_t cells_per_entry =
        data.layout == kLayoutRebuilt ? kRebuiltStartGridCellsPerEntry : kStoredStartGridCellsPerEntry;
    start_grid_dimensions(data.bounds_min, data.bounds_max, data.inner_cell_count, cells_per_entry, data.grid);
    fill_start_grid(data);
}

}  // namespace tetprobe
