#include "level_peers.h"

#include "brick_grid.h"
#include "knn_peer.h"

#include "bake/inside_test.h"
#include "bake/ray_caster.h"

#include <chrono>
#include <cstdio>
#include <memory>

namespace bench {

namespace {

// 1 per position that is not inside geometry (bake/inside_test.h, the test the playable space uses).
std::vector<uint8_t> valid_flags(const Level& level, const std::vector<float>& positions, uint32_t threads) {
    std::vector<uint8_t> valid(positions.size() / 3, 1);
    for (uint32_t i : tetprobe::find_inside_probes(level.scene, positions, threads)) valid[i] = 0;
    return valid;
}

}  // namespace

LevelResult evaluate_grid(const Level& level, size_t budget_bytes, GridEncoding encoding, const LevelSettings& settings,
                          uint32_t threads) {
    LevelResult r;
    r.method = encoding == GridEncoding::half ? "grid_half" : "grid_apv8";
    r.layout = grid_encoding_id(encoding);
    r.label = encoding == GridEncoding::half ? "uniform grid, dilated, half SH" : "uniform grid, dilated, APV 8-bit L2";
    int dims[3];
    DilatedGrid::dims_for_budget(level.playable_lo, level.playable_hi, budget_bytes, encoding, dims);
    DilatedGrid grid(level.playable_lo, level.playable_hi, dims, encoding);
    const std::vector<float> positions = grid.positions();
    auto start = std::chrono::steady_clock::now();
    const std::vector<uint8_t> valid = valid_flags(level, positions, threads);
    std::vector<float> kept;
    for (size_t i = 0; i < valid.size(); ++i)
        if (valid[i]) kept.insert(kept.end(), &positions[3 * i], &positions[3 * i] + 3);
    r.placement_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const std::vector<float> baked = bake_probes(level, kept, settings);
    r.bake_seconds = seconds_since(start);
    std::vector<float> sh(27 * valid.size(), 0.0f);
    for (size_t i = 0, j = 0; i < valid.size(); ++i)
        if (valid[i]) std::copy(&baked[27 * j], &baked[27 * j] + 27, &sh[27 * i]), ++j;
    start = std::chrono::steady_clock::now();
    grid.set_sh(sh, valid);
    r.build_seconds = seconds_since(start);
    r.probes = grid.probe_count();
    r.bytes = grid.bytes();
    r.resident_bytes = grid.resident_bytes();
    r.note = std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + ", " +
             std::to_string(valid.size() - kept.size() / 3) + " inside geometry (dilated in " +
             std::to_string(grid.dilation_passes()) + " passes)";
    measure_method(level, [] {}, [&](const float* p, float* out) { grid.interpolate(p, out); }, &r);
    return r;
}

LevelResult evaluate_bricks(const Level& level, size_t budget_bytes, const LevelSettings& settings, uint32_t threads) {
    LevelResult r;
    r.method = "bricks_apv8";
    r.layout = "apv8";
    r.label = "adaptive brick grid (Volumetric Lightmap), APV 8-bit L2";
    double lo[3], hi[3];
    tetprobe::scene_bounds(level.scene, lo, hi);
    const double origin[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    const tetprobe::RayCaster caster(level.scene, origin);
    double bake_seconds = 0, valid_seconds = 0;
    BrickBuildHooks hooks;
    hooks.mean_irradiance = level.mean;
    hooks.bake = [&](const std::vector<float>& p) {
        const auto start = std::chrono::steady_clock::now();
        std::vector<float> sh = bake_probes(level, p, settings);
        bake_seconds += seconds_since(start);
        return sh;
    };
    hooks.valid = [&](const std::vector<float>& p) {
        const auto start = std::chrono::steady_clock::now();
        std::vector<uint8_t> v = valid_flags(level, p, threads);
        valid_seconds += seconds_since(start);
        return v;
    };
    hooks.near_surface = [&](const float point[3], float radius) {
        const float local[3] = {float(point[0] - origin[0]), float(point[1] - origin[1]), float(point[2] - origin[2])};
        tetprobe::SurfacePoint nearest;
        return caster.nearest_surface(local, radius, &nearest);
    };
    const auto start = std::chrono::steady_clock::now();
    const BrickGrid grid(level.playable_lo, level.playable_hi, budget_bytes, hooks);
    r.build_seconds = seconds_since(start) - bake_seconds - valid_seconds;
    r.bake_seconds = bake_seconds;
    r.placement_seconds = valid_seconds;
    r.probes = grid.samples_baked();
    r.bytes = grid.bytes();
    r.resident_bytes = grid.resident_bytes();
    r.note = grid.summary();
    measure_method(level, [] {}, [&](const float* p, float* out) { grid.interpolate(p, out); }, &r);
    return r;
}

LevelResult evaluate_knn(const Level& level, const std::vector<float>& positions, const std::vector<float>& sh, bool damped) {
    LevelResult r;
    r.method = damped ? "knn4_damped" : "knn4";
    r.layout = "half";
    r.label = damped ? "4 nearest, inverse distance, damped" : "4 nearest, inverse distance";
    const auto start = std::chrono::steady_clock::now();
    const KnnPeer knn(positions, sh, level.playable_lo, level.playable_hi);
    r.build_seconds = seconds_since(start);
    r.probes = positions.size() / 3;
    r.bytes = knn.bytes() + (damped ? 27 * sizeof(float) : 0);  // plus one object's damping state
    r.resident_bytes = r.bytes;
    char note[96];
    std::snprintf(note, sizeof note, "%.1f candidates a cell", knn.mean_candidates());
    r.note = note;
    if (damped) {
        r.note += "; damping time constant 6 frames; at the evaluation points a still object (no damping)";
        TemporalDamping damping(kLevelDampingFrames);
        measure_method(level, [&] { damping.reset(); }, [&](const float* p, float* out) {
            float raw[27];
            knn.interpolate(p, raw);
            damping.update(raw, out);
        }, &r);
    } else {
        measure_method(level, [] {}, [&](const float* p, float* out) { knn.interpolate(p, out); }, &r);
    }
    return r;
}

}  // namespace bench
