#include "bake/candidate_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <unordered_map>

namespace tetprobe {

ChangingPairs changing_pairs(const std::vector<float>& positions, const PointSignal& signal, double spacing, size_t limit) {
    const size_t count = positions.size() / 3;
    const double reach = 1.5 * spacing;
    auto cell_of = [&](size_t i, int a) { return int64_t(std::floor(positions[3 * i + size_t(a)] / reach)); };
    auto key = [](int64_t x, int64_t y, int64_t z) {
        return uint64_t(x * 73856093) ^ uint64_t(y * 19349663) ^ uint64_t(z * 83492791);
    };
    std::unordered_multimap<uint64_t, uint32_t> grid;
    grid.reserve(count);
    for (size_t i = 0; i < count; ++i) grid.emplace(key(cell_of(i, 0), cell_of(i, 1), cell_of(i, 2)), uint32_t(i));
    // (excess beyond the noise, i, j), i < j
    std::vector<std::tuple<double, uint32_t, uint32_t>> found;
    for (size_t i = 0; i < count; ++i) {
        const int64_t c[3] = {cell_of(i, 0), cell_of(i, 1), cell_of(i, 2)};
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const auto range = grid.equal_range(key(c[0] + dx, c[1] + dy, c[2] + dz));
                    for (auto it = range.first; it != range.second; ++it) {
                        const size_t j = it->second;
                        if (j <= i) continue;
                        double d2 = 0;
                        for (int a = 0; a < 3; ++a) d2 += double(positions[3 * i + size_t(a)] - positions[3 * j + size_t(a)]) *
                                                          double(positions[3 * i + size_t(a)] - positions[3 * j + size_t(a)]);
                        if (d2 > reach * reach) continue;
                        double diff = 0;
                        for (int k = 0; k < kSignalSize; ++k) {
                            const double d = double(signal.value[kSignalSize * i + size_t(k)]) - signal.value[kSignalSize * j + size_t(k)];
                            diff += d * d;
                        }
                        const double noise = double(signal.noise[i]) + signal.noise[j];
                        if (diff > kRefineDeviations * kRefineDeviations * noise) found.emplace_back(-(diff - noise), uint32_t(i), uint32_t(j));
                    }
                }
    }
    std::sort(found.begin(), found.end());  // a hash collision may list a pair twice: kept once below
    found.erase(std::unique(found.begin(), found.end()), found.end());
    if (found.size() > limit) found.resize(limit);
    ChangingPairs pairs;
    for (const auto& f : found) {
        pairs.a.insert(pairs.a.end(), &positions[3 * size_t(std::get<1>(f))], &positions[3 * size_t(std::get<1>(f))] + 3);
        pairs.b.insert(pairs.b.end(), &positions[3 * size_t(std::get<2>(f))], &positions[3 * size_t(std::get<2>(f))] + 3);
    }
    return pairs;
}

}  // namespace tetprobe
