// C ABI of the SH helpers (the contract is written in tetprobe.h).
#include "boundary.h"
#include "core/sh.h"
#include "core/sh_eval_options.h"
#include "core/sh_window.h"
#include "sh_eval_options_struct.h"

#include <cmath>
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
    if (tp_status s = read_sh_eval_options(options, settings)) return s;
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
    if (tp_status s = read_sh_eval_options(options, settings)) return s;
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
    if (tp_status s = read_sh_eval_options(options, settings)) return s;
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
    ShOrder order;
    if (tp_status s = read_sh_order(options, order)) return s;  // the window fields are not read
    if (tp_status s = require_finite(sh, 27, "sh")) return s;
    float ordered[27];
    for (int i = 0; i < 27; ++i) ordered[i] = sh[i];
    sh_apply_order(ordered, order);
    *out_strength = float(sh_nonnegative_window_strength(ordered));
    return TP_OK;
    TP_API_END
}

}  // extern "C"
