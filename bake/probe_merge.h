// Merging of duplicate and near-duplicate probes, so that the triangulation never sees two points
// closer than the merge tolerance (TetGen drops exact duplicates and builds needle cells from near
// ones).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace tetprobe {

struct ProbeMerge {
    std::vector<uint32_t> survivors;  // index (into the merged points) of each kept point, ascending
    std::vector<uint32_t> group_of;   // per point: position of its survivor in `survivors`
    size_t merged_count() const { return group_of.size() - survivors.size(); }
};

// Greedy merge in the given order: a point within `tolerance` (inclusive, so 0 merges exact
// duplicates only) of an earlier survivor joins the earliest such survivor, otherwise it survives
// itself. Survivors are therefore pairwise farther apart than the tolerance. Close pairs are found by
// a sorted sweep along one direction, O(n log n) unless many points crowd within the tolerance.
ProbeMerge merge_close_points(const std::vector<Eigen::Vector3d>& points, double tolerance);

}  // namespace tetprobe
