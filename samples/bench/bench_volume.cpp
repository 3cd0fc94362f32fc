// The probe-volume row of the store benchmark (see bench_volume.h).
#include "bench_volume.h"

#include "bench_timing.h"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace bench {

namespace {

constexpr size_t kVolumeObjects = 16;  // volumes per frame
constexpr size_t kVolumeFrames = 8;    // frames timed (after an untimed first one)
constexpr float kLow = 0.05f * kBox, kHigh = 0.95f * kBox;  // the objects' range (bench_store.cpp)
constexpr float kHalf = 0.5f * kVolumeCell * (kVolumeSide - 1);

// Point (0, 0, 0) of the volume of object o at frame f: the object's position, pulled in so that its volume stays
// within the objects' range (inside the probes' box: what a proxy volume covers in a level; beyond the hull see
// the "outside" rows).
void volume_origin(const ObjectPaths& paths, size_t o, size_t f, float origin[3]) {
    const float* at = paths.at(o, f);
    for (int a = 0; a < 3; ++a) origin[a] = std::min(std::max(at[a], kLow + kHalf), kHigh - kHalf) - kHalf;
}

}  // namespace

double time_volume_points(const tp_store* store, const ObjectPaths& paths, float* sink) {
    const size_t objects = std::min(kVolumeObjects, paths.objects), frames = std::min(kVolumeFrames + 1, paths.frames);
    if (objects == 0 || frames < 2) return 0;
    const uint32_t dims[3] = {kVolumeSide, kVolumeSide, kVolumeSide};
    const size_t points = size_t(kVolumeSide) * kVolumeSide * kVolumeSide;
    std::vector<float> out(27 * points);
    const float cell[3] = {kVolumeCell, kVolumeCell, kVolumeCell};
    auto run_frame = [&](size_t f, std::vector<int32_t>& hints) {
        for (size_t o = 0; o < objects; ++o) {
            float origin[3];
            volume_origin(paths, o, f, origin);
            if (tp_store_sample_volume(store, origin, cell, dims, &hints[o], nullptr, out.data()) != TP_OK)
                std::fprintf(stderr, "tp_store_sample_volume: %s\n", tp_last_error());
            *sink += out[27 * (o % points)];
        }
    };
    const double seconds = median_seconds([&] {
        std::vector<int32_t> hints(objects, -1);
        run_frame(0, hints);  // untimed: each volume's first hint
        const Clock::time_point t0 = Clock::now();
        for (size_t f = 1; f < frames; ++f) run_frame(f, hints);
        return seconds_since(t0);
    });
    return 1e9 * seconds / double(objects * (frames - 1) * points);
}

double volume_steps_per_point(const tp_store* store, const ObjectPaths& paths) {
    const size_t objects = std::min(kVolumeObjects, paths.objects);
    double steps = 0, points = 0;
    for (size_t o = 0; o < objects; ++o) {
        float origin[3];
        volume_origin(paths, o, 1, origin);
        int32_t hint = -1;
        uint32_t row = 0;
        for (uint32_t z = 0; z < kVolumeSide; ++z)  // the walk of tp_store_sample_volume (capi/tetprobe.h)
            for (uint32_t j = 0; j < kVolumeSide; ++j, ++row) {
                const uint32_t y = z % 2 ? kVolumeSide - 1 - j : j;
                for (uint32_t i = 0; i < kVolumeSide; ++i) {
                    const uint32_t x = row % 2 ? kVolumeSide - 1 - i : i;
                    const uint32_t index[3] = {x, y, z};
                    float p[3];
                    for (int a = 0; a < 3; ++a) p[a] = float(double(origin[a]) + double(index[a]) * double(kVolumeCell));
                    tp_location loc{};
                    loc.struct_size = sizeof loc;
                    tp_store_locate(store, p, &hint, &loc);
                    if (row == 0 && i == 0) continue;  // the cold start of each volume
                    steps += loc.steps;
                    points += 1;
                }
            }
    }
    return points > 0 ? steps / points : 0;
}

}  // namespace bench
