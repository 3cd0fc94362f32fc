// Peer of the benchmark (never linked into a tetprobe library): the K nearest probes blended with inverse
// distance weights. A query inside the acceleration box (the probes' bounds, grown to a given query box)
// scans its cell's candidate list: every probe whose distance to the cell is within an upper bound of the
// 4th-nearest distance anywhere in the cell (the 4th-nearest distance of the cell's centre plus half the
// cell's diagonal), nearest the cell's centre first so that the scan stops once no later probe can be
// nearer than the 4th found: it finds exactly the 4 nearest; outside the box, a ring search over a bucket
// grid.
// SH are kept as 27 halves per probe, like the store and the grid peer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bench {

class KnnPeer {
public:
    static constexpr int kNeighbours = 4;

    // positions: 3 floats per probe; sh: 27 floats per probe; query_lo, query_hi (may be null): where
    // queries will be, so the candidate lists cover it.
    KnnPeer(const std::vector<float>& positions, const std::vector<float>& sh, const float* query_lo = nullptr,
            const float* query_hi = nullptr);

    size_t probe_count() const { return positions_.size() / 3; }
    // The (up to) kNeighbours nearest probes, nearest first; returns how many were found.
    int nearest(const float position[3], uint32_t out_probes[kNeighbours], float out_distances[kNeighbours]) const;
    // Weights 1/d over the nearest probes (normalised); at a probe (d = 0) that probe alone.
    void interpolate(const float position[3], float out_sh[27]) const;
    // Positions, halves, the candidate lists (offsets; 16-bit indices while probes fit, else 32-bit; a float
    // distance to the centre each) and the
    // bucket grid of the search outside them, plus a small header.
    size_t bytes() const;
    double mean_candidates() const;  // probes a list holds on average

private:
    size_t bucket_of(const int cell[3]) const { return size_t(cell[0]) + size_t(dims_[0]) * (size_t(cell[1]) + size_t(dims_[1]) * size_t(cell[2])); }

    std::vector<float> positions_;
    std::vector<uint16_t> halves_;
    float lo_[3];
    float cell_[3];
    int dims_[3];
    std::vector<uint32_t> bucket_start_;  // buckets + 1 offsets into bucket_probes_
    std::vector<uint32_t> bucket_probes_;
    // The candidate lists: a cell grid over box_lo_ .. box_lo_ + box_dims_ * box_cell_.
    float box_lo_[3], box_hi_[3], box_inv_cell_[3];
    int box_dims_[3];
    std::vector<uint32_t> list_start_;  // cells + 1
    std::vector<uint32_t> list_probes_;        // each cell's, nearest its centre first
    std::vector<float> list_centre_distance_;  // of each entry
    float list_half_diagonal_ = 0;             // of a cell, rounded up
};

// Exponential smoothing of one object's blended SH from frame to frame: out = out + alpha (in - out),
// alpha = 1 - exp(-1 / time_constant_frames); the first frame passes through unchanged.
class TemporalDamping {
public:
    explicit TemporalDamping(double time_constant_frames);
    double alpha() const { return alpha_; }
    void update(const float sh[27], float out_sh[27]);
    void reset() { primed_ = false; }

private:
    float alpha_;
    bool primed_ = false;
    float state_[27];
};

}  // namespace bench
