#include "bake/probe_merge.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace tetprobe {

namespace {

struct CellKey {
    int64_t x, y, z;
    bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct CellKeyHash {
    size_t operator()(const CellKey& k) const {
        uint64_t h = uint64_t(k.x) * 0x9E3779B97F4A7C15ull;
        h ^= uint64_t(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= uint64_t(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return size_t(h);
    }
};

}  // namespace

ProbeMerge merge_close_points(const std::vector<Eigen::Vector3d>& points, double tolerance) {
    ProbeMerge merge;
    merge.group_of.resize(points.size());

    double extent = 0;
    for (const auto& p : points) extent = std::max(extent, p.cwiseAbs().maxCoeff());
    // A cell size far below the coordinates' resolution would overflow the grid keys; at that point
    // "within tolerance" means "equal", which a cell as small as the coordinates' ulp still finds.
    const double cell = std::max(tolerance, extent * 1e-15);
    const bool exact = !(cell > 0);

    std::unordered_map<CellKey, std::vector<uint32_t>, CellKeyHash> grid;  // cell -> survivor slots
    grid.reserve(points.size());
    auto key_of = [&](const Eigen::Vector3d& p) {
        if (exact) return CellKey{0, 0, 0};
        return CellKey{int64_t(std::floor(p.x() / cell)), int64_t(std::floor(p.y() / cell)),
                       int64_t(std::floor(p.z() / cell))};
    };

    const double tolerance2 = tolerance * tolerance;
    for (uint32_t i = 0; i < points.size(); ++i) {
        const CellKey key = key_of(points[i]);
        uint32_t best = UINT32_MAX;
        for (int64_t dx = -1; dx <= 1; ++dx)
            for (int64_t dy = -1; dy <= 1; ++dy)
                for (int64_t dz = -1; dz <= 1; ++dz) {
                    if (exact && (dx || dy || dz)) continue;
                    auto it = grid.find(CellKey{key.x + dx, key.y + dy, key.z + dz});
                    if (it == grid.end()) continue;
                    for (uint32_t slot : it->second) {
                        if (slot < best && (points[merge.survivors[slot]] - points[i]).squaredNorm() <= tolerance2)
                            best = slot;
                    }
                }
        if (best == UINT32_MAX) {
            best = uint32_t(merge.survivors.size());
            merge.survivors.push_back(i);
            grid[key].push_back(best);
        }
        merge.group_of[i] = best;
    }
    return merge;
}

}  // namespace tetprobe
