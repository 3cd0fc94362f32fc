#include "method_scene.h"

#include "bake/ray_caster.h"
#include "bake/scene_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>

namespace bench {

const float kAxisNormals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const float kUp[3] = {0, 1, 0};

MethodSettings method_settings(bool quick) {
    MethodSettings s;
    if (quick) {
        s.quick = true;
        s.rays = 32;
        s.bounces = 1;
        s.queries = 150;
        s.frames = 40;
        s.slice_size = 8;
    }
    return s;
}

namespace {

// Query points are redrawn closer than this to a point or spot light: the 1/d^2 peak there would
// dominate every method's error alike.
constexpr float kLightClearance = 0.5f;

void check(tp_status status, const char* what) {
    if (status != TP_OK) throw std::runtime_error(std::string(what) + ": " + tp_last_error());
}

// A closed Lissajous loop through the query box, 0.9 of its half-extent from the centre on each axis,
// with phases (0, phase_y, phase_z).
std::vector<float> lissajous_path(const float lo[3], const float hi[3], size_t frames, double phase_y, double phase_z) {
    const double frequency[3] = {1, 2, 3}, phase[3] = {0, phase_y, phase_z};
    std::vector<float> path;
    for (size_t f = 0; f < frames; ++f) {
        const double t = 6.283185307179586 * double(f) / double(frames);
        for (int k = 0; k < 3; ++k)
            path.push_back(float(0.5 * (lo[k] + hi[k]) + 0.45 * (hi[k] - lo[k]) * std::sin(frequency[k] * t + phase[k])));
    }
    return path;
}

// Where an object can be: not inside a wall or a closed block. Judged by 14 rays (axes and diagonals):
// enclosed when at least half of them first hit the back of a triangle (the sample scenes' surfaces face
// the space an object can be in).
class FreeSpace {
public:
    FreeSpace(const std::string& path, const std::vector<float>& probes)
        : scene_(tetprobe::load_scene_file(path)), caster_(scene_, origin_of(probes, origin_)) {}

    bool free(const float p[3]) const {
        float local[3];
        for (int k = 0; k < 3; ++k) local[k] = float(p[k] - origin_[k]);
        int back = 0;
        for (int i = 0; i < 14; ++i) {
            float d[3];
            if (i < 6) {
                for (int k = 0; k < 3; ++k) d[k] = kAxisNormals[i][k];
            } else {
                for (int k = 0; k < 3; ++k) d[k] = ((i - 6) >> k & 1 ? 1.0f : -1.0f) * 0.57735027f;
            }
            tetprobe::RayHit hit;
            if (!caster_.intersect(local, d, 0.0f, INFINITY, &hit)) continue;
            const tetprobe::Mesh& mesh = scene_.meshes()[hit.mesh];
            const float* a = &mesh.vertices[3 * mesh.indices[3 * hit.triangle]];
            const float* b = &mesh.vertices[3 * mesh.indices[3 * hit.triangle + 1]];
            const float* c = &mesh.vertices[3 * mesh.indices[3 * hit.triangle + 2]];
            const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            back += n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0;
        }
        return back < 7;
    }

    // True when the straight move from a to b crosses no surface.
    bool clear(const float a[3], const float b[3]) const {
        float local[3], direction[3], length = 0;
        for (int k = 0; k < 3; ++k) local[k] = float(a[k] - origin_[k]), direction[k] = b[k] - a[k], length += direction[k] * direction[k];
        length = std::sqrt(length);
        if (!(length > 0)) return true;
        for (float& c : direction) c /= length;
        return !caster_.occluded(local, direction, 0.0f, length, -1);
    }

private:
    static const double* origin_of(const std::vector<float>& probes, double origin[3]) {
        for (int k = 0; k < 3; ++k) origin[k] = 0;
        for (size_t i = 0; i < probes.size(); ++i) origin[i % 3] += probes[i] / double(probes.size() / 3);
        return origin;
    }

