#include "bake/start_grid.h"

#include "core/store_format.h"

#include <algorithm>
#include <cmath>

namespace tetprobe {

namespace {

// Walks the inner cells towards local point p from `cell` by the most negative barycentric
// coordinate; stops inside, at the hull, or after a step cap (a cycle is possible only through
// rounding, and any inner cell is still a valid start).
uint32_t walk_inner_cells(const StoreData& data, const double p[3], uint32_t cell) {
    const uint32_t d = data.dimension, inner = data.inner_cell_count;
    if (d == 0) return 0;
    const uint32_t cap = 64 + 4 * inner;
    for (uint32_t step = 0; step < cap; ++step) {
        const float* m = &data.inner_matrices[size_t(cell) * 12];
        const float* anchor = &data.positions[size_t(data.cell_vertices[size_t(cell) * 4 + d]) * 3];
        const double q[3] = {p[0] - anchor[0], p[1] - anchor[1], p[2] - anchor[2]};
        double b[4], sum = 0;
        for (uint32_t k = 0; k < d; ++k) {
            b[k] = m[k * 4] * q[0] + m[k * 4 + 1] * q[1] + m[k * 4 + 2] * q[2] + m[k * 4 + 3];
            sum += b[k];
        }
        b[d] = 1 - sum;
        uint32_t worst = 0;
        for (uint32_t k = 1; k <= d; ++k) {
            if (b[k] < b[worst]) worst = k;
        }
        if (b[worst] >= 0) return cell;
        const uint32_t next = data.cell_neighbours[size_t(cell) * 4 + worst];
        if (next >= inner) return cell;
        cell = next;
    }
    return cell;
}

}  // namespace

void start_grid_dimensions(const float lo[3], const float hi[3], uint32_t inner_cells, uint32_t out[3]) {
    double extent[3], largest = 0;
    for (int a = 0; a < 3; ++a) {
        extent[a] = std::max(0.0, double(hi[a]) - double(lo[a]));
        largest = std::max(largest, extent[a]);
    }
    const double target = std::min(double(kMaxStartGridCells), std::max(1.0, inner_cells / 4.0));
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

void build_start_grid(StoreData& data) {
    start_grid_dimensions(data.bounds_min, data.bounds_max, data.inner_cell_count, data.grid);
    const uint32_t gx = data.grid[0], gy = data.grid[1], gz = data.grid[2];
    data.grid_cells.assign(size_t(gx) * gy * gz, 0);
    double step[3];
    for (int a = 0; a < 3; ++a) {
        step[a] = (double(data.bounds_max[a]) - double(data.bounds_min[a])) / double(data.grid[a]);
    }
    uint32_t cell = 0;
    for (uint32_t z = 0; z < gz; ++z) {
        for (uint32_t y = 0; y < gy; ++y) {
            // Serpentine rows keep consecutive centres adjacent, so each walk is a step or two.
            const bool backwards = ((y + z * gy) & 1u) != 0;
            for (uint32_t i = 0; i < gx; ++i) {
                const uint32_t x = backwards ? gx - 1 - i : i;
                const double p[3] = {data.bounds_min[0] + (x + 0.5) * step[0], data.bounds_min[1] + (y + 0.5) * step[1],
                                     data.bounds_min[2] + (z + 0.5) * step[2]};
                cell = walk_inner_cells(data, p, cell);
                data.grid_cells[(size_t(z) * gy + y) * gx + x] = cell;
            }
        }
    }
}

}  // namespace tetprobe
