// C ABI of the SH helpers (the contract is written in tetprobe.h).
#include "boundary.h"
#include "core/sh.h"

#include <cmath>

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

}  // extern "C"
