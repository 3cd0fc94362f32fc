// Peer of the benchmark (never linked into a tetprobe library): a uniform probe grid as Unity's Adaptive
// Probe Volumes and Unreal's volumes ship one at a single density. Probes on a lattice over a box,
// trilinear interpolation of the 8 around a query (a query outside the box is clamped onto it), probes
// inside geometry marked invalid and given values dilated from their valid neighbours (dilate_probes), and
// SH in half floats (54 bytes a probe) or in APV's 8-bit L2 encoding (32 bytes, apv_sh_encoding.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

enum class GridEncoding { half, apv8 };

// Bytes a probe ships with: 27 halves, or APV's record.
size_t grid_probe_bytes(GridEncoding encoding);
const char* grid_encoding_id(GridEncoding encoding);

// Fills the SH (27 floats per probe) of invalid probes of a dims[0] x dims[1] x dims[2] lattice (x fastest):
// pass by pass, each invalid probe next to (26-neighbourhood) probes with values takes their mean, until
// every probe has one. Returns the passes it took; throws std::runtime_error when no probe is valid.
int dilate_probes(const int dims[3], std::vector<uint8_t> valid, std::vector<float>& sh);

class DilatedGrid {
public:
    static constexpr size_t kHeaderBytes = 9 * sizeof(float);  // origin, 1 / cell size, dims

    // The most probes (at least 2 per axis) whose grid over [lo, hi] ships within budget bytes.
    static void dims_for_budget(const float lo[3], const float hi[3], size_t budget_bytes, GridEncoding encoding,
                                int out_dims[3]);

    DilatedGrid(const float lo[3], const float hi[3], const int dims[3], GridEncoding encoding);

    size_t probe_count() const { return size_t(dims_[0]) * dims_[1] * dims_[2]; }
    const int* dims() const { return dims_; }
    GridEncoding encoding() const { return encoding_; }
    // Lattice positions, x fastest, then y, z.
    std::vector<float> positions() const;
    // sh: 27 floats per probe in positions() order, valid: 1 per probe; invalid probes' SH are dilated.
    void set_sh(std::vector<float> sh, const std::vector<uint8_t>& valid);
    // Trilinear blend of the 8 probes around the position.
    void interpolate(const float position[3], float out_sh[27]) const;
    // What ships (probes x grid_probe_bytes + header), and what this implementation holds (halves padded
    // to 28 for whole loads).
    size_t bytes() const { return probe_count() * grid_probe_bytes(encoding_) + kHeaderBytes; }
    size_t resident_bytes() const { return records_.size() + kHeaderBytes; }
    int dilation_passes() const { return dilation_passes_; }

private:
    float lo_[3], inv_cell_[3], cell_[3], top_[3];
    int dims_[3];
    size_t stride_[3];
    size_t record_bytes_;
    GridEncoding encoding_;
    std::vector<uint8_t> records_;
    size_t corner_offsets_[8];  // bytes from the base probe's record to each corner's
    int dilation_passes_ = 0;
};

}  // namespace bench
