// Probe placement and probes inside geometry (full library only).
#include "bake_structs.h"
#include "boundary.h"
#include "scene_handle.h"
#include "strides.h"

#include "bake/inside_probe_fix.h"
#include "bake/inside_test.h"
#include "bake/probe_placement.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

using tetprobe::fail;

namespace {

// Copies count strided positions, refusing non-finite ones (count 0 gives none).
tp_status read_positions(const float* positions, size_t stride, size_t count, std::vector<float>& out) {
    tetprobe::copy_finite_positions(positions, stride, count, out);
    return TP_OK;
}

// The struct before light_clearance was added: a caller built against it gets that field's default.
constexpr size_t kFirstPlacementOptionsSize = offsetof(tp_placement_options, light_clearance);

static_assert(TP_PLACEMENT_WHOLE == uint32_t(tetprobe::PlacementMode::whole) &&
                  TP_PLACEMENT_WALKABLE == uint32_t(tetprobe::PlacementMode::walkable),
              "TP_PLACEMENT_* must equal PlacementMode");

// The one reading of tp_placement_options.
tp_status read_placement_options(const tp_placement_options* options, tetprobe::PlacementSettings& settings) {
    if (!options) return TP_OK;
    if (options->struct_size < kFirstPlacementOptionsSize)
        return fail(TP_ERROR_INVALID_ARGUMENT, "options->struct_size is not set (call tp_placement_options_init)");
    if (options->mode != TP_PLACEMENT_WHOLE && options->mode != TP_PLACEMENT_WALKABLE)
        return fail(TP_ERROR_INVALID_ARGUMENT, "unknown placement mode " + std::to_string(options->mode));
    if (options->rays < 2)
        return fail(TP_ERROR_INVALID_ARGUMENT, "options->rays must be at least 2 (the candidates are baked in two halves)");
    settings.rules.mode = static_cast<tetprobe::PlacementMode>(options->mode);
    settings.rules.spacing = options->spacing;
    settings.rules.margin = options->margin;
    settings.rules.walk_min_height = options->walk_min_height;
    settings.rules.walk_max_height = options->walk_max_height;
    settings.target_count = options->target_count;
    settings.error_bound = options->error_bound;
    settings.rays = options->rays;
    settings.bounces = options->bounces;
    settings.seed = options->seed;
    settings.threads = options->threads;
    settings.progress = tetprobe::progress_from_c(options->progress, options->progress_user);
    if (options->struct_size >= offsetof(tp_placement_options, light_clearance) + sizeof(float))
        settings.light_clearance = options->light_clearance;
    return TP_OK;
}

}  // namespace

extern "C" {

TP_API tp_status tp_place_probes_bound(const tp_scene* scene, const tp_placement_options* options, size_t* out_bound) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_bound);
    *out_bound = 0;
    tetprobe::PlacementSettings settings;
    if (tp_status s = read_placement_options(options, settings)) return s;
    *out_bound = tetprobe::placement_bound(scene->scene, settings);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_place_probes(const tp_scene* scene, const tp_placement_options* options, float* out_positions,
                                 size_t capacity, size_t* out_count, float* out_error_curve, size_t curve_capacity,
                                 size_t* out_curve_points) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_positions);
    TP_REQUIRE_NOT_NULL(out_count);
    *out_count = 0;
    if (out_curve_points) *out_curve_points = 0;
    tetprobe::checked_packed(out_positions, "out_positions", capacity, "capacity", 3 * sizeof(float));
    if (out_error_curve)
        tetprobe::checked_packed(out_error_curve, "out_error_curve", curve_capacity, "curve_capacity", 2 * sizeof(float));
    tetprobe::PlacementSettings settings;
    if (tp_status s = read_placement_options(options, settings)) return s;
    const tetprobe::Placement placement = tetprobe::place_probes(scene->scene, settings);
    const size_t count = placement.positions.size() / 3, points = placement.curve.size();
    *out_count = count;
    if (out_curve_points) *out_curve_points = points;
    if (count > capacity)
        return fail(TP_ERROR_BUFFER_TOO_SMALL, "the placement has " + std::to_string(count) + " probes, capacity is " +
                                                   std::to_string(capacity) + " (size it with tp_place_probes_bound)");
    if (out_error_curve && points > curve_capacity)
        return fail(TP_ERROR_BUFFER_TOO_SMALL, "the error curve has " + std::to_string(points) +
                                                   " points, curve_capacity is " + std::to_string(curve_capacity) +
                                                   " (size it with tp_place_probes_bound)");
    std::memcpy(out_positions, placement.positions.data(), placement.positions.size() * sizeof(float));
    if (out_error_curve)
        for (size_t i = 0; i < points; ++i) {
            out_error_curve[2 * i] = float(placement.curve[i].probes);
            out_error_curve[2 * i + 1] = float(placement.curve[i].error);
        }
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_find_inside_probes(const tp_scene* scene, const float* positions, size_t position_stride,
                                       size_t count, uint32_t* out_indices, size_t capacity, size_t* out_count) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_count);
    *out_count = 0;
    tetprobe::checked_packed(out_indices, "out_indices", capacity, "capacity", sizeof(uint32_t));
    std::vector<float> probes;
    if (tp_status s = read_positions(positions, position_stride, count, probes)) return s;
    const std::vector<uint32_t> inside = tetprobe::find_inside_probes(scene->scene, probes, 0);
    *out_count = inside.size();
    if (inside.size() > capacity)
        return fail(TP_ERROR_BUFFER_TOO_SMALL, std::to_string(inside.size()) + " probes are inside geometry, capacity is " +
                                                   std::to_string(capacity));
    if (!inside.empty()) std::memcpy(out_indices, inside.data(), inside.size() * sizeof(uint32_t));
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_fix_inside_probes(const tp_scene* scene, const float* positions, size_t position_stride,
                                      size_t count, uint32_t mode, float margin, float* out_positions,
                                      size_t capacity, size_t* out_count) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(scene);
    TP_REQUIRE_NOT_NULL(out_count);
    *out_count = 0;
    tetprobe::checked_packed(out_positions, "out_positions", capacity, "capacity", 3 * sizeof(float));
    if (mode != TP_INSIDE_DROP && mode != TP_INSIDE_PUSH)
        return fail(TP_ERROR_INVALID_ARGUMENT, "unknown mode " + std::to_string(mode) + " (TP_INSIDE_DROP or TP_INSIDE_PUSH)");
    std::vector<float> probes;
    if (tp_status s = read_positions(positions, position_stride, count, probes)) return s;
    const std::vector<float> fixed = tetprobe::fix_inside_probes(scene->scene, probes, static_cast<tetprobe::InsideFix>(mode),
                                                                 margin, 0);
    *out_count = fixed.size() / 3;
    if (fixed.size() / 3 > capacity)
        return fail(TP_ERROR_BUFFER_TOO_SMALL, "the result has " + std::to_string(fixed.size() / 3) +
                                                   " probes, capacity is " + std::to_string(capacity));
    if (!fixed.empty()) std::memmove(out_positions, fixed.data(), fixed.size() * sizeof(float));
    return TP_OK;
    TP_API_END
}

}  // extern "C"
