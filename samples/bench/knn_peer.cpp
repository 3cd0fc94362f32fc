#include "knn_peer.h"

#include "grid_peer.h"

#include "core/half.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bench {

KnnPeer::KnnPeer(const std::vector<float>& positions, const std::vector<float>& sh) : positions_(positions) {
    const size_t count = positions.size() / 3;
    if (count == 0 || positions.size() != 3 * count || sh.size() != 27 * count)
        throw std::invalid_argument("KnnPeer: 3 position floats and 27 SH floats per probe, at least one probe");
    halves_.resize(sh.size());
    for (size_t i = 0; i < sh.size(); ++i) halves_[i] = tetprobe::float_to_half(sh[i]);
    float hi[3];
    for (int k = 0; k < 3; ++k) lo_[k] = hi[k] = positions[k];
    for (size_t p = 0; p < count; ++p)
        for (int k = 0; k < 3; ++k)
            lo_[k] = std::min(lo_[k], positions[3 * p + k]), hi[k] = std::max(hi[k], positions[3 * p + k]);
    // About two probes per bucket.
    grid_dims_for_count(lo_, hi, std::max<size_t>(1, count / 2), dims_);
    for (int k = 0; k < 3; ++k) cell_[k] = dims_[k] > 1 ? (hi[k] - lo_[k]) / float(dims_[k]) : 0.0f;
    std::vector<size_t> bucket(count);
    bucket_start_.assign(size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    for (size_t p = 0; p < count; ++p) {
        int cell[3];
        for (int k = 0; k < 3; ++k)
            cell[k] = dims_[k] > 1 ? std::min(int((positions[3 * p + k] - lo_[k]) / cell_[k]), dims_[k] - 1) : 0;
        bucket[p] = bucket_of(cell);
        ++bucket_start_[bucket[p] + 1];
    }
    for (size_t b = 1; b < bucket_start_.size(); ++b) bucket_start_[b] += bucket_start_[b - 1];
    bucket_probes_.resize(count);
    std::vector<uint32_t> fill(bucket_start_.begin(), bucket_start_.end() - 1);
    for (size_t p = 0; p < count; ++p) bucket_probes_[fill[bucket[p]]++] = uint32_t(p);
}

int KnnPeer::nearest(const float position[3], uint32_t out_probes[kNeighbours], float out_distances[kNeighbours]) const {
    int centre[3];
    float ring_gap = INFINITY;  // every bucket at Chebyshev ring r + 1 is at least r * ring_gap away
    for (int k = 0; k < 3; ++k) {
        centre[k] = dims_[k] > 1 ? std::min(std::max(int(std::floor((position[k] - lo_[k]) / cell_[k])), 0), dims_[k] - 1) : 0;
        if (dims_[k] > 1) ring_gap = std::min(ring_gap, cell_[k]);
    }
    const int max_ring = std::max(dims_[0], std::max(dims_[1], dims_[2]));
    float best_d2[kNeighbours];
    int found = 0;
    for (int ring = 0; ring <= max_ring; ++ring) {
        if (found == kNeighbours && ring > 0) {
            const float bound = float(ring - 1) * ring_gap;
            if (bound * bound > best_d2[kNeighbours - 1]) break;
        }
        int lo[3], hi[3];
        for (int k = 0; k < 3; ++k) lo[k] = std::max(centre[k] - ring, 0), hi[k] = std::min(centre[k] + ring, dims_[k] - 1);
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) {
                    const int cell[3] = {x, y, z};
                    bool on_ring = false;
                    for (int k = 0; k < 3; ++k) on_ring |= std::abs(cell[k] - centre[k]) == ring;
                    if (!on_ring) continue;
                    const size_t b = bucket_of(cell);
                    for (uint32_t s = bucket_start_[b]; s < bucket_start_[b + 1]; ++s) {
                        const uint32_t p = bucket_probes_[s];
                        float d2 = 0;
                        for (int k = 0; k < 3; ++k) {
                            const float d = positions_[3 * p + k] - position[k];
                            d2 += d * d;
                        }
                        if (found == kNeighbours && !(d2 < best_d2[kNeighbours - 1])) continue;
                        int slot = found < kNeighbours ? found++ : kNeighbours - 1;
                        while (slot > 0 && best_d2[slot - 1] > d2) {
                            best_d2[slot] = best_d2[slot - 1], out_probes[slot] = out_probes[slot - 1];
                            --slot;
                        }
                        best_d2[slot] = d2, out_probes[slot] = p;
                    }
                }
    }
    for (int i = 0; i < found; ++i) out_distances[i] = std::sqrt(best_d2[i]);
    return found;
}

void KnnPeer::interpolate(const float position[3], float out_sh[27]) const {
    uint32_t probes[kNeighbours];
    float distances[kNeighbours], weights[kNeighbours];
    const int found = nearest(position, probes, distances);
    if (distances[0] == 0) {
        weights[0] = 1;
        for (int i = 1; i < found; ++i) weights[i] = 0;
    } else {
        float sum = 0;
        for (int i = 0; i < found; ++i) sum += weights[i] = 1 / distances[i];
        for (int i = 0; i < found; ++i) weights[i] /= sum;
    }
    const uint16_t* sh[kNeighbours];
    for (int i = 0; i < kNeighbours; ++i) {
        if (i >= found) weights[i] = 0;
        sh[i] = &halves_[27 * size_t(probes[i < found ? i : 0])];
    }
    tetprobe::blend_sh_halves(sh, weights, out_sh);
}

size_t KnnPeer::bytes() const {
    return positions_.size() * sizeof(float) + halves_.size() * sizeof(uint16_t) +
           bucket_start_.size() * sizeof(uint32_t) + bucket_probes_.size() * sizeof(uint32_t) + 9 * sizeof(float);
}

TemporalDamping::TemporalDamping(double time_constant_frames)
    : alpha_(float(1.0 - std::exp(-1.0 / time_constant_frames))) {}

void TemporalDamping::update(const float sh[27], float out_sh[27]) {
    if (!primed_) {
        std::copy(sh, sh + 27, state_);
        primed_ = true;
    } else {
        for (int i = 0; i < 27; ++i) state_[i] += alpha_ * (sh[i] - state_[i]);
    }
    std::copy(state_, state_ + 27, out_sh);
}

}  // namespace bench
