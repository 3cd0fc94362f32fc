// Peer of the benchmark (never linked into a tetprobe library): a uniform grid of probes with trilinear
// interpolation, the light-probe-proxy-volume / irradiance-volume approach. SH are kept as 27 halves per
// probe, as a shipping grid would store them (in memory padded to 28, so the blend's loads are whole:
// trilinear_blend.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bench {

// Probes per axis for a grid over [lo, hi] holding at most max_probes: the finest spacing common to every
// axis, then the axis of the widest spacing refined while the count still fits; an axis of zero extent
// gets one probe.
void grid_dims_for_count(const float lo[3], const float hi[3], size_t max_probes, int out_dims[3]);

// The probe positions of a grid, x fastest, then y, then z: lo + cell * index on each axis.
std::vector<float> grid_positions(const float lo[3], const float cell[3], const int dims[3]);

// Byte offsets of a grid cell's 8 corner records from its base record (corner c: +x if c & 1, +y if
// c & 2, +z if c & 4), for records stride[k] bytes apart along axis k.
void grid_corner_offsets(const size_t stride[3], size_t out_offsets[8]);

class GridPeer {
public:
    GridPeer(const float lo[3], const float hi[3], const int dims[3]);

    size_t probe_count() const { return size_t(dims_[0]) * dims_[1] * dims_[2]; }
    const int* dims() const { return dims_; }
    // Positions of the grid probes, x fastest, then y, then z (the order set_sh expects).
    std::vector<float> positions() const;
    // 27 floats per probe in positions() order, stored as halves.
    void set_sh(const std::vector<float>& sh);
    // Trilinear blend of the 8 surrounding probes; a point outside the grid is clamped onto it.
    void interpolate(const float position[3], float out_sh[27]) const;
    // Run-time data as it ships: 27 halves per probe plus the header (origin, cell size, dims).
    size_t bytes() const { return probe_count() * 27 * sizeof(uint16_t) + kHeaderBytes; }

    static constexpr size_t kHeaderBytes = 3 * sizeof(float) + 3 * sizeof(float) + 3 * sizeof(int32_t);

private:
    float lo_[3];
    float cell_[3];      // spacing per axis (0 on an axis with one probe)
    float inv_cell_[3];  // 0 on an axis with one probe
    int dims_[3];
    size_t stride_[3];   // bytes between neighbouring records along each axis (0 on an axis with one probe)
    size_t corner_offsets_[8];
    std::vector<uint16_t> halves_;  // 28 per probe
};

}  // namespace bench
