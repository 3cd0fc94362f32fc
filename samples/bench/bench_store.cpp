// The store benchmark: query cost (coherent, cold, teleport, outside the hull) next to the blend-only
// floor, walk steps, bytes per probe and per cell, and build time next to TetGen's own call.
// Prints markdown tables; every time is the median of several repetitions.
#include "bench.h"

#include "bake/store_builder.h"
#include "core/half.h"
#include "core/store.h"
#include "core/store_data.h"
#include "core/store_format.h"

#include <tetgen.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kRepetitions = 5;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Median over kRepetitions runs of `run`, which returns its own elapsed seconds.
double median_seconds(const std::function<double()>& run, int repetitions = kRepetitions) {
    std::vector<double> times;
    for (int i = 0; i < repetitions; ++i) times.push_back(run());
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

std::string cpu_name() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

// Probes uniformly at random in the cube [0, 10]^3, with the 8 corners (so the hull is the cube).
std::vector<float> random_probes(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 10.0f);
    std::vector<float> p;
    for (int c = 0; c < 8; ++c) {
        p.push_back(c & 1 ? 10.0f : 0.0f);
        p.push_back(c & 2 ? 10.0f : 0.0f);
        p.push_back(c & 4 ? 10.0f : 0.0f);
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

std::unique_ptr<tetprobe::Store> build(const std::vector<float>& positions, const std::vector<float>& sh) {
    tetprobe::BuildSettings settings;
    const tetprobe::StoreData data = tetprobe::build_store_data(positions.data(), 12, sh.data(), 108,
                                                                positions.size() / 3, settings);
    const std::vector<uint8_t> blob = tetprobe::write_store_blob(data);
    return tetprobe::Store::load(blob.data(), blob.size());
}

// An object moving in small steps (step = 0.2% of the box per frame) and turning slowly, kept in [lo, hi]^3.
std::vector<float> coherent_path(size_t frames, float lo, float hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> turn(0.0f, 0.15f);
    std::vector<float> path;
    float p[3] = {0.5f * (lo + hi), 0.5f * (lo + hi), 0.5f * (lo + hi)}, v[3] = {1, 0.3f, -0.2f};
    const float step = 0.002f * 10.0f;
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
            path.push_back(p[k]);
        }
    }
    return path;
}

std::vector<float> random_points(size_t n, float lo, float hi, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    std::vector<float> p(3 * n);
    for (float& v : p) v = u(rng);
    return p;
}

// Points on a sphere shell around the cube (outside the hull), in path order when coherent.
std::vector<float> outside_points(size_t n, bool coherent, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g(0.0f, 1.0f);
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
        for (int k = 0; k < 3; ++k) p.push_back(5.0f + 12.0f * d[k] / len);
    }
    return p;
}

enum class HintMode { carried, none };

struct QueryStats {
    double ns = 0;
    double steps = 0;
    double fallbacks = 0;
};

// Times interpolate over the points (hint carried from the previous query, or none), then counts steps.
QueryStats time_queries(const tetprobe::Store& store, const std::vector<float>& points, HintMode mode) {
    const size_t n = points.size() / 3;
    volatile float sink = 0;
    QueryStats stats;
    stats.ns = 1e9 / double(n) * median_seconds([&] {
        float out[27];
        int32_t hint = -1;
        float acc = 0;
        const auto start = Clock::now();
        for (size_t i = 0; i < n; ++i) {
            if (mode == HintMode::none) hint = -1;
            store.interpolate(&points[3 * i], &hint, out);
            acc += out[0];
        }
        const double s = seconds_since(start);
        sink = sink + acc;
        return s;
    });
    int32_t hint = -1;
    for (size_t i = 0; i < n; ++i) {
        const tetprobe::Location loc = store.locate(&points[3 * i], mode == HintMode::none ? -1 : hint);
        hint = loc.cell;
        stats.steps += loc.steps;
        stats.fallbacks += loc.fallback ? 1 : 0;
    }
    stats.steps /= double(n);
    stats.fallbacks /= double(n);
    return stats;
}

// The blend-only floor: the same 4 x 27 half -> float blend for the same locations, with no search.
double time_blend_floor(const tetprobe::Store& store, const std::vector<float>& points) {
    const size_t n = points.size() / 3;
    const uint8_t* blob = store.blob_data();
    tetprobe::SectionEntry section;
    std::memcpy(&section, blob + sizeof(tetprobe::StoreHeader) + tetprobe::kSectionSh * sizeof(tetprobe::SectionEntry),
                sizeof section);
    const uint16_t* halves = reinterpret_cast<const uint16_t*>(blob + section.offset);
    std::vector<uint32_t> probes(4 * n);
    std::vector<float> weights(4 * n);
    int32_t hint = -1;
    for (size_t i = 0; i < n; ++i) {
        const tetprobe::Location loc = store.locate(&points[3 * i], hint);
        hint = loc.cell;
        std::copy(loc.probes, loc.probes + 4, &probes[4 * i]);
        std::copy(loc.weights, loc.weights + 4, &weights[4 * i]);
    }
    volatile float sink = 0;
    return 1e9 / double(n) * median_seconds([&] {
        float out[27];
        float acc = 0;
        const auto start = Clock::now();
        for (size_t i = 0; i < n; ++i) {
            const uint16_t* sh[4] = {halves + 27 * size_t(probes[4 * i]), halves + 27 * size_t(probes[4 * i + 1]),
                                     halves + 27 * size_t(probes[4 * i + 2]), halves + 27 * size_t(probes[4 * i + 3])};
            tetprobe::blend_sh_halves(sh, &weights[4 * i], out);
            acc += out[0];
        }
        const double s = seconds_since(start);
        sink = sink + acc;
        return s;
    });
}

