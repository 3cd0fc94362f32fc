// Peer of the benchmark (never linked into a tetprobe library): the K nearest probes blended with inverse
// distance weights, found through a uniform bucket grid. SH are kept as 27 halves per probe, like the
// store and the grid peer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bench {

class KnnPeer {
public:
    static constexpr int kNeighbours = 4;

    // positions: 3 floats per probe; sh: 27 floats per probe.
    KnnPeer(const std::vector<float>& positions, const std::vector<float>& sh);

    size_t probe_count() const { return positions_.size() / 3; }
    // The (up to) kNeighbours nearest probes, nearest first; returns how many were found.
    int nearest(const float position[3], uint32_t out_probes[kNeighbours], float out_distances[kNeighbours]) const;
    // Weights 1/d over the nearest probes (normalised); at a probe (d = 0) that probe alone.
    void interpolate(const float position[3], float out_sh[27]) const;
    // Positions, halves, the bucket offsets and the probe indices, plus a small header.
    size_t bytes() const;

private:
    size_t bucket_of(const int cell[3]) const { return size_t(cell[0]) + size_t(dims_[0]) * (size_t(cell[1]) + size_t(dims_[1]) * size_t(cell[2])); }

    std::vector<float> positions_;
    std::vector<uint16_t> halves_;
    float lo_[3];
    float cell_[3];
    int dims_[3];
    std::vector<uint32_t> bucket_start_;  // buckets + 1 offsets into bucket_probes_
    std::vector<uint32_t> bucket_probes_;
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
