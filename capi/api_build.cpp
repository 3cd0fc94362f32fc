// tp_store_build: the C ABI of the store builder (bake-time library only).
#include "bake/store_builder.h"
#include "capi/bake_structs.h"
#include "capi/boundary.h"
#include "capi/scene_handle.h"
#include "capi/strides.h"
#include "capi/store_handle.h"
#include "core/store.h"
#include "core/store_data.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace {

constexpr size_t kPositionBytes = 3 * sizeof(float);
constexpr size_t kShBytes = TP_SH_FLOATS * sizeof(float);

// Whether a caller's struct of struct_size bytes reaches to the end of the field at offset/size.
bool has_field(uint32_t struct_size, size_t offset, size_t size) { return size_t(struct_size) >= offset + size; }

#define TP_OPTION_FIELD(options, field) \
    has_field((options)->struct_size, offsetof(tp_build_options, field), sizeof((options)->field))

// Reads the fields the caller's version of tp_build_options has; the rest keep their defaults.
tetprobe::BuildSettings read_build_options(const tp_build_options* options) {
    tetprobe::BuildSettings settings;
    if (!options) return settings;
    if (!TP_OPTION_FIELD(options, flags)) {
        throw tetprobe::Error(tetprobe::Status::invalid_argument,
                              "options->struct_size " + std::to_string(options->struct_size) +
                                  " is too small (call tp_build_options_init)");
    }
    settings.flags = options->flags;  // TP_BUILD_* are the store's kFlag* bits (boundary.h)
    if (TP_OPTION_FIELD(options, merge_tolerance)) settings.merge_tolerance = options->merge_tolerance;
    if (TP_OPTION_FIELD(options, flat_tolerance)) settings.flat_tolerance = options->flat_tolerance;
    if (TP_OPTION_FIELD(options, progress))
        settings.progress = tetprobe::progress_from_c(
            options->progress, TP_OPTION_FIELD(options, progress_user) ? options->progress_user : nullptr);
    if (TP_OPTION_FIELD(options, occlusion_lights) && options->occlusion) {
        settings.occlusion = options->occlusion;
        settings.occlusion_stride = options->occlusion_stride;
        settings.occlusion_lights = options->occlusion_lights;
    }
    if (TP_OPTION_FIELD(options, scene) && options->scene) settings.scene = &options->scene->scene;
    return settings;
}

}  // namespace

extern "C" {

TP_API tp_status tp_store_build(const float* positions, size_t position_stride, const float* sh, size_t sh_stride,
                                size_t probe_count, const tp_build_options* options, tp_store** out_store) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(out_store);
    *out_store = nullptr;
    if (probe_count == 0) return tetprobe::fail(TP_ERROR_DEGENERATE, "no probes: a store needs at least one probe");
    using tetprobe::checked_buffer;
    position_stride =
        checked_buffer(positions, "positions", probe_count, "probe_count", position_stride, "position_stride", kPositionBytes);
    sh_stride = sh ? checked_buffer(sh, "sh", probe_count, "probe_count", sh_stride, "sh_stride", kShBytes) : kShBytes;
    tetprobe::BuildSettings settings = read_build_options(options);
    if (settings.occlusion)
        settings.occlusion_stride = checked_buffer(settings.occlusion, "options->occlusion", probe_count, "probe_count",
                                                   settings.occlusion_stride, "options->occlusion_stride", 4);

    const tetprobe::StoreData data =
        tetprobe::build_store_data(positions, position_stride, sh, sh_stride, probe_count, settings);
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(data);
    std::unique_ptr<tetprobe::Store> store = tetprobe::Store::load(blob.data(), blob.size());
    *out_store = new tp_store{std::move(store)};
    return TP_OK;
    TP_API_END
}

}  // extern "C"
