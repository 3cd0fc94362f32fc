#include "query_sets.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace bench {

std::vector<float> random_probes(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, kBox);
    std::vector<float> p;
    for (int c = 0; c < 8; ++c) {
        p.push_back(c & 1 ? kBox : 0.0f);
        p.push_back(c & 2 ? kBox : 0.0f);
        p.push_back(c & 4 ? kBox : 0.0f);
    }
    while (p.size() < 3 * n) p.push_back(u(rng));
    return p;
}

std::vector<float> random_sh(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<float> sh(27 * n);
    for (float& v : sh) v = u(rng);
    return sh;
}

std::vector<float> random_points(size_t n, float lo, float hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    std::vector<float> p(3 * n);
    for (float& v : p) v = u(rng);
    return p;
}

std::vector<float> outside_points(size_t n, bool coherent, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g(0.0f, 1.0f);
    const float centre = 0.5f * kBox, radius = 1.2f * 0.5f * kBox * std::sqrt(3.0f);
    std::vector<float> p;
    for (size_t i = 0; i < n; ++i) {
        float d[3];
        if (coherent) {
            const double t = 6.283185307 * 4.0 * double(i) / double(n);
            d[0] = float(std::cos(t)), d[1] = float(0.3 * std::sin(3.0 * t)), d[2] = float(std::sin(t));
        } else {
            d[0] = g(rng), d[1] = g(rng), d[2] = g(rng);
        }
        const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int k = 0; k < 3; ++k) p.push_back(centre + radius * d[k] / len);
    }
    return p;
}

ObjectPaths moving_objects(size_t objects, size_t frames, float lo, float hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> start(lo, hi);
    std::normal_distribution<float> turn(0.0f, 0.15f);
    ObjectPaths paths;
    paths.objects = objects;
    paths.frames = frames;
    paths.by_object.resize(3 * objects * frames);
    paths.by_frame.resize(3 * objects * frames);
    const float step = 0.002f * kBox;
    for (size_t o = 0; o < objects; ++o) {
        float p[3] = {start(rng), start(rng), start(rng)};
        float v[3] = {turn(rng), turn(rng), turn(rng) + 0.1f};
        for (size_t f = 0; f < frames; ++f) {
            for (float& c : v) c += turn(rng);
            const float n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            for (int k = 0; k < 3; ++k) {
                v[k] /= n;
                p[k] += step * v[k];
                if (p[k] < lo || p[k] > hi) {
                    v[k] = -v[k];
                    p[k] = std::min(std::max(p[k], lo), hi);
                }
                paths.by_object[3 * (o * frames + f) + k] = p[k];
                paths.by_frame[3 * (f * objects + o) + k] = p[k];
            }
        }
    }
    return paths;
}

}  // namespace bench
