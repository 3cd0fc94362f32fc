// Shadow caster volumes and the conservative box / sphere tests against them.
#include "boundary.h"
#include "strides.h"

#include "core/shadow_caster_volume.h"

#include <cmath>
#include <string>

using tetprobe::fail;

namespace {

bool finite3(const float v[3]) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

tp_status check_planes(const float* planes, size_t plane_count) {
    tetprobe::checked_packed(planes, "planes", plane_count, "plane_count", 4 * sizeof(float));
    for (size_t i = 0; i < 4 * plane_count; ++i)
        if (!std::isfinite(planes[i]))
            return fail(TP_ERROR_INVALID_ARGUMENT, "plane " + std::to_string(i / 4) + " is not finite");
    return TP_OK;
}

}  // namespace

extern "C" {

TP_API size_t tp_shadow_caster_volume_bound(size_t plane_count) {
    if (plane_count > (SIZE_MAX - 1) / 4) return SIZE_MAX;  // no such volume fits in memory: never wrap
    return tetprobe::shadow_caster_volume_bound(plane_count);
}

TP_API tp_status tp_shadow_caster_volume(const float* planes, size_t plane_count, uint32_t light_type,
                                         const float light_vector[3], float* out_planes, size_t capacity,
                                         size_t* out_count) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(planes);
    TP_REQUIRE_NOT_NULL(light_vector);
    TP_REQUIRE_NOT_NULL(out_count);
    *out_count = 0;
    tetprobe::checked_packed(out_planes, "out_planes", capacity, "capacity", 4 * sizeof(float));
    if (tp_status s = check_planes(planes, plane_count)) return s;
    if (!finite3(light_vector)) return fail(TP_ERROR_INVALID_ARGUMENT, "light_vector is not finite");
    tetprobe::CasterLight light;
    switch (light_type) {
        case TP_LIGHT_DIRECTIONAL: light = tetprobe::CasterLight::directional; break;
        case TP_LIGHT_POINT:
        case TP_LIGHT_SPOT: light = tetprobe::CasterLight::point; break;  // a cone is inside the sphere
        default: return fail(TP_ERROR_INVALID_ARGUMENT, "unknown light_type " + std::to_string(light_type));
    }
    std::vector<tetprobe::Plane> region(plane_count);
    for (size_t i = 0; i < plane_count; ++i)
        region[i] = tetprobe::Plane(planes[4 * i], planes[4 * i + 1], planes[4 * i + 2], planes[4 * i + 3]);
    std::vector<tetprobe::Plane> volume = tetprobe::shadow_caster_volume(
        region, light, Eigen::Vector3d(light_vector[0], light_vector[1], light_vector[2]));
    *out_count = volume.size();
    if (volume.size() > capacity)
        return fail(TP_ERROR_BUFFER_TOO_SMALL, "the volume has " + std::to_string(volume.size()) +
                                                   " planes, capacity is " + std::to_string(capacity));
    for (size_t i = 0; i < volume.size(); ++i)
        for (int c = 0; c < 4; ++c) out_planes[4 * i + c] = float(volume[i][c]);
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_volume_test_aabb(const float* planes, size_t plane_count, const float box_min[3],
                                     const float box_max[3], int* out_intersects) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(box_min);
    TP_REQUIRE_NOT_NULL(box_max);
    TP_REQUIRE_NOT_NULL(out_intersects);
    *out_intersects = 1;
    if (tp_status s = check_planes(planes, plane_count)) return s;
    if (!finite3(box_min) || !finite3(box_max)) return fail(TP_ERROR_INVALID_ARGUMENT, "the box is not finite");
    for (int a = 0; a < 3; ++a)
        if (box_min[a] > box_max[a])
            return fail(TP_ERROR_INVALID_ARGUMENT, "box_min is above box_max on axis " + std::to_string(a));
    *out_intersects = tetprobe::volume_may_intersect_aabb(planes, plane_count, box_min, box_max) ? 1 : 0;
    return TP_OK;
    TP_API_END
}

TP_API tp_status tp_volume_test_sphere(const float* planes, size_t plane_count, const float center[3],
                                       float radius, int* out_intersects) {
    TP_API_BEGIN
    TP_REQUIRE_NOT_NULL(center);
    TP_REQUIRE_NOT_NULL(out_intersects);
    *out_intersects = 1;
    if (tp_status s = check_planes(planes, plane_count)) return s;
    if (!finite3(center)) return fail(TP_ERROR_INVALID_ARGUMENT, "center is not finite");
    if (!std::isfinite(radius) || radius < 0.0f)
        return fail(TP_ERROR_INVALID_ARGUMENT, "radius must be finite and >= 0");
    *out_intersects = tetprobe::volume_may_intersect_sphere(planes, plane_count, center, radius) ? 1 : 0;
    return TP_OK;
    TP_API_END
}

}  // extern "C"
