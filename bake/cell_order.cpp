#include "bake/cell_order.h"

#include "core/store_format.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace tetprobe {

namespace {

uint64_t spread_bits(uint64_t x) {
    x &= 0x1FFFFFull;
    x = (x | (x << 32)) & 0x001F00000000FFFFull;
    x = (x | (x << 16)) & 0x001F0000FF0000FFull;
    x = (x | (x << 8)) & 0x100F00F00F00F00Full;
    x = (x | (x << 4)) & 0x10C30C30C30C30C3ull;
    x = (x | (x << 2)) & 0x1249249249249249ull;
    return x;
}

// Centroid of the probes in a cell's vertex slots (kOuter32 / kNone32 slots skipped).
void cell_centroid(const StoreData& data, uint32_t cell, float out[3]) {
    double sum[3] = {0, 0, 0};
    int count = 0;
    for (int k = 0; k < 4; ++k) {
        const uint32_t v = data.cell_vertices[size_t(cell) * 4 + size_t(k)];
        if (v >= kOuter32) continue;
        for (int a = 0; a < 3; ++a) sum[a] += data.positions[size_t(v) * 3 + size_t(a)];
        ++count;
    }
    for (int a = 0; a < 3; ++a) out[a] = count ? float(sum[a] / count) : 0.0f;
}

}  // namespace

uint64_t morton_code(const float p[3], const float lo[3], const float hi[3]) {
    uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
        const double extent = double(hi[a]) - double(lo[a]);
        double f = extent > 0 ? (double(p[a]) - double(lo[a])) / extent : 0.0;
        f = std::min(std::max(f, 0.0), 1.0);
        code |= spread_bits(uint64_t(f * double(0x1FFFFF))) << a;
    }
    return code;
}

void order_cells_for_locality(StoreData& data) {
    const uint32_t cells = data.cell_count(), inner = data.inner_cell_count;
    std::vector<uint64_t> codes(cells);
    std::vector<float> centroids(size_t(cells) * 3);
    for (uint32_t c = 0; c < cells; ++c) {
        cell_centroid(data, c, &centroids[size_t(c) * 3]);
        codes[c] = morton_code(&centroids[size_t(c) * 3], data.bounds_min, data.bounds_max);
    }
    std::vector<uint32_t> old_of_new(cells);
    std::iota(old_of_new.begin(), old_of_new.end(), 0u);
    auto by_code = [&](uint32_t a, uint32_t b) { return codes[a] < codes[b] || (codes[a] == codes[b] && a < b); };
    std::sort(old_of_new.begin(), old_of_new.begin() + inner, by_code);
    std::sort(old_of_new.begin() + inner, old_of_new.end(), by_code);

    double mean[3] = {0, 0, 0};
    const uint32_t probes = data.probe_count();
    for (uint32_t i = 0; i < probes; ++i) {
        for (int a = 0; a < 3; ++a) mean[a] += data.positions[size_t(i) * 3 + size_t(a)] / double(probes);
    }
    uint32_t nearest = 0;
    double nearest_distance = -1;
    for (uint32_t n = 0; n < inner; ++n) {
        const float* c = &centroids[size_t(old_of_new[n]) * 3];
        double d2 = 0;
        for (int a = 0; a < 3; ++a) d2 += (c[a] - mean[a]) * (c[a] - mean[a]);
        if (nearest_distance < 0 || d2 < nearest_distance) {
            nearest_distance = d2;
            nearest = n;
        }
    }
    if (inner > 0) std::swap(old_of_new[0], old_of_new[nearest]);

    std::vector<uint32_t> new_of_old(cells);
    for (uint32_t n = 0; n < cells; ++n) new_of_old[old_of_new[n]] = n;

    std::vector<uint32_t> vertices(data.cell_vertices.size()), neighbours(data.cell_neighbours.size());
    std::vector<float> inner_matrices(data.inner_matrices.size()), outer_matrices(data.outer_matrices.size());
    for (uint32_t n = 0; n < cells; ++n) {
        const uint32_t o = old_of_new[n];
        for (size_t k = 0; k < 4; ++k) {
            vertices[size_t(n) * 4 + k] = data.cell_vertices[size_t(o) * 4 + k];
            const uint32_t link = data.cell_neighbours[size_t(o) * 4 + k];
            neighbours[size_t(n) * 4 + k] = link < cells ? new_of_old[link] : link;
        }
        if (n < inner) {
            std::copy_n(&data.inner_matrices[size_t(o) * 12], 12, &inner_matrices[size_t(n) * 12]);
        } else {
            std::copy_n(&data.outer_matrices[size_t(o - inner) * 16], 16, &outer_matrices[size_t(n - inner) * 16]);
        }
    }
    data.cell_vertices = std::move(vertices);
    data.cell_neighbours = std::move(neighbours);
    data.inner_matrices = std::move(inner_matrices);
    data.outer_matrices = std::move(outer_matrices);
}

}  // namespace tetprobe