// TetGen's own Delaunay call on the same points ("Qz": quiet, zero-based), for comparison with a full build.
double time_tetgen(const std::vector<float>& positions) {
    return median_seconds(
        [&] {
            tetgenio in, out;
            in.numberofpoints = int(positions.size() / 3);
            in.pointlist = new REAL[positions.size()];
            for (size_t i = 0; i < positions.size(); ++i) in.pointlist[i] = positions[i];
            const auto start = Clock::now();
            try {
                tetrahedralize(const_cast<char*>("Qz"), &in, &out);
            } catch (int) {
                return -1.0;
            }
            return seconds_since(start);
        },
        3);
}

double time_build(const std::vector<float>& positions, const std::vector<float>& sh) {
    return median_seconds(
        [&] {
            const auto start = Clock::now();
            auto store = build(positions, sh);
            return seconds_since(start);
        },
        3);
}

}  // namespace

int run_store_bench(int argc, char** argv) {
    std::string command;
    for (int i = 0; i < argc; ++i) command += (i ? " " : "") + std::string(argv[i]);
    std::printf("## Store benchmark\n\n");
    std::printf("machine: %s, %u hardware threads; half SIMD path (F16C/AVX2/FMA): %s; compiler: %s\n",
                cpu_name().c_str(), std::thread::hardware_concurrency(),
                tetprobe::half_simd_available() ? "yes" : "no", __VERSION__);
    std::printf("command: `%s`; every time is the median of %d runs (build: 3)\n\n", command.c_str(), kRepetitions);

    const size_t kQueries = 200000;
    std::printf("### Queries (single thread; interpolate = locate + blend; %zu coherent queries per run)\n\n", kQueries);
    std::printf("| probes | query | ns/query | steps/query | fallback fraction |\n");
    std::printf("| ---: | --- | ---: | ---: | ---: |\n");
    for (size_t n : {size_t(1500), size_t(10000), size_t(50000)}) {
        const std::vector<float> positions = random_probes(n, 7), sh = random_sh(n, 8);
        const auto store = build(positions, sh);
        const std::vector<float> coherent = coherent_path(kQueries, 0.5f, 9.5f, 11);
        const std::vector<float> scattered = random_points(kQueries / 4, 0.5f, 9.5f, 12);
        const std::vector<float> outside_coherent = outside_points(kQueries / 4, true, 13);
        const std::vector<float> outside_cold = outside_points(kQueries / 20, false, 14);
        const auto row = [&](const char* name, const QueryStats& q) {
            std::printf("| %zu | %s | %.1f | %.3f | %.1e |\n", n, name, q.ns, q.steps, q.fallbacks);
            std::fflush(stdout);
        };
        row("coherent (hint from last frame)", time_queries(*store, coherent, HintMode::carried));
        std::printf("| %zu | blend-only floor (same locations, no search) | %.1f | - | - |\n", n,
                    time_blend_floor(*store, coherent));
        row("cold (no hint)", time_queries(*store, scattered, HintMode::none));
        row("teleport (stale hint of a random place)", time_queries(*store, scattered, HintMode::carried));
        row("outside the hull, coherent", time_queries(*store, outside_coherent, HintMode::carried));
        row("outside the hull, cold", time_queries(*store, outside_cold, HintMode::none));
    }
    std::printf("\ncoherent: an object moving 0.2%% of the box per frame; cold and teleport: uniform random points "
                "inside the hull; outside: a shell at 1.2x the box's half-diagonal (outer cells); fallback: the walk cycled "
                "or hit its step cap and decided by the exhaustive search in double (over the outer cells alone "
                "beyond the hull).\n\n");

    std::printf("### Size and build time\n\n");
    std::printf("| probes | cells (inner + outer) | index bits | bytes | bytes/probe | bytes/cell | build ms | "
                "TetGen tetrahedralize(\"Qz\") ms |\n");
    std::printf("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (size_t n : {size_t(1500), size_t(10000), size_t(50000)}) {
        const std::vector<float> positions = random_probes(n, 21), sh = random_sh(n, 22);
        const auto store = build(positions, sh);
        const tetprobe::StoreHeader& h = store->header();
        const double build_ms = 1e3 * time_build(positions, sh);
        const double tetgen_ms = 1e3 * time_tetgen(positions);
        std::printf("| %zu | %u (%u + %u) | %d | %zu | %.1f | %.1f | %.1f | %.1f |\n", n, h.cell_count,
                    h.inner_cell_count, h.cell_count - h.inner_cell_count, (h.flags & tetprobe::kFlagIndex32) ? 32 : 16,
                    store->blob_size(), double(store->blob_size()) / h.probe_count,
                    double(store->blob_size()) / h.cell_count, build_ms, tetgen_ms);
        std::fflush(stdout);
    }
    std::printf("\nbuild: the library's whole build (screening, merging, TetGen, hull and outer cells, matrices, "
                "ordering, start grid, blob); TetGen: its Delaunay call alone on the same points.\n\n");
    return 0;
}
