#include "bake/placement_signal.h"

#include "bake/sampling.h"
#include "core/error.h"
#include "core/sh.h"

#include <array>

namespace tetprobe {

namespace {

// Each half's seed: the caller's seed mixed with the half's number, so halves never share samples.
uint64_t half_seed(uint64_t seed, int half) { return mix64(seed ^ (0x5eedull + uint64_t(half))); }

// Row n of the map from SH (27) to the luminance irradiance of normal n.
const std::array<std::array<double, 27>, kSignalSize>& luminance_rows() {
    static const std::array<std::array<double, 27>, kSignalSize> rows = [] {
        static const double normals[kSignalSize][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        static const double luminance[3] = {0.2126, 0.7152, 0.0722};
        std::array<std::array<double, 27>, kSignalSize> m{};
        for (int n = 0; n < kSignalSize; ++n) {
            double basis[9];
            sh_basis(normals[n][0], normals[n][1], normals[n][2], basis);
            for (int c = 0; c < 3; ++c)
                for (int k = 0; k < 9; ++k)
                    m[size_t(n)][size_t(9 * c + k)] = luminance[c] * sh_cosine_lobe_band(k == 0 ? 0 : k < 4 ? 1 : 2) * basis[k];
        }
        return m;
    }();
    return rows;
}

}  // namespace

void luminance6(const float sh[27], double out[kSignalSize]) {
    const auto& rows = luminance_rows();
    for (int n = 0; n < kSignalSize; ++n) {
        double sum = 0;
        for (int k = 0; k < 27; ++k) sum += rows[size_t(n)][size_t(k)] * double(sh[k]);
        out[n] = sum;
    }
}

PointSignal measure_signal(const Scene& scene, const std::vector<float>& positions, const BakeSettings& settings,
                           const Progress& progress) {
    if (settings.rays < 2) throw Error(Status::invalid_argument, "rays must be at least 2 (two half bakes measure the noise)");
    const size_t count = positions.size() / 3;
    PointSignal signal;
    signal.value.assign(kSignalSize * count, 0.0f);
    signal.noise.assign(count, 0.0f);
    std::vector<double> first;  // the first half's signal, until the second is baked
    for (int half = 0; half < 2; ++half) {
        BakeSettings bake = settings;
        bake.rays = half == 0 ? settings.rays / 2 : settings.rays - settings.rays / 2;
        bake.seed = half_seed(settings.seed, half);
        bake.progress = progress.part(0.5 * half, 0.5 * (half + 1));
        const std::vector<float> sh = bake_lighting(scene, positions, bake);
        if (half == 0) {
            first.resize(kSignalSize * count);
            for (size_t i = 0; i < count; ++i) luminance6(&sh[27 * i], &first[kSignalSize * i]);
            continue;
        }
        // Halves weigh by their rays; the variance of the weighted mean from the one difference.
        const double a = double(settings.rays / 2) / settings.rays, b = 1.0 - a;
        for (size_t i = 0; i < count; ++i) {
            double second[kSignalSize], squares = 0;
            luminance6(&sh[27 * i], second);
            for (int n = 0; n < kSignalSize; ++n) {
                const double x = first[kSignalSize * i + size_t(n)], y = second[n];
                signal.value[kSignalSize * i + size_t(n)] = float(a * x + b * y);
                squares += (x - y) * (x - y);
            }
            // Var(x - y) = Var(x) + Var(y) with Var(x) = v / a, Var(y) = v / b for a sample variance v of
            // the full ray count; Var(mean) = a^2 v / a + b^2 v / b = v, so Var(mean) = Var(x - y) a b.
            signal.noise[i] = float(squares * a * b);
        }
    }
    return signal;
}

}  // namespace tetprobe
