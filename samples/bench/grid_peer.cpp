#include "grid_peer.h"

#include "trilinear_blend.h"

#include "core/half.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bench {

void grid_dims_for_count(const float lo[3], const float hi[3], size_t max_probes, int out_dims[3]) {
    double extent[3], diagonal = 0;
    for (int k = 0; k < 3; ++k) extent[k] = double(hi[k]) - lo[k], diagonal += extent[k] * extent[k];
    diagonal = std::sqrt(diagonal);
    auto dims_at = [&](double spacing, int dims[3]) {
        size_t count = 1;
        for (int k = 0; k < 3; ++k) {
            dims[k] = extent[k] <= 1e-6 * diagonal ? 1 : 1 + int(std::floor(extent[k] / spacing));
            count *= size_t(dims[k]);
        }
        return count;
    };
    // The count falls as the spacing grows: bisect for the finest spacing that fits.
    double coarse = 2 * diagonal + 1, fine = diagonal * 1e-6 + 1e-9;
    int dims[3];
    if (dims_at(coarse, dims) > max_probes) throw std::invalid_argument("grid_dims_for_count: max_probes too small");
    for (int step = 0; step < 200; ++step) {
        const double mid = 0.5 * (coarse + fine);
        (dims_at(mid, dims) <= max_probes ? coarse : fine) = mid;
    }
    dims_at(coarse, out_dims);
    // Then spend what is left: refine the axis of the widest spacing while the count still fits.
    for (;;) {
        int widest = -1;
        double widest_spacing = 0;
        size_t count = size_t(out_dims[0]) * out_dims[1] * out_dims[2];
        for (int k = 0; k < 3; ++k) {
            if (extent[k] <= 1e-6 * diagonal || count / size_t(out_dims[k]) * size_t(out_dims[k] + 1) > max_probes) continue;
            const double spacing = out_dims[k] > 1 ? extent[k] / (out_dims[k] - 1) : INFINITY;
            if (spacing > widest_spacing) widest = k, widest_spacing = spacing;
        }
        if (widest < 0) return;
        ++out_dims[widest];
    }
}

std::vector<float> grid_positions(const float lo[3], const float cell[3], const int dims[3]) {
    std::vector<float> p;
    p.reserve(3 * size_t(dims[0]) * size_t(dims[1]) * size_t(dims[2]));
    for (int z = 0; z < dims[2]; ++z)
        for (int y = 0; y < dims[1]; ++y)
            for (int x = 0; x < dims[0]; ++x) {
                const int i[3] = {x, y, z};
                for (int k = 0; k < 3; ++k) p.push_back(lo[k] + cell[k] * float(i[k]));
            }
    return p;
}

void grid_corner_offsets(const size_t stride[3], size_t out_offsets[8]) {
    for (int c = 0; c < 8; ++c)
        out_offsets[c] = (c & 1 ? stride[0] : 0) + (c & 2 ? stride[1] : 0) + (c & 4 ? stride[2] : 0);
}

GridPeer::GridPeer(const float lo[3], const float hi[3], const int dims[3]) {
    for (int k = 0; k < 3; ++k) {
        if (dims[k] < 1) throw std::invalid_argument("GridPeer: dims must be >= 1");
        lo_[k] = lo[k];
        dims_[k] = dims[k];
        cell_[k] = dims[k] > 1 ? (hi[k] - lo[k]) / float(dims[k] - 1) : 0.0f;
        inv_cell_[k] = dims[k] > 1 ? 1.0f / cell_[k] : 0.0f;
    }
    // An axis of one probe has stride 0: its +1 corner is the same record, and its fraction is 0.
    size_t step = kGridHalves * sizeof(uint16_t);
    for (int k = 0; k < 3; ++k) {
        stride_[k] = dims_[k] > 1 ? step : 0;
        step *= size_t(dims_[k]);
    }
    grid_corner_offsets(stride_, corner_offsets_);
}

std::vector<float> GridPeer::positions() const { return grid_positions(lo_, cell_, dims_); }

void GridPeer::set_sh(const std::vector<float>& sh) {
    if (sh.size() != 27 * probe_count()) throw std::invalid_argument("GridPeer::set_sh: 27 floats per probe");
    halves_.assign(kGridHalves * probe_count(), 0);
    for (size_t p = 0; p < probe_count(); ++p)
        for (int i = 0; i < 27; ++i) halves_[kGridHalves * p + size_t(i)] = tetprobe::float_to_half(sh[27 * p + size_t(i)]);
}

void GridPeer::interpolate(const float position[3], float out_sh[27]) const {
    float frac[3];
    size_t offset = 0;
    for (int k = 0; k < 3; ++k) {
        // On an axis of one probe u is 0 (inv_cell 0), the base 0 and the fraction 0.
        const float u = std::min(std::max((position[k] - lo_[k]) * inv_cell_[k], 0.0f), float(dims_[k] - 1));
        const int base = std::max(std::min(int(u), dims_[k] - 2), 0);
        frac[k] = u - float(base);
        offset += size_t(base) * stride_[k];
    }
    trilinear_halves(reinterpret_cast<const uint8_t*>(halves_.data()) + offset, corner_offsets_, frac, out_sh);
}

}  // namespace bench