    double origin_[3];
    tetprobe::Scene scene_;
    tetprobe::RayCaster caster_;
};

// The first loop of a fixed sequence of phases that stays in free space and crosses no surface (an object
// walks through the door, not the wall); if none does, the one with the fewest bad frames.
std::vector<float> free_path(const FreeSpace& space, const float lo[3], const float hi[3], size_t frames,
                             size_t* out_bad_frames) {
    std::vector<float> best;
    size_t best_bad = SIZE_MAX;
    for (int i = 0; i < 64 && best_bad > 0; ++i) {
        std::vector<float> path = lissajous_path(lo, hi, frames, 0.5 + 0.785398 * (i % 8), 1.0 + 0.785398 * (i / 8));
        size_t bad = 0;
        for (size_t f = 0; f < frames; ++f)
            bad += !space.free(&path[3 * f]) || !space.clear(&path[3 * f], &path[3 * ((f + 1) % frames)]);
        if (bad < best_bad) best_bad = bad, best = std::move(path);
    }
    *out_bad_frames = best_bad;
    return best;
}

}  // namespace

float irradiance_luminance(const float sh[27], const float n[3]) {
    float rgb[3];
    tp_sh_eval_irradiance(sh, n, rgb);
    return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
}

std::vector<float> bake_at(const tp_scene* scene, const std::vector<float>& positions, const MethodSettings& settings,
                           uint64_t seed) {
    tp_bake_options options;
    tp_bake_options_init(&options);
    options.rays = settings.rays;
    options.bounces = settings.bounces;
    options.seed = seed;
    std::vector<float> sh(positions.size() / 3 * 27);
    if (!sh.empty()) check(tp_bake(scene, positions.data(), 0, positions.size() / 3, &options, sh.data(), 0), "tp_bake");
    return sh;
}

MethodScene::~MethodScene() { tp_scene_release(scene); }

void prepare_method_scene(const std::string& path, const MethodSettings& settings, bool with_slice, MethodScene* out) {
    MethodScene& s = *out;
    s.file = path;
    // The name, and the positions of point and spot lights (queries keep clear of their 1/d^2 peak).
    std::vector<float> light_positions;
    {
        std::ifstream in(path);
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        s.name = j.is_object() && j.contains("name") && j["name"].is_string() ? j["name"].get<std::string>() : path;
        if (j.is_object() && j.contains("lights") && j["lights"].is_array())
            for (const nlohmann::json& light : j["lights"])
                if (light.is_object() && light.contains("position") && light["position"].is_array() &&
                    light["position"].size() == 3)
                    for (const nlohmann::json& c : light["position"])
                        if (c.is_number()) light_positions.push_back(c.get<float>());
    }
    check(tp_scene_load_file(path.c_str(), &s.scene), "tp_scene_load_file");
    const float* listed;
    size_t listed_count;
    check(tp_scene_probes(s.scene, &listed, &listed_count), "tp_scene_probes");
    s.probe_source = "scene file";
    s.probes.assign(listed, listed + 3 * listed_count);
    if (listed_count == 0) {
        // No probes in the file: a uniform 6 x 3 x 6 lattice over the middle 80% of the meshes' bounds.
        const tetprobe::Scene scene = tetprobe::load_scene_file(path);
        if (scene.meshes().empty()) throw std::runtime_error(path + ": no probes and no meshes to place them in");
        float lo[3], hi[3];
        for (int k = 0; k < 3; ++k) lo[k] = INFINITY, hi[k] = -INFINITY;
        for (const tetprobe::Mesh& mesh : scene.meshes())
            for (int k = 0; k < 3; ++k)
                lo[k] = std::min(lo[k], mesh.bounds_min[k]), hi[k] = std::max(hi[k], mesh.bounds_max[k]);
        const int counts[3] = {6, 3, 6};
        for (int z = 0; z < counts[2]; ++z)
            for (int y = 0; y < counts[1]; ++y)
                for (int x = 0; x < counts[0]; ++x) {
                    const int i[3] = {x, y, z};
                    for (int k = 0; k < 3; ++k)
                        s.probes.push_back(lo[k] + (hi[k] - lo[k]) * (0.1f + 0.8f * float(i[k]) / float(counts[k] - 1)));
                }
        listed_count = s.probes.size() / 3;
        s.probe_source = "uniform";
    }
    for (int k = 0; k < 3; ++k) s.probe_min[k] = s.probe_max[k] = s.probes[k];
    for (size_t p = 0; p < listed_count; ++p)
        for (int k = 0; k < 3; ++k)
            s.probe_min[k] = std::min(s.probe_min[k], s.probes[3 * p + k]),
            s.probe_max[k] = std::max(s.probe_max[k], s.probes[3 * p + k]);
    double diagonal = 0;
    for (int k = 0; k < 3; ++k) diagonal += double(s.probe_max[k] - s.probe_min[k]) * (s.probe_max[k] - s.probe_min[k]);
    diagonal = std::sqrt(diagonal);
    for (int k = 0; k < 3; ++k) {
        // A flat probe layer (the race track) is queried half a unit above and below it.
        const bool thin = s.probe_max[k] - s.probe_min[k] < 0.01 * diagonal;
        s.query_min[k] = thin ? s.probe_min[k] - 0.5f : s.probe_min[k];
        s.query_max[k] = thin ? s.probe_max[k] + 0.5f : s.probe_max[k];
    }

    const FreeSpace space(path, s.probes);
    std::mt19937 rng(2024);
    s.queries.resize(3 * settings.queries);
    for (size_t i = 0; i < settings.queries; ++i) {
        float* q = &s.queries[3 * i];
        bool rejected = true;
        while (rejected) {
            for (int k = 0; k < 3; ++k) q[k] = std::uniform_real_distribution<float>(s.query_min[k], s.query_max[k])(rng);
            rejected = !space.free(q);
            for (size_t l = 0; l + 3 <= light_positions.size(); l += 3) {
                float d2 = 0;
                for (int k = 0; k < 3; ++k) d2 += (q[k] - light_positions[l + k]) * (q[k] - light_positions[l + k]);
                rejected |= d2 < kLightClearance * kLightClearance;
            }
        }
    }
    s.path = free_path(space, s.query_min, s.query_max, settings.frames, &s.path_bad_frames);

    s.probe_sh = bake_at(s.scene, s.probes, settings, settings.seed);
    s.reference = bake_at(s.scene, s.queries, settings, settings.seed);
    s.second_reference = bake_at(s.scene, s.queries, settings, settings.seed + 1000);
    // Each path point alone (probe index 0 of its own bake): every frame draws the same rays, so the
    // reference's own frame-to-frame jumps are the light's, not sampling noise.
    s.path_reference.resize(27 * settings.frames);
    for (size_t f = 0; f < settings.frames; ++f) {
        const std::vector<float> one(&s.path[3 * f], &s.path[3 * f + 3]);
        const std::vector<float> sh = bake_at(s.scene, one, settings, settings.seed);
        std::copy(sh.begin(), sh.end(), &s.path_reference[27 * f]);
    }

    double sum = 0;
    for (size_t i = 0; i < settings.queries; ++i)
        for (const auto& n : kAxisNormals) sum += irradiance_luminance(&s.reference[27 * i], n);
    s.mean_irradiance = sum / double(6 * settings.queries);
    if (!(s.mean_irradiance > 0)) throw std::runtime_error(path + ": the reference irradiance is not positive");

    if (with_slice) {
        double height = 0;
        for (size_t p = 0; p < listed_count; ++p) height += s.probes[3 * p + 1];
        s.slice_height = float(height / double(listed_count));
        s.slice_x[0] = s.probe_min[0], s.slice_x[1] = s.probe_max[0];
        s.slice_z[0] = s.probe_min[2], s.slice_z[1] = s.probe_max[2];
        const int n = settings.slice_size;
        for (int row = 0; row < n; ++row)
            for (int column = 0; column < n; ++column) {
                s.slice_points.push_back(s.slice_x[0] + (s.slice_x[1] - s.slice_x[0]) * (float(column) + 0.5f) / float(n));
                s.slice_points.push_back(s.slice_height);
                s.slice_points.push_back(s.slice_z[0] + (s.slice_z[1] - s.slice_z[0]) * (float(row) + 0.5f) / float(n));
            }
        s.slice_reference = bake_at(s.scene, s.slice_points, settings, settings.seed);
    }
}

}  // namespace bench

namespace bench {

MethodArgs parse_method_args(int argc, char** argv, const std::vector<std::string>& default_scenes) {
    MethodArgs args;
    for (int i = 2; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--quick")) args.quick = true;
        else if (!std::strcmp(argv[i], "--out") && i + 1 < argc) args.out = argv[++i];
        else if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) args.scenes.push_back(argv[++i]);
    }
    if (args.scenes.empty())
        for (const std::string& name : default_scenes)
            if (std::ifstream(name)) args.scenes.push_back(name);
    return args;
}

}  // namespace bench

namespace bench {

size_t repetitions_for(const std::function<void()>& one_pass, double target_seconds, size_t max_repetitions) {
    const auto start = std::chrono::steady_clock::now();
    one_pass();
    const double pass = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double wanted = pass > 0 ? target_seconds / pass : double(max_repetitions);
    return std::max<size_t>(1, std::min<size_t>(max_repetitions, size_t(wanted)));
}

}  // namespace bench
