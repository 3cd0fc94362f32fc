#include "core/cell_order.h"

#include "core/store_format.h"

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <tuple>
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

// Stable LSD radix sort of indices by a 32-bit key (four 8-bit passes, no comparisons).
void radix_sort_by_key(std::vector<uint32_t>& keys, std::vector<uint32_t>& items) {
    std::vector<uint32_t> key_buffer(keys.size()), item_buffer(items.size());
    for (int shift = 0; shift < 32; shift += 8) {
        size_t counts[257] = {};
        for (uint32_t k : keys) ++counts[((k >> shift) & 0xFFu) + 1];
        for (int b = 0; b < 256; ++b) counts[b + 1] += counts[b];
        for (size_t i = 0; i < keys.size(); ++i) {
            const size_t to = counts[(keys[i] >> shift) & 0xFFu]++;
            key_buffer[to] = keys[i];
            item_buffer[to] = items[i];
        }
        keys.swap(key_buffer);
        items.swap(item_buffer);
    }
}

// Within each run of equal keys (after a stable sort), orders the cells by their vertex slots.
void order_equal_keys_by_vertices(const std::vector<uint32_t>& keys, std::vector<uint32_t>& items,
                                  const std::vector<uint32_t>& cell_vertices) {
    auto slots = [&](uint32_t c) {
        const uint32_t* v = &cell_vertices[size_t(c) * 4];
        return std::tie(v[0], v[1], v[2], v[3]);
    };
    for (size_t i = 0; i < keys.size();) {
        size_t j = i + 1;
        while (j < keys.size() && keys[j] == keys[i]) ++j;
        if (j - i > 1)
            std::sort(items.begin() + ptrdiff_t(i), items.begin() + ptrdiff_t(j),
                      [&](uint32_t a, uint32_t b) { return slots(a) < slots(b); });
        i = j;
    }
}

}  // namespace

uint64_t morton_code(const double p[3], const double lo[3], const double hi[3]) {
    uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
        const double extent = hi[a] - lo[a];
        double f = extent > 0 ? (p[a] - lo[a]) / extent : 0.0;
        f = std::min(std::max(f, 0.0), 1.0);
        code |= spread_bits(uint64_t(f * double(0x1FFFFF))) << a;
    }
    return code;
}

std::vector<uint32_t> curve_order(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& lo,
                                  const Eigen::Vector3d& hi) {
    std::vector<uint64_t> codes(points.size());
    for (size_t i = 0; i < points.size(); ++i) codes[i] = morton_code(points[i].data(), lo.data(), hi.data());
    std::vector<uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const Eigen::Vector3d &p = points[a], &q = points[b];
        return std::tie(codes[a], p.x(), p.y(), p.z(), a) < std::tie(codes[b], q.x(), q.y(), q.z(), b);
    });
    return order;
}

void order_cells_for_locality(StoreData& data) {
    const uint32_t cells = data.cell_count(), inner = data.inner_cell_count;
    const double lo[3] = {data.bounds_min[0], data.bounds_min[1], data.bounds_min[2]};
    const double hi[3] = {data.bounds_max[0], data.bounds_max[1], data.bounds_max[2]};
    const double centre[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};

    // Keys: the top 32 bits of each centroid's Morton code (about 1/2000 of the bounds per axis, finer
    // than any walk cares about).
    std::vector<uint32_t> keys(cells), old_of_new(cells);
    std::vector<double> distance(inner);
    for (uint32_t c = 0; c < cells; ++c) {
        const uint32_t* v = &data.cell_vertices[size_t(c) * 4];
        double centroid[3] = {0, 0, 0};
        int count = 0;
        for (int k = 0; k < 4; ++k) {
            if (v[k] >= kOuter32) continue;
            const float* p = &data.positions[size_t(v[k]) * 3];
            centroid[0] += p[0];
            centroid[1] += p[1];
            centroid[2] += p[2];
            ++count;
        }
        for (double& x : centroid) x /= count;
        keys[c] = uint32_t(morton_code(centroid, lo, hi) >> 31);
        old_of_new[c] = c;
        if (c < inner) {
            distance[c] = (centroid[0] - centre[0]) * (centroid[0] - centre[0]) +
                          (centroid[1] - centre[1]) * (centroid[1] - centre[1]) +
                          (centroid[2] - centre[2]) * (centroid[2] - centre[2]);
        }
    }
    std::vector<uint32_t> inner_keys(keys.begin(), keys.begin() + inner), outer_keys(keys.begin() + inner, keys.end());
    std::vector<uint32_t> inner_order(old_of_new.begin(), old_of_new.begin() + inner);
    std::vector<uint32_t> outer_order(old_of_new.begin() + inner, old_of_new.end());
    radix_sort_by_key(inner_keys, inner_order);
    radix_sort_by_key(outer_keys, outer_order);
    order_equal_keys_by_vertices(inner_keys, inner_order, data.cell_vertices);
    order_equal_keys_by_vertices(outer_keys, outer_order, data.cell_vertices);
    std::copy(inner_order.begin(), inner_order.end(), old_of_new.begin());
    std::copy(outer_order.begin(), outer_order.end(), old_of_new.begin() + inner);
    // The inner cell nearest the centre (the first in this order among equally near ones) to slot 0.
    uint32_t nearest = 0;
    for (uint32_t n = 1; n < inner; ++n)
        if (distance[old_of_new[n]] < distance[old_of_new[nearest]]) nearest = n;
    if (inner > 0) std::swap(old_of_new[0], old_of_new[nearest]);

    std::vector<uint32_t> new_of_old(cells);
    for (uint32_t n = 0; n < cells; ++n) new_of_old[old_of_new[n]] = n;

    std::vector<uint32_t> vertices(data.cell_vertices.size()), neighbours(data.cell_neighbours.size());
    for (uint32_t n = 0; n < cells; ++n) {
        const uint32_t o = old_of_new[n];
        for (size_t k = 0; k < 4; ++k) {
            vertices[size_t(n) * 4 + k] = data.cell_vertices[size_t(o) * 4 + k];
            const uint32_t link = data.cell_neighbours[size_t(o) * 4 + k];
            neighbours[size_t(n) * 4 + k] = link < cells ? new_of_old[link] : link;
        }
    }
    data.cell_vertices = std::move(vertices);
    data.cell_neighbours = std::move(neighbours);
}

}  // namespace tetprobe
