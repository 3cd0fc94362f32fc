// C ABI of the SH helpers (the contract is written in tetprobe.h).
#include "boundary.h"
#include "core/sh.h"
#include "core/sh_eval_options.h"
#include "struct_defaults.h"

#include <cmath>
#include <cstddef>
#include <string>

namespace tetprobe {

namespace {

// A finite, non-zero direction scaled to unit length (callers may pass any length).
tp_status unit_direction(const float in[3], float out[3], const char* name) {
    const double length = std::sqrt(double(in[0]) * in[0] + double(in[1]) * in[1] + double(in[2]) * in[2]);
    if (!std::isfinite(length) || !(length > 0))
        return fail(TP_ERROR_INVALID_ARGUMENT, std::string(name) + " must be finite and non-zero");
    for (int k = 0; k < 3; ++k) out[k] = float(in[k] / length);
    return TP_OK;
}

tp_status require_finite(const float* values, int count, const char* name) {
    for (int i = 0; i < count; ++i)
        if (!std::isfinite(values[i])) return fail(TP_ERROR_INVALID_ARGUMENT, std::string(name) + " is not finite");
    return TP_OK;
}

// One set of values: the C ABI's order and window constants are the run time's enumerators.
static_assert(TP_SH_ORDER_L2 == uint32_t(ShOrder::l2) && TP_SH_ORDER_L1 == uint32_t(ShOrder::l1) &&
                  TP_SH_ORDER_ZH3 == uint32_t(ShOrder::zh3),
              "TP_SH_ORDER_* must equal ShOrder");
static_assert(TP_SH_WINDOW_NONE == uint32_t(ShWindow::none) && TP_SH_WINDOW_SLOAN == uint32_t(ShWindow::sloan) &&
                  TP_SH_WINDOW_NONNEGATIVE == uint32_t(ShWindow::nonnegative),
              "TP_SH_WINDOW_* must equal ShWindow");

// Whether a caller's struct of struct_size bytes reaches to the end of the field at offset/size.
bool has_field(uint32_t struct_size, size_t offset, size_t size) { return size_t(struct_size) >= offset + size; }

#define TP_SH_OPTION_FIELD(options, field) \
    has_field((options)->struct_size, offsetof(tp_sh_eval_options, field), sizeof((options)->field))

// The run time's options from the caller's (NULL = defaults); fields past struct_size keep their defaults.
tp_status read_eval_options(const tp_sh_eval_options* options, ShEvalOptions& out) {
    out = ShEvalOptions{};
    if (!options) return TP_OK;
    if (!TP_SH_OPTION_FIELD(options, order))
        return fail(TP_ERROR_INVALID_ARGUMENT, "options->struct_size " + std::to_string(options->struct_size) +
                                                   " is too small (call tp_sh_eval_options_init)");
    if (options->order > TP_SH_ORDER_ZH3)
        return fail(TP_ERROR_INVALID_ARGUMENT, "options->order " + std::to_string(options->order) +
                                                   " is not a TP_SH_ORDER_* value");
    out.order = ShOrder(options->order);
    if (TP_SH_OPTION_FIELD(options, window)) {
        if (options->window > TP_SH_WINDOW_NONNEGATIVE)
            return fail(TP_ERROR_INVALID_ARGUMENT, "options->window " + std::to_string(options->window) +
                                                       " is not a TP_SH_WINDOW_* value");
        out.window = ShWindow(options->window);
    }
    if (out.window == ShWindow::sloan) {
        const float strength = TP_SH_OPTION_FIELD(options, window_strength) ? options->window_strength : 0.0f;
        if (!std::isfinite(strength) || strength < 0)
            return fail(TP_ERROR_INVALID_ARGUMENT, "options->window_strength " + std::to_string(strength) +
                                                       " must be finite and >= 0");
        out.window_strength = strength;
    }
    return TP_OK;
}

}  // namespace

}  // namespace tetprobe

using namespace tetprobe;

extern "C" {

TP_API tp_status tp_sh_eval_radiance(const float sh[27], const float direction[3], float out_rgb[3]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    TP_REQUIRE_NOT_NULL(direction);
    TP_REQUIRE_NOT_NULL(out_rgb);
    float d[3];
    if (tp_status s = unit_direction(direction, d, "direction")) return s;
    sh_eval_radiance(sh, d, out_rgb);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_eval_irradiance(const float sh[27], const float normal[3], float out_rgb[3]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    TP_REQUIRE_NOT_NULL(normal);
    TP_REQUIRE_NOT_NULL(out_rgb);
    float n[3];
    if (tp_status s = unit_direction(normal, n, "normal")) return s;
    sh_eval_irradiance(sh, n, out_rgb);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_add_ambient(float sh[27], const float rgb[3]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    TP_REQUIRE_NOT_NULL(rgb);
    if (tp_status s = require_finite(rgb, 3, "rgb")) return s;
    sh_add_ambient(sh, rgb);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_add_directional(float sh[27], const float direction[3], const float rgb[3]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    TP_REQUIRE_NOT_NULL(direction);
    TP_REQUIRE_NOT_NULL(rgb);
    float d[3];
    if (tp_status s = unit_direction(direction, d, "direction")) return s;
    if (tp_status s = require_finite(rgb, 3, "rgb")) return s;
    sh_add_directional(sh, d, rgb);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_eval_irradiance_ex(const float sh[27], const float normal[3],
                                          const tp_sh_eval_options* options, float out_rgb[3]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    TP_REQUIRE_NOT_NULL(normal);
    TP_REQUIRE_NOT_NULL(out_rgb);
    ShEvalOptions settings;
    if (tp_status s = read_eval_options(options, settings)) return s;
    if (settings.window == ShWindow::nonnegative)
        if (tp_status s = require_finite(sh, 27, "sh")) return s;
    float n[3];
    if (tp_status s = unit_direction(normal, n, "normal")) return s;
    sh_eval_irradiance_with_options(sh, n, settings, out_rgb);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_apply_options(float sh[27], const tp_sh_eval_options* options) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    ShEvalOptions settings;
    if (tp_status s = read_eval_options(options, settings)) return s;
    if (settings.window == ShWindow::nonnegative)
        if (tp_status s = require_finite(sh, 27, "sh")) return s;
    sh_apply_eval_options(sh, settings);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_min_irradiance(const float sh[27], const tp_sh_eval_options* options, float out_min_rgb[3],
                                      float out_normal[3]) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    TP_REQUIRE_NOT_NULL(out_min_rgb);
    TP_REQUIRE_NOT_NULL(out_normal);
    ShEvalOptions settings;
    if (tp_status s = read_eval_options(options, settings)) return s;
    if (tp_status s = require_finite(sh, 27, "sh")) return s;
    sh_min_irradiance_with_options(sh, settings, out_min_rgb, out_normal);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_sh_nonnegative_window_strength(const float sh[27], const tp_sh_eval_options* options,
                                                   float* out_strength) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(sh);
    TP_REQUIRE_NOT_NULL(out_strength);
    ShEvalOptions settings;
    if (tp_status s = read_eval_options(options, settings)) return s;
    if (tp_status s = require_finite(sh, 27, "sh")) return s;
    float ordered[27];
    for (int i = 0; i < 27; ++i) ordered[i] = sh[i];
    sh_apply_order(ordered, settings.order);
    *out_strength = float(sh_nonnegative_window_strength(ordered));
    return TP_OK;
    TP_API_END
}

}  // extern "C"
