#include "knn_peer.h"

#include "grid_peer.h"

#include "core/half.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bench {

namespace {

// Keeps probe p (squared distance d2) among the `found` nearest so far, sorted by distance, if it is
// nearer than the farthest of a full list.
inline void keep_if_nearer(uint32_t p, float d2, uint32_t out_probes[KnnPeer::kNeighbours],
                           float best_d2[KnnPeer::kNeighbours], int& found) {
    constexpr int n = KnnPeer::kNeighbours;
    if (found == n && !(d2 < best_d2[n - 1])) return;
    int slot = found < n ? found++ : n - 1;
    while (slot > 0 && best_d2[slot - 1] > d2) {
        best_d2[slot] = best_d2[slot - 1], out_probes[slot] = out_probes[slot - 1];
        --slot;
    }
    best_d2[slot] = d2, out_probes[slot] = p;
}

}  // namespace

KnnPeer::KnnPeer(const std::vector<float>& positions, const std::vector<float>& sh, const float* query_lo,
                 const float* query_hi)
    : positions_(positions) {
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

    // Candidate lists over the probes' box grown to the query box, about two cells a probe.
    for (int k = 0; k < 3; ++k) {
        box_lo_[k] = std::min(lo_[k], query_lo ? query_lo[k] : lo_[k]);
        box_hi_[k] = std::max(hi[k], query_hi ? query_hi[k] : hi[k]);
    }
    grid_dims_for_count(box_lo_, box_hi_, std::max<size_t>(1, 2 * count), box_dims_);
    float box_cell[3];
    for (int k = 0; k < 3; ++k) {
        box_cell[k] = std::max(box_hi_[k] - box_lo_[k], 1e-6f) / float(box_dims_[k]);
        box_inv_cell_[k] = 1.0f / box_cell[k];
    }
    const float half_diagonal = 0.5f * std::sqrt(box_cell[0] * box_cell[0] + box_cell[1] * box_cell[1] + box_cell[2] * box_cell[2]);
    const size_t cells = size_t(box_dims_[0]) * box_dims_[1] * box_dims_[2];
    std::vector<uint32_t> starts(1, 0), lists;  // kept aside while nearest() still uses the ring search
    std::vector<float> centre_distances;
    list_half_diagonal_ = half_diagonal * 1.00001f + 1e-6f;
    for (size_t c = 0; c < cells; ++c) {
        const int i[3] = {int(c % size_t(box_dims_[0])), int(c / size_t(box_dims_[0]) % size_t(box_dims_[1])),
                          int(c / (size_t(box_dims_[0]) * box_dims_[1]))};
        float cell_lo[3], cell_hi[3], centre[3];
        for (int k = 0; k < 3; ++k) {
            cell_lo[k] = box_lo_[k] + box_cell[k] * float(i[k]);
            cell_hi[k] = cell_lo[k] + box_cell[k];
            centre[k] = 0.5f * (cell_lo[k] + cell_hi[k]);
        }
        uint32_t near[kNeighbours];
        float distances[kNeighbours];
        const int found = nearest(centre, near, distances);
        // Every query in the cell has its k-th nearest within this (d_k is 1-Lipschitz); a 1e-5 relative
        // slack covers the float rounding of the distances compared.
        const float reach = (distances[found - 1] + half_diagonal) * 1.00001f + 1e-6f;
        std::vector<std::pair<float, uint32_t>> members;  // (distance to the centre, probe)
        for (size_t p = 0; p < count; ++p) {
            float d2 = 0, c2 = 0;
            for (int k = 0; k < 3; ++k) {
                const float v = positions[3 * p + k];
                const float gap = std::max(std::max(cell_lo[k] - v, v - cell_hi[k]), 0.0f);
                d2 += gap * gap;
                c2 += (v - centre[k]) * (v - centre[k]);
            }
            if (d2 <= reach * reach) members.push_back({std::sqrt(c2), uint32_t(p)});
        }
        // Nearest the centre first: a scan stops once no later probe can beat the 4th found.
        std::sort(members.begin(), members.end());
        for (const auto& m : members) lists.push_back(m.second), centre_distances.push_back(m.first);
        starts.push_back(uint32_t(lists.size()));
    }
    list_start_ = std::move(starts);
    list_probes_ = std::move(lists);
    list_centre_distance_ = std::move(centre_distances);
}

int KnnPeer::nearest(const float position[3], uint32_t out_probes[kNeighbours], float out_distances[kNeighbours]) const {
    if (!list_start_.empty() && position[0] >= box_lo_[0] && position[0] <= box_hi_[0] && position[1] >= box_lo_[1] &&
        position[1] <= box_hi_[1] && position[2] >= box_lo_[2] && position[2] <= box_hi_[2]) {
        size_t cell = 0, scale = 1;
        for (int k = 0; k < 3; ++k) {
            cell += size_t(std::min(int((position[k] - box_lo_[k]) * box_inv_cell_[k]), box_dims_[k] - 1)) * scale;
            scale *= size_t(box_dims_[k]);
        }
        float best_d2[kNeighbours];
        int found = 0;
        for (uint32_t s = list_start_[cell]; s < list_start_[cell + 1]; ++s) {
            // |p - q| >= |p - centre| - |q - centre| >= |p - centre| - half diagonal.
            const float bound = list_centre_distance_[s] - list_half_diagonal_;
            if (found == kNeighbours && bound > 0 && bound * bound > best_d2[kNeighbours - 1]) break;
            const uint32_t p = list_probes_[s];
            const float dx = positions_[3 * p] - position[0], dy = positions_[3 * p + 1] - position[1],
                        dz = positions_[3 * p + 2] - position[2];
            const float d2 = dx * dx + dy * dy + dz * dz;
            keep_if_nearer(p, d2, out_probes, best_d2, found);
        }
        for (int i = 0; i < found; ++i) out_distances[i] = std::sqrt(best_d2[i]);
        return found;
    }
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
                        keep_if_nearer(p, d2, out_probes, best_d2, found);
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
    const size_t index = probe_count() <= 65536 ? sizeof(uint16_t) : sizeof(uint32_t);
    return positions_.size() * sizeof(float) + halves_.size() * sizeof(uint16_t) +
           bucket_start_.size() * sizeof(uint32_t) + bucket_probes_.size() * index +
           list_start_.size() * sizeof(uint32_t) + list_probes_.size() * (index + sizeof(float)) + 19 * sizeof(float);
}

double KnnPeer::mean_candidates() const {
    return list_start_.size() > 1 ? double(list_probes_.size()) / double(list_start_.size() - 1) : 0.0;
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
