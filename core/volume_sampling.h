// Probe volumes for large objects (what Unity's Light Probe Proxy Volume does): the interpolated SH at every point
// of a small 3D grid around an object, for a renderer to upload as a 3D texture and sample per pixel. The grid is
// walked from neighbour to neighbour with one cell hint carried along, each point answered by the store's own
// single query (Store::interpolate), so every point is bit for bit what a single query there gives.
#pragma once

#include "core/error.h"
#include "core/store.h"

#include <cstddef>
#include <cstdint>

namespace tetprobe {

// The largest number of points along each side of a volume.
constexpr uint32_t kMaxVolumeSide = 32;

// What a volume holds per point (the values of TP_VOLUME_*).
enum class VolumeFormat : uint32_t {
    sh_l2 = 0,      // 27 floats, the SH contract
    sh_l1 = 1,      // 12 floats: bands 0 and 1, [r0..r3, g0..g3, b0..b3]
    unity_l1 = 2,   // 3 float4: unity_SHAr, SHAg, SHAb of the L1 SH (unity_sh_constants.h)
    unity_l2 = 3,   // 7 float4: unity_SHAr, SHAg, SHAb, SHBr, SHBg, SHBb, SHC
};

// Floats written at once (a point's SH, or one float4 of a Unity format) and how many of those a point has.
uint32_t volume_unit_floats(VolumeFormat format);
uint32_t volume_units_per_point(VolumeFormat format);

struct VolumeGrid {
    float origin[3] = {0, 0, 0};     // world position of point (0, 0, 0)
    float cell_size[3] = {1, 1, 1};  // spacing of the points along x, y, z
    uint32_t dims[3] = {1, 1, 1};    // points along x, y, z, 1..kMaxVolumeSide each
};

// Where a volume's values go: point (x, y, z)'s unit k starts x * point + y * row + z * slice + k * unit bytes
// from the output (strides already resolved and checked by the caller; no alignment needed).
struct VolumeStrides {
    size_t point = 0, row = 0, slice = 0, unit = 0;
};

// Throws Error(Status::invalid_argument) for a side of 0 or above kMaxVolumeSide, an unknown format, a
// non-finite origin, a cell size that is not finite and positive, or a far corner that is not finite.
void validate_volume(const VolumeGrid& grid, uint32_t format);

// World coordinate of point index i along an axis: the product is exact in double, so the one rounding to
// float is the same whether or not the compiler fuses the multiply and add.
inline float volume_coordinate(float origin, float cell_size, uint32_t i) {
    return float(double(origin) + double(i) * double(cell_size));
}

// Fills a validated volume. The walk: slices z = 0, 1, ...; within slice z the rows y ascending when z is even,
// descending when odd; within the r-th row walked (r counted over the whole walk from 0) x ascending when r is even,
// descending when odd, so each point is a neighbour of the one before. Point after point, Store::interpolate runs
// with *hint (may be null: start cold), which it updates; on return *hint is the cell of point (0, 0, 0), where
// the next frame's walk starts. A point the query fails at (outside a store without extrapolation, or a forged
// store's query that gave up) gets zero SH (in a Unity format: the constants of zero SH), and the walk goes on.
// Returns ok or the first failure, with its point in first_failed[3]. Never allocates, never throws.
Status sample_volume(const Store& store, const VolumeGrid& grid, VolumeFormat format, const VolumeStrides& strides,
                     int32_t* hint, void* out, uint32_t first_failed[3]);

}  // namespace tetprobe
