// Probe volumes: the grid walked point to point with a carried hint, each point the store's single query.
#include "core/volume_sampling.h"

#include "core/unity_sh_constants.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace tetprobe {

uint32_t volume_unit_floats(VolumeFormat format) {
    switch (format) {
        case VolumeFormat::sh_l2: return 27;
        case VolumeFormat::sh_l1: return 12;
        default: return 4;
    }
}

uint32_t volume_units_per_point(VolumeFormat format) {
    switch (format) {
        case VolumeFormat::unity_l1: return kUnityL1Floats / 4;
        case VolumeFormat::unity_l2: return kUnityL2Floats / 4;
        default: return 1;
    }
}

void validate_volume(const VolumeGrid& grid, uint32_t format) {
    if (format > uint32_t(VolumeFormat::unity_l2))
        throw Error(Status::invalid_argument, "unknown volume format " + std::to_string(format));
    for (int a = 0; a < 3; ++a) {
        const std::string axis = "[" + std::to_string(a) + "]";
        if (grid.dims[a] == 0) throw Error(Status::invalid_argument, "dims" + axis + " is 0 (a volume has at least 1 point a side)");
        if (grid.dims[a] > kMaxVolumeSide)
            throw Error(Status::invalid_argument, "dims" + axis + " (" + std::to_string(grid.dims[a]) +
                                                      ") is above " + std::to_string(kMaxVolumeSide) +
                                                      ", the most points a side of a volume has");
        if (!std::isfinite(grid.origin[a])) throw Error(Status::invalid_argument, "origin" + axis + " is not finite");
        if (!std::isfinite(grid.cell_size[a]) || !(grid.cell_size[a] > 0))
            throw Error(Status::invalid_argument, "cell_size" + axis + " is not finite and positive");
        if (!std::isfinite(volume_coordinate(grid.origin[a], grid.cell_size[a], grid.dims[a] - 1)))
            throw Error(Status::invalid_argument, "the volume's far corner along axis " + std::to_string(a) +
                                                      " is not finite (origin + (dims - 1) x cell_size overflows)");
    }
}

namespace {

// Writes one point's SH in the format's layout.
void write_point(const float sh[27], VolumeFormat format, const VolumeStrides& strides, unsigned char* at) {
    switch (format) {
        case VolumeFormat::sh_l2:
            std::memcpy(at, sh, 27 * sizeof(float));
            break;
        case VolumeFormat::sh_l1:
            for (int c = 0; c < 3; ++c) std::memcpy(at + 16 * c, sh + 9 * c, 4 * sizeof(float));
            break;
        case VolumeFormat::unity_l1:
        case VolumeFormat::unity_l2: {
            float constants[kUnityL2Floats];
            const bool l2 = format == VolumeFormat::unity_l2;
            unity_sh_constants(sh, l2, constants);
            const int units = l2 ? kUnityL2Floats / 4 : kUnityL1Floats / 4;
            for (int k = 0; k < units; ++k) std::memcpy(at + k * strides.unit, constants + 4 * k, 4 * sizeof(float));
            break;
        }
    }
}

}  // namespace

Status sample_volume(const Store& store, const VolumeGrid& grid, VolumeFormat format, const VolumeStrides& strides,
                     int32_t* hint, void* out, uint32_t first_failed[3]) {
    const uint32_t nx = grid.dims[0], ny = grid.dims[1], nz = grid.dims[2];
    float xs[kMaxVolumeSide], ys[kMaxVolumeSide], zs[kMaxVolumeSide];
    for (uint32_t i = 0; i < nx; ++i) xs[i] = volume_coordinate(grid.origin[0], grid.cell_size[0], i);
    for (uint32_t i = 0; i < ny; ++i) ys[i] = volume_coordinate(grid.origin[1], grid.cell_size[1], i);
    for (uint32_t i = 0; i < nz; ++i) zs[i] = volume_coordinate(grid.origin[2], grid.cell_size[2], i);
    int32_t carried = hint ? *hint : -1;
    int32_t first_cell = carried;
    Status result = Status::ok;
    unsigned char* base = static_cast<unsigned char*>(out);
    uint32_t row = 0;  // rows walked so far
    for (uint32_t z = 0; z < nz; ++z) {
        for (uint32_t yy = 0; yy < ny; ++yy, ++row) {
            const uint32_t y = z % 2 == 0 ? yy : ny - 1 - yy;
            for (uint32_t xx = 0; xx < nx; ++xx) {
                const uint32_t x = row % 2 == 0 ? xx : nx - 1 - xx;
                const float position[3] = {xs[x], ys[y], zs[z]};
                unsigned char* const at = base + x * strides.point + y * strides.row + z * strides.slice;
                // L2 into a float-aligned point: the query blends straight into it (a copy of a buffer just
                // written costs more than the copy itself: a store-forwarding stall).
                const bool direct = format == VolumeFormat::sh_l2 && reinterpret_cast<uintptr_t>(at) % alignof(float) == 0;
                float sh[27];
                float* const target = direct ? reinterpret_cast<float*>(at) : sh;
                const Status status = store.interpolate(position, &carried, target);
                if (status != Status::ok && result == Status::ok) {
                    result = status;
                    first_failed[0] = x, first_failed[1] = y, first_failed[2] = z;
                }
                if (row == 0 && xx == 0) first_cell = carried;
                if (!direct) write_point(sh, format, strides, at);
            }
        }
    }
    if (hint) *hint = first_cell;
    return result;
}

}  // namespace tetprobe
