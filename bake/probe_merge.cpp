#include "bake/probe_merge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace tetprobe {

namespace {

// A direction no lattice or axis plane is aligned with, so that few points share a projection.
const Eigen::Vector3d kSweepDirection = Eigen::Vector3d(0.5407, 0.5946, 0.5950).normalized();

}  // namespace

ProbeMerge merge_close_points(const std::vector<Eigen::Vector3d>& points, double tolerance) {
    const size_t n = points.size();
    ProbeMerge merge;
    merge.group_of.resize(n);

    // Candidate pairs by a sweep along one direction: two points within the tolerance are within it
    // along any unit direction (plus the projections' rounding), so sorting the projections and
    // scanning a window finds every close pair in O(n log n) for any but pathologically dense sets.
    double extent = 0;
    std::vector<std::pair<double, uint32_t>> sweep(n);
    for (uint32_t i = 0; i < n; ++i) {
        extent = std::max(extent, points[i].cwiseAbs().maxCoeff());
        sweep[i] = {kSweepDirection.dot(points[i]), i};
    }
    std::sort(sweep.begin(), sweep.end());
    const double window = tolerance + 8 * extent * 0x1p-52;
    const double tolerance2 = tolerance * tolerance;
    std::vector<std::pair<uint32_t, uint32_t>> close;  // (later, earlier) in the given order
    for (size_t a = 0; a < n; ++a) {
        for (size_t b = a + 1; b < n && sweep[b].first - sweep[a].first <= window; ++b) {
            const uint32_t i = sweep[a].second, j = sweep[b].second;
            if ((points[i] - points[j]).squaredNorm() <= tolerance2) close.emplace_back(std::max(i, j), std::min(i, j));
        }
    }
    std::sort(close.begin(), close.end());

    // Greedy in the given order: a point joins the earliest earlier survivor within the tolerance.
    std::vector<uint32_t> slot_of(n, UINT32_MAX);  // survivor slot of a surviving point
    size_t next = 0;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t best = UINT32_MAX;
        for (; next < close.size() && close[next].first == i; ++next) {
            best = std::min(best, slot_of[close[next].second]);  // earlier survivors have smaller slots
        }
        if (best == UINT32_MAX) {
            best = uint32_t(merge.survivors.size());
            merge.survivors.push_back(i);
            slot_of[i] = best;
        }
        merge.group_of[i] = best;
    }
    return merge;
}

}  // namespace tetprobe
