#include "bake/occlusion_bake.h"

#include "bake/parallel_jobs.h"
#include "bake/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetprobe {

std::vector<uint8_t> bake_occlusion(const Scene& scene, const std::vector<float>& positions,
                                    const BakeSettings& settings, uint32_t* mixed_lights) {
    std::vector<const Light*> mixed;
    for (const Light& light : scene.lights())
        if (light.mixed) mixed.push_back(&light);
    if (mixed_lights) *mixed_lights = uint32_t(mixed.size());
    const size_t count = positions.size() / 3;
    std::vector<uint8_t> out(count * 4, 255);
    if (mixed.empty() || count == 0 || scene.meshes().empty()) return out;

    // Local frame at the centre of the probes' bounds (float rays keep their precision there).
    double origin[3];
    for (int k = 0; k < 3; ++k) {
        double lo = positions[size_t(k)], hi = lo;
        for (size_t i = 0; i < count; ++i) {
            lo = std::min(lo, double(positions[3 * i + size_t(k)]));
            hi = std::max(hi, double(positions[3 * i + size_t(k)]));
        }
        origin[k] = 0.5 * (lo + hi);
    }
    const RayCaster caster(scene, origin);
    run_jobs(count, settings.threads, [&](size_t i) {
        float probe[3];
        bool in_range = true;
        for (int k = 0; k < 3; ++k) {
            probe[k] = float(double(positions[3 * i + size_t(k)]) - origin[k]);
            in_range &= std::fabs(probe[k]) < kLargestRayCoordinate;
        }
        if (!in_range) return;  // beyond what Embree traces: left unshadowed
        for (size_t l = 0; l < mixed.size(); ++l) {
            const Light& light = *mixed[l];
            if (!light.shadows) continue;
            double to_light[3], distance = std::numeric_limits<double>::infinity();
            if (light.positional()) {
                double length = 0;
                for (int k = 0; k < 3; ++k) {
                    to_light[k] = light.position[size_t(k)] - origin[k] - probe[k];
                    length += to_light[k] * to_light[k];
                }
                distance = std::sqrt(length);
                if (!(distance > 0)) continue;  // a probe at the light sees it
                for (double& x : to_light) x /= distance;
            } else {
                for (int k = 0; k < 3; ++k) to_light[k] = -light.direction[size_t(k)];
            }
            const float direction[3] = {float(to_light[0]), float(to_light[1]), float(to_light[2])};
            if (light.positional() && !(distance < kLargestRayCoordinate)) continue;
            const float far = std::isinf(distance) ? std::numeric_limits<float>::infinity() : float(distance);
            if (caster.occluded(probe, direction, 0.0f, far, -1)) out[4 * i + l] = 0;
        }
    }, settings.progress, "occlusion");
    return out;
}

}  // namespace tetprobe
