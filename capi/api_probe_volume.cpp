// C ABI of probe volumes: the layout checked and resolved here, the walk in core/volume_sampling.
#include "boundary.h"
#include "strides.h"

#include "core/volume_sampling.h"
#include "store_handle.h"

#include <cstddef>
#include <cstring>
#include <string>

using tetprobe::fail;

namespace {

static_assert(TP_VOLUME_MAX_SIDE == tetprobe::kMaxVolumeSide, "TP_VOLUME_MAX_SIDE must equal kMaxVolumeSide");
static_assert(TP_VOLUME_SH_L2 == uint32_t(tetprobe::VolumeFormat::sh_l2) &&
                  TP_VOLUME_SH_L1 == uint32_t(tetprobe::VolumeFormat::sh_l1) &&
                  TP_VOLUME_UNITY_L1 == uint32_t(tetprobe::VolumeFormat::unity_l1) &&
                  TP_VOLUME_UNITY_L2 == uint32_t(tetprobe::VolumeFormat::unity_l2),
              "TP_VOLUME_* must equal VolumeFormat");

tp_volume_layout default_volume_layout() {
    tp_volume_layout layout{};
    layout.struct_size = sizeof layout;
    layout.format = TP_VOLUME_SH_L2;
    return layout;
}

// The caller's layout (NULL = defaults); fields beyond an older caller's struct_size keep their defaults.
tp_volume_layout read_layout(const tp_volume_layout* given) {
    tp_volume_layout layout = default_volume_layout();
    if (!given) return layout;
    if (given->struct_size < offsetof(tp_volume_layout, format) + sizeof(uint32_t))
        throw tetprobe::Error(tetprobe::Status::invalid_argument,
                              "layout->struct_size is not set (use tp_volume_layout_init)");
    const size_t n = given->struct_size < sizeof layout ? given->struct_size : sizeof layout;
    std::memcpy(reinterpret_cast<unsigned char*>(&layout) + sizeof(uint32_t),
                reinterpret_cast<const unsigned char*>(given) + sizeof(uint32_t), n - sizeof(uint32_t));
    layout.struct_size = sizeof layout;
    return layout;
}

// Resolves the strides (0 = packed) and checks that every byte the volume writes lies in one object at out:
// each stride at least the bytes written at once, each axis's span and their sum within PTRDIFF_MAX, and
// nothing wrapping the address space (strides.h).
tetprobe::VolumeStrides resolve_strides(const tp_volume_layout& layout, tetprobe::VolumeFormat format,
                                        const uint32_t dims[3], const float* out) {
    const size_t unit = tetprobe::volume_unit_floats(format) * sizeof(float);
    const size_t units = tetprobe::volume_units_per_point(format);
    tetprobe::VolumeStrides s;
    s.unit = units > 1 ? tetprobe::checked_buffer(out, "out", units, "float4s per point", layout.vector_stride,
                                                  "vector_stride", unit)
                       : unit;
    s.point = tetprobe::checked_buffer(out, "out", dims[0], "dims[0]", layout.point_stride ? layout.point_stride : units * unit,
                                       "point_stride", unit);
    s.row = tetprobe::checked_buffer(out, "out", dims[1], "dims[1]", layout.row_stride ? layout.row_stride : dims[0] * s.point,
                                     "row_stride", unit);
    s.slice = tetprobe::checked_buffer(out, "out", dims[2], "dims[2]",
                                       layout.slice_stride ? layout.slice_stride : dims[1] * s.row, "slice_stride", unit);
    // The last byte written: the sum of each axis's span, each already within PTRDIFF_MAX.
    const size_t spans[4] = {(dims[0] - 1) * s.point, (dims[1] - 1) * s.row, (dims[2] - 1) * s.slice, (units - 1) * s.unit};
    size_t extent = unit;
    for (size_t span : spans) {
        if (span > size_t(PTRDIFF_MAX) - extent)
            throw tetprobe::Error(tetprobe::Status::invalid_argument,
                                  "the volume's layout spans more than PTRDIFF_MAX bytes (its strides overflow)");
        extent += span;
    }
    if (!tetprobe::buffer_fits(out, 1, 0, extent))
        throw tetprobe::Error(tetprobe::Status::invalid_argument, "the volume's layout overflows the address space at out");
    return s;
}

}  // namespace

extern "C" {

TP_API tp_status tp_volume_layout_init(tp_volume_layout* layout) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(layout);
    *layout = default_volume_layout();
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_store_sample_volume(const tp_store* store, const float origin[3], const float cell_size[3],
                                        const uint32_t dims[3], int32_t* cell_hint, const tp_volume_layout* layout,
                                        float* out) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(store);
    TP_REQUIRE_NOT_NULL(origin);
    TP_REQUIRE_NOT_NULL(cell_size);
    TP_REQUIRE_NOT_NULL(dims);
    TP_REQUIRE_NOT_NULL(out);
    const tp_volume_layout settings = read_layout(layout);
    tetprobe::VolumeGrid grid;
    for (int a = 0; a < 3; ++a) {
        grid.origin[a] = origin[a];
        grid.cell_size[a] = cell_size[a];
        grid.dims[a] = dims[a];
    }
    tetprobe::validate_volume(grid, settings.format);
    const auto format = static_cast<tetprobe::VolumeFormat>(settings.format);
    const tetprobe::VolumeStrides strides = resolve_strides(settings, format, grid.dims, out);
    uint32_t failed[3] = {0, 0, 0};
    const tetprobe::Status status = tetprobe::sample_volume(*store->store, grid, format, strides, cell_hint, out, failed);
    if (status == tetprobe::Status::ok) return TP_OK;
    const std::string point = "(" + std::to_string(failed[0]) + ", " + std::to_string(failed[1]) + ", " +
                              std::to_string(failed[2]) + ")";
    if (status == tetprobe::Status::outside)
        return fail(status, "volume points are outside the probes' hull (store built without extrapolation); the first "
                            "walked at point " + point + " (their SH is zero)");
    return fail(status, "a query gave up after examining its cap of cells (a corrupt or forged store); the first at "
                        "volume point " + point + " (the SH of failed points is zero)");
    TP_API_END
}

}  // extern "C"
