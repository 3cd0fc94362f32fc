#include "core/cell_order.h"

#include "core/store_format.h"

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <tuple>
#include <utility>

namespace tetprobe {

namespace {

// Bit i of x to bit 3 i, for x below 2^7.
struct SpreadTable {
    uint32_t bits[128];
    constexpr SpreadTable() : bits() {
        for (uint32_t x = 0; x < 128; ++x)
            for (uint32_t i = 0; i < 7; ++i) bits[x] |= ((x >> i) & 1u) << (3 * i);
    }
};
constexpr SpreadTable kSpread;

// Bit i of the low 21 bits of x to bit 3 i, seven bits at a time.
uint64_t spread_bits(uint64_t x) {
    return uint64_t(kSpread.bits[x & 0x7F]) | uint64_t(kSpread.bits[(x >> 7) & 0x7F]) << 21 |
           uint64_t(kSpread.bits[(x >> 14) & 0x7F]) << 42;
}

// Stable LSD radix sort of indices by a 32-bit key (three 11-bit passes, no comparisons). The three
// digits' counts are taken in one read of the keys (a pass permutes the keys, not the counts).
void radix_sort_by_key(std::vector<uint32_t>& keys, std::vector<uint32_t>& items) {
    std::vector<uint32_t> key_buffer(keys.size()), item_buffer(items.size());
    std::vector<uint32_t> all_counts(3 * 2049, 0u);
    for (uint32_t k : keys) {
        ++all_counts[(k & 0x7FFu) + 1];
        ++all_counts[2049 + ((k >> 11) & 0x7FFu) + 1];
        ++all_counts[2 * 2049 + ((k >> 22) & 0x7FFu) + 1];
    }
    for (int shift = 0; shift < 32; shift += 11) {
        uint32_t* const counts = &all_counts[size_t(shift / 11) * 2049];
        for (int b = 0; b < 2048; ++b) counts[size_t(b) + 1] += counts[size_t(b)];
        for (size_t i = 0; i < keys.size(); ++i) {
            const uint32_t to = counts[(keys[i] >> shift) & 0x7FFu]++;
            key_buffer[to] = keys[i];
            item_buffer[to] = items[i];
        }
        keys.swap(key_buffer);
        items.swap(item_buffer);
    }
}

// Within each run of equal keys (after a stable sort), orders the cells by their vertex slots.
void order_equal_keys_by_vertices(const std::vector<uint32_t>& keys, std::vector<uint32_t>& items,
                                  const CellSource& source) {
    auto slots = [&](uint32_t c) {
        const uint32_t* v = source.vertices(c);
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
    const uint32_t inner = data.inner_cell_count;
    std::vector<uint32_t> vertices, neighbours;
    vertices.swap(data.cell_vertices);
    neighbours.swap(data.cell_neighbours);
    const CellSource source{vertices.data(), neighbours.data(), vertices.data() + size_t(inner) * 4,
                            neighbours.data() + size_t(inner) * 4, inner, uint32_t(vertices.size() / 4)};
    order_cells_for_locality(data, source);
}

void order_cells_for_locality(StoreData& data, const CellSource& source) {
    const uint32_t cells = source.cells, inner = source.inner;
    data.inner_cell_count = inner;
    double lo[3], scale[3], centre[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = data.bounds_min[a];
        const double extent = double(data.bounds_max[a]) - lo[a];
        scale[a] = extent > 0 ? double(0x1FFFFF) / extent : 0.0;  // a flat axis quantises to 0
        centre[a] = 0.5 * (lo[a] + double(data.bounds_max[a]));
    }

    // Keys: the top 32 bits of the Morton code of each cell's centroid quantised to 21 bits per axis
    // (about 1/2000 of the bounds per axis, finer than any walk cares about). Plain IEEE arithmetic
    // (no library functions), so a loader on another platform computes the same keys.
    const float* positions = data.positions.data();
    // Written straight into the two sorts' inputs (inner cells, then outer ones).
    std::vector<uint32_t> inner_keys(inner), outer_keys(cells - inner), inner_order(inner), outer_order(cells - inner);
    std::iota(inner_order.begin(), inner_order.end(), 0u);
    std::iota(outer_order.begin(), outer_order.end(), inner);
    // The inner cells nearest the centre, in the old order (usually one; all of them on a tie).
    std::vector<uint32_t> nearest_cells;
    double nearest_distance = 0;
    const uint32_t corners_inner = data.dimension + 1, corners_outer = data.dimension;
    const double inverse_inner = 1.0 / corners_inner, inverse_outer = corners_outer ? 1.0 / corners_outer : 0.0;
    for (uint32_t c = 0; c < cells; ++c) {
        const uint32_t* v = source.vertices(c);
        const uint32_t corners = c < inner ? corners_inner : corners_outer;
        const double inverse = c < inner ? inverse_inner : inverse_outer;
        double sum[3] = {0, 0, 0};
        for (uint32_t k = 0; k < corners; ++k) {
            const float* p = positions + size_t(v[k]) * 3;
            sum[0] += p[0];
            sum[1] += p[1];
            sum[2] += p[2];
        }
        uint64_t code = 0;
        double centroid[3];
        for (int a = 0; a < 3; ++a) {
            centroid[a] = sum[a] * inverse;
            double f = (centroid[a] - lo[a]) * scale[a];
            f = f < 0 ? 0 : f > double(0x1FFFFF) ? double(0x1FFFFF) : f;
            code |= spread_bits(uint64_t(int64_t(f))) << a;  // f < 2^21: a signed conversion, no fix-up
        }
        (c < inner ? inner_keys[c] : outer_keys[c - inner]) = uint32_t(code >> 31);
        if (c < inner) {
            const double distance = (centroid[0] - centre[0]) * (centroid[0] - centre[0]) +
                                    (centroid[1] - centre[1]) * (centroid[1] - centre[1]) +
                                    (centroid[2] - centre[2]) * (centroid[2] - centre[2]);
            if (nearest_cells.empty() || distance < nearest_distance) {
                nearest_cells.assign(1, c);
                nearest_distance = distance;
            } else if (distance == nearest_distance) {
                nearest_cells.push_back(c);
            }
        }
    }
    radix_sort_by_key(inner_keys, inner_order);
    radix_sort_by_key(outer_keys, outer_order);
    // Cells with equal keys (and equally near the centre below) go by their vertex slots, so the order
    // depends only on which cells there are.
    order_equal_keys_by_vertices(inner_keys, inner_order, source);
    order_equal_keys_by_vertices(outer_keys, outer_order, source);
    std::vector<uint32_t> old_of_new(cells);
    std::copy(inner_order.begin(), inner_order.end(), old_of_new.begin());
    std::copy(outer_order.begin(), outer_order.end(), old_of_new.begin() + inner);
    std::vector<uint32_t> new_of_old(cells);
    for (uint32_t n = 0; n < cells; ++n) new_of_old[old_of_new[n]] = n;
    // The inner cell nearest the centre (the first in this order among equally near ones) to slot 0.
    // Found among the nearest cells noted above: a search in the new order would read the
    // distances in a random order.
    if (inner > 0) {
        uint32_t nearest = new_of_old[nearest_cells[0]];
        for (uint32_t c : nearest_cells) nearest = std::min(nearest, new_of_old[c]);
        const uint32_t first = old_of_new[0], moved = old_of_new[nearest];
        std::swap(old_of_new[0], old_of_new[nearest]);
        new_of_old[first] = nearest;
        new_of_old[moved] = 0;
    }

    // Scattered in the old order: the reads stay sequential and the scattered writes do not stall
    // (a gather in the new order waited on a cache miss per cell: half of this function's time).
    // Written once, straight from the source (the rebuild's mesh and outer cells need no copy first).
    data.cell_vertices.resize(size_t(cells) * 4);
    data.cell_neighbours.resize(size_t(cells) * 4);
    uint32_t* const vertices = data.cell_vertices.data();
    uint32_t* const neighbours = data.cell_neighbours.data();
    constexpr uint32_t kAhead = 8;  // cells: the scattered writes' lines are fetched this far ahead
    for (uint32_t o = 0; o < cells; ++o) {
        if (o + kAhead < cells) {
            const size_t ahead = size_t(new_of_old[o + kAhead]) * 4;
            __builtin_prefetch(vertices + ahead, 1);
            __builtin_prefetch(neighbours + ahead, 1);
        }
        const uint32_t n = new_of_old[o];
        const uint32_t *from_vertices = source.vertices(o), *from_neighbours = source.neighbours(o);
        for (size_t k = 0; k < 4; ++k) {
            vertices[size_t(n) * 4 + k] = from_vertices[k];
            const uint32_t link = from_neighbours[k];
            neighbours[size_t(n) * 4 + k] = link < cells ? new_of_old[link] : link;
        }
    }
}

}  // namespace tetprobe
