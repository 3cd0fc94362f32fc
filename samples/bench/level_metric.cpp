#include "level_metric.h"

#include "method_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bench {

std::vector<float> luminance6(const float* sh, size_t count) {
    std::vector<float> out(6 * count);
    for (size_t i = 0; i < count; ++i)
        for (int n = 0; n < 6; ++n) out[6 * i + size_t(n)] = irradiance_luminance(sh + 27 * i, kAxisNormals[n]);
    return out;
}

void relative_error(const std::vector<float>& a, const std::vector<float>& b, double mean, double* rms, double* p95,
                    double* max) {
    if (a.size() != b.size() || a.empty()) throw std::invalid_argument("relative_error: arrays of different sizes");
    std::vector<double> errors(a.size());
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        errors[i] = std::fabs(double(a[i]) - double(b[i])) / mean;
        sum += errors[i] * errors[i];
    }
    *rms = std::sqrt(sum / double(errors.size()));
    // The 95th percentile: the smallest error at least 95% of the errors do not exceed.
    const size_t k = std::min(errors.size() - 1, size_t(std::ceil(0.95 * double(errors.size()))) - 1);
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(k), errors.end());
    *p95 = errors[k];
    if (max) *max = *std::max_element(errors.begin(), errors.end());
}

LevelError level_error(const Level& level, const std::vector<float>& sh_at_points, const std::vector<float>& sh_on_paths) {
    const size_t count = level.points.size() / 3;
    if (sh_at_points.size() != 27 * count) throw std::invalid_argument("level_error: 27 floats per evaluation point");
    LevelError e;
    relative_error(luminance6(sh_at_points.data(), count), luminance6(level.reference.data(), count), level.mean, &e.rms,
                   &e.p95, &e.max);
    if (!sh_on_paths.empty()) {
        const std::vector<float> path = luminance6(sh_on_paths.data(), sh_on_paths.size() / 27);
        size_t frame = 0;
        for (uint32_t frames : level.path_frames) {
            for (size_t f = frame + 1; f < frame + frames; ++f)
                for (size_t n = 0; n < 6; ++n)
                    e.worst_jump = std::max(e.worst_jump, std::fabs(double(path[6 * f + n]) - path[6 * (f - 1) + n]) / level.mean);
            frame += frames;
        }
    }
    return e;
}

}  // namespace bench
