#include "dilated_grid.h"

#include "apv_sh_encoding.h"
#include "grid_peer.h"
#include "trilinear_blend.h"

#include "core/half.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace bench {

size_t grid_probe_bytes(GridEncoding encoding) { return encoding == GridEncoding::half ? 27 * 2 : kApvRecordBytes; }
const char* grid_encoding_id(GridEncoding encoding) { return encoding == GridEncoding::half ? "half" : "apv8"; }

int dilate_probes(const int dims[3], std::vector<uint8_t> valid, std::vector<float>& sh) {
    const size_t count = size_t(dims[0]) * dims[1] * dims[2];
    if (std::find(valid.begin(), valid.end(), uint8_t(1)) == valid.end())
        throw std::runtime_error("dilate_probes: no probe is valid");
    int passes = 0;
    for (;;) {
        std::vector<size_t> filled;
        std::vector<float> values;
        for (size_t i = 0; i < count; ++i) {
            if (valid[i]) continue;
            const int x = int(i % size_t(dims[0])), y = int(i / size_t(dims[0]) % size_t(dims[1])),
                      z = int(i / (size_t(dims[0]) * dims[1]));
            float sum[27] = {};
            int n = 0;
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int a = x + dx, b = y + dy, c = z + dz;
                        if (a < 0 || b < 0 || c < 0 || a >= dims[0] || b >= dims[1] || c >= dims[2]) continue;
                        const size_t j = size_t(a) + size_t(dims[0]) * (size_t(b) + size_t(dims[1]) * size_t(c));
                        if (!valid[j]) continue;
                        for (int k = 0; k < 27; ++k) sum[k] += sh[27 * j + size_t(k)];
                        ++n;
                    }
            if (n == 0) continue;
            filled.push_back(i);
            for (float s : sum) values.push_back(s / float(n));
        }
        if (filled.empty()) return passes;
        ++passes;
        for (size_t f = 0; f < filled.size(); ++f) {
            std::copy(&values[27 * f], &values[27 * f] + 27, &sh[27 * filled[f]]);
            valid[filled[f]] = 1;
        }
    }
}

void DilatedGrid::dims_for_budget(const float lo[3], const float hi[3], size_t budget_bytes, GridEncoding encoding,
                                  int out_dims[3]) {
    const size_t per_probe = grid_probe_bytes(encoding);
    if (budget_bytes < kHeaderBytes + 8 * per_probe) {
        out_dims[0] = out_dims[1] = out_dims[2] = 2;
        return;
    }
    grid_dims_for_count(lo, hi, (budget_bytes - kHeaderBytes) / per_probe, out_dims);
    for (int k = 0; k < 3; ++k) out_dims[k] = std::max(out_dims[k], 2);
}

DilatedGrid::DilatedGrid(const float lo[3], const float hi[3], const int dims[3], GridEncoding encoding)
    : encoding_(encoding) {
    record_bytes_ = encoding == GridEncoding::half ? kGridHalves * 2 : kApvRecordBytes;
    for (int k = 0; k < 3; ++k) {
        if (dims[k] < 2) throw std::invalid_argument("DilatedGrid: at least 2 probes per axis");
        dims_[k] = dims[k];
        lo_[k] = lo[k];
        cell_[k] = std::max(hi[k] - lo[k], 1e-6f) / float(dims[k] - 1);
        inv_cell_[k] = 1.0f / cell_[k];
        // The largest u whose base cell is dims - 2 with frac <= 1.
        top_[k] = float(dims[k] - 1);
    }
    stride_[0] = record_bytes_, stride_[1] = stride_[0] * size_t(dims_[0]), stride_[2] = stride_[1] * size_t(dims_[1]);
    grid_corner_offsets(stride_, corner_offsets_);
}

std::vector<float> DilatedGrid::positions() const { return grid_positions(lo_, cell_, dims_); }

void DilatedGrid::set_sh(std::vector<float> sh, const std::vector<uint8_t>& valid) {
    if (sh.size() != 27 * probe_count() || valid.size() != probe_count())
        throw std::invalid_argument("DilatedGrid::set_sh: 27 floats and a flag per probe");
    dilation_passes_ = dilate_probes(dims_, valid, sh);
    records_.assign(probe_count() * record_bytes_, 0);
    for (size_t i = 0; i < probe_count(); ++i) {
        uint8_t* r = &records_[i * record_bytes_];
        if (encoding_ == GridEncoding::apv8) {
            apv_encode(&sh[27 * i], r);
        } else {
            for (int k = 0; k < 27; ++k) {
                const uint16_t h = tetprobe::float_to_half(sh[27 * i + size_t(k)]);
                std::memcpy(r + 2 * k, &h, 2);
            }
        }
    }
}

void DilatedGrid::interpolate(const float position[3], float out_sh[27]) const {
    float frac[3];
    size_t offset = 0;
    for (int k = 0; k < 3; ++k) {
        const float u = std::min(std::max((position[k] - lo_[k]) * inv_cell_[k], 0.0f), top_[k]);
        const int base = std::min(int(u), dims_[k] - 2);
        frac[k] = u - float(base);
        offset += size_t(base) * stride_[k];
    }
    if (encoding_ == GridEncoding::half) trilinear_halves(records_.data() + offset, corner_offsets_, frac, out_sh);
    else trilinear_apv(records_.data() + offset, corner_offsets_, frac, out_sh);
}

}  // namespace bench
