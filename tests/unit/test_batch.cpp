// Batches: the same answers as one query at a time (SH bytes, weights, hints), bit for bit, on stores
// of every family and layout, with the AVX2 kernels and the portable ones, with hints, without and
// chained; an engine's split of a frame (batch calls on disjoint ranges from its own threads) gives
// the same bytes as one call; queries outside a store without extrapolation are reported by their
// first index and answered with zeros. Tagged [threads]: `make tsan` runs them.
#include "probe_families.h"

#include "bake/store_builder.h"
#include "core/store.h"
#include "core/store_data.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

using namespace tetprobe;

namespace {

struct Encoding {
    StoreLayout layout = kLayoutFast;
    ShEncoding sh = kShHalf;
    bool quantize_positions = false;
};

std::vector<uint8_t> build_blob(const std::vector<float>& positions, uint32_t flags = 0, Encoding encoding = {}) {
    std::vector<float> sh(positions.size() / 3 * 27);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = i % 9 ? u(rng) : 2 + u(rng);  // L0 positive: radiance
    BuildSettings settings;
    settings.flags = flags;
    settings.layout = encoding.layout;
    settings.sh_encoding = encoding.sh;
    settings.quantize_positions = encoding.quantize_positions;
    const StoreData data = build_store_data(positions.data(), 12, sh.data(), 108, positions.size() / 3, settings);
    return write_store_blob(data);
}

std::unique_ptr<Store> build(const std::vector<float>& positions, uint32_t flags = 0) {
    const std::vector<uint8_t> blob = build_blob(positions, flags);
    return Store::load(blob.data(), blob.size());
}

// The blob loaded with the portable kernels (TP_NO_AVX2 is read once, at load).
std::unique_ptr<Store> load_portable(const std::vector<uint8_t>& blob) {
    setenv("TP_NO_AVX2", "1", 1);
    std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
    unsetenv("TP_NO_AVX2");
    return store;
}

// The blob loaded with a batch kernel ("lanes" or "loop", TP_BATCH_KERNEL, read at load), AVX2 or portable.
std::unique_ptr<Store> load_with(const std::vector<uint8_t>& blob, const char* batch_kernel, bool portable) {
    setenv("TP_BATCH_KERNEL", batch_kernel, 1);
    std::unique_ptr<Store> store = portable ? load_portable(blob) : Store::load(blob.data(), blob.size());
    unsetenv("TP_BATCH_KERNEL");
    return store;
}

// An object path through the box and beyond it: coherent steps, so hints matter.
std::vector<float> path(size_t count, float reach) {
    std::vector<float> p;
    for (size_t i = 0; i < count; ++i) {
        const double s = double(i) / double(count);
        p.push_back(float(reach * std::sin(17 * s)));
        p.push_back(float(reach * std::cos(11 * s)));
        p.push_back(float(reach * std::sin(5 * s + 1)));
    }
    return p;
}

// Queries that make the filter uncertain and the walk long: a path through the set's box and beyond,
// every probe itself, midpoints of probe pairs (on edges and facets of lattices) and random points.
std::vector<float> hard_queries(const std::vector<float>& positions, size_t count) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < positions.size(); ++i) lo[i % 3] = std::min(lo[i % 3], positions[i]), hi[i % 3] = std::max(hi[i % 3], positions[i]);
    std::vector<float> q;
    for (size_t i = 0; i < count; ++i) {
        const double s = double(i) / double(count);
        const double t[3] = {std::sin(17 * s), std::cos(11 * s), std::sin(5 * s + 1)};
        for (int k = 0; k < 3; ++k) q.push_back(float(0.5 * (lo[k] + hi[k]) + 0.7 * (hi[k] - lo[k] + 1) * t[k]));
    }
    const size_t n = positions.size() / 3;
    std::mt19937 rng(11);
    std::uniform_int_distribution<size_t> pick(0, n - 1);
    for (size_t i = 0; i < n; ++i) q.insert(q.end(), &positions[3 * i], &positions[3 * i] + 3);
    for (size_t i = 0; i < 2 * n; ++i) {
        const size_t a = pick(rng), b = pick(rng);
        for (int k = 0; k < 3; ++k) q.push_back(float(0.5 * (double(positions[3 * a + k]) + positions[3 * b + k])));
    }
    return q;
}

struct Answers {
    std::vector<float> sh;
    std::vector<int32_t> cells;
    std::vector<uint32_t> probes;
    std::vector<float> weights;
    std::vector<Status> status;
};

// One query at a time: each from hints[i] (or, chained, from the previous query's cell).
Answers singles(const Store& store, const std::vector<float>& points, const std::vector<int32_t>& hints, bool chain) {
    const size_t n = points.size() / 3;
    Answers a{std::vector<float>(27 * n), std::vector<int32_t>(n), std::vector<uint32_t>(4 * n),
              std::vector<float>(4 * n), std::vector<Status>(n)};
    int32_t chained = -1;
    for (size_t i = 0; i < n; ++i) {
        int32_t hint = chain ? chained : hints[i];
        const Location loc = store.locate(&points[3 * i], hint);
        // With occlusion asked for, the query goes through Location and answer_sh; without, through the
        // kernel's fused locate + blend (on a store without leak control): the same bits.
        int32_t general_hint = hint;
        float general[27], occlusion[4];
        const Status general_status = store.interpolate(&points[3 * i], &general_hint, general, occlusion);
        a.status[i] = store.interpolate(&points[3 * i], &hint, &a.sh[27 * i]);
        REQUIRE(a.status[i] == loc.status);
        REQUIRE(hint == loc.cell);
        REQUIRE(general_status == loc.status);
        REQUIRE(general_hint == loc.cell);
        REQUIRE(std::memcmp(general, &a.sh[27 * i], sizeof general) == 0);
        a.cells[i] = chained = hint;
        for (int k = 0; k < 4; ++k) {
            a.probes[4 * i + k] = loc.status == Status::ok ? loc.probes[k] : 0;
            a.weights[4 * i + k] = loc.status == Status::ok ? loc.weights[k] : 0.0f;
        }
    }
    return a;
}

// The same through the batches (interpolate and weights): hints updated in place, or chained.
Answers batch(const Store& store, const std::vector<float>& points, const std::vector<int32_t>& hints, bool chain) {
    const size_t n = points.size() / 3;
    Answers a{std::vector<float>(27 * n, -1.0f), hints, std::vector<uint32_t>(4 * n), std::vector<float>(4 * n), {}};
    BatchSettings settings;
    settings.chain_hints = chain;
    size_t first = 0;
    store.interpolate_batch(n, points.data(), 12, chain ? nullptr : a.cells.data(), 4, a.sh.data(), 108, settings, &first);
    std::vector<int32_t> again = hints;
    store.weights_batch(n, points.data(), 12, chain ? nullptr : again.data(), 4, a.probes.data(), 16, a.weights.data(),
                        16, settings, &first);
    if (!chain) REQUIRE(again == a.cells);
    return a;
}

void require_same(const Answers& batch, const Answers& single, bool compare_cells) {
    REQUIRE(batch.sh.size() == single.sh.size());
    CHECK(std::memcmp(batch.sh.data(), single.sh.data(), batch.sh.size() * sizeof(float)) == 0);
    CHECK(std::memcmp(batch.weights.data(), single.weights.data(), batch.weights.size() * sizeof(float)) == 0);
    CHECK(batch.probes == single.probes);
    if (compare_cells) CHECK(batch.cells == single.cells);
}

}  // namespace

TEST_CASE("batches answer as single queries bit for bit, on every kind of store and both instruction sets", "[batch]") {
    struct Case {
        families::ProbeSet set;
        uint32_t flags;
        Encoding encoding;
    };
    const std::vector<Case> cases = {
        {families::random_cloud(600, 3), 0, {}},
        {families::random_cloud(300, 4), 0, {kLayoutCompact, kShHalf, false}},
        {families::random_cloud(300, 4), 0, {kLayoutFast, kShUnorm8, false}},
        {families::random_cloud(300, 4), 0, {kLayoutFast, kShHalfL1, true}},
        {families::random_cloud(300, 4), 0, {kLayoutCompact, kShUnorm8L1, true}},
        {families::lattice(5, 4, 4), 0, {kLayoutCompact, kShUnorm8, true}},
        {families::random_cloud(300, 5), kFlagIndex32, {}},
        {families::random_cloud(200, 6), kFlagNoExtrapolation, {}},
        {families::lattice(6, 5, 4), 0, {}},
        {families::lattice(5, 5, 5, 1, 2e-7, 3), 0, {}},
        {families::rotated_lattice(5, 2), 0, {}},
        {families::slab(8, 0.01), 0, {}},
        {families::dense_room_in_a_level(1), 0, {}},
        {families::plane(60, 4), 0, {}},
        {families::line(20), 0, {}},
    };
    for (const Case& c : cases) {
        INFO(c.set.name << " flags " << c.flags << " layout " << c.encoding.layout << " SH encoding " << c.encoding.sh
                        << " quantised " << c.encoding.quantize_positions);
        const std::vector<uint8_t> blob = build_blob(c.set.positions, c.flags, c.encoding);
        const auto chosen = Store::load(blob.data(), blob.size());
        const auto portable = load_portable(blob);
        const std::vector<float> points = hard_queries(c.set.positions, 1500);
        const size_t n = points.size() / 3;
        const std::vector<int32_t> cold(n, -1);
        const Answers expected = singles(*chosen, points, cold, false);
        require_same(singles(*portable, points, cold, false), expected, true);
        std::vector<int32_t> warm = expected.cells;
        std::rotate(warm.begin(), warm.begin() + 7, warm.end());  // hints from other queries: longer walks
        const Answers from_hints = singles(*chosen, points, warm, false);
        const Answers chained = singles(*chosen, points, cold, true);
        // Both batch kernels (eight lanes in structure of arrays, and the loop), each on both instruction sets.
        for (const char* kernel : {"lanes", "loop"})
            for (bool portable_kernels : {false, true}) {
                INFO("batch kernel " << kernel << (portable_kernels ? ", portable" : ", AVX2 where there"));
                const auto store = load_with(blob, kernel, portable_kernels);
                // Cold, then from the cells found (the next frame's hints), then chained.
                require_same(batch(*store, points, cold, false), expected, true);
                require_same(batch(*store, points, warm, false), from_hints, true);
                require_same(batch(*store, points, cold, true), chained, false);
            }
    }
}

TEST_CASE("batches of every size up to past two lane refills answer as single queries", "[batch]") {
    // Fewer queries than lanes, exactly as many, and lanes that run dry at different times.
    const std::vector<float> positions = families::random_cloud(400, 8).positions;
    const std::vector<uint8_t> blob = build_blob(positions);
    const std::vector<float> points = path(40, 9.0f);  // inside the hull and beyond it
    for (const char* kernel : {"lanes", "loop"})
        for (bool portable : {false, true}) {
            INFO("batch kernel " << kernel << (portable ? ", portable" : ", AVX2 where there"));
            const auto store = load_with(blob, kernel, portable);
            for (size_t count = 1; count <= 40; ++count) {
                INFO(count << " queries");
                const std::vector<float> some(points.begin(), points.begin() + 3 * count);
                std::vector<int32_t> hints(count);
                for (size_t i = 0; i < count; ++i) hints[i] = i % 4 == 3 ? -1 : int32_t((i * 37) % store->header().cell_count);
                require_same(batch(*store, some, hints, false), singles(*store, some, hints, false), true);
            }
        }
}

TEST_CASE("a frame split into ranges on the caller's threads answers as one batch call", "[batch][threads]") {
    const auto store = build(families::random_cloud(600, 3).positions);
    const size_t n = 3 * 1024 + 17;
    const std::vector<float> points = path(n, 14.0f);  // inside the hull and beyond it
    std::vector<float> whole(n * 27);
    std::vector<int32_t> whole_hints(n, -1);
    REQUIRE(store->interpolate_batch(n, points.data(), 12, whole_hints.data(), 4, whole.data(), 108, BatchSettings{},
                                     nullptr) == Status::ok);
    for (size_t workers : {2u, 3u}) {
        std::vector<float> split(n * 27, -1.0f);
        std::vector<int32_t> hints(n, -1);
        std::vector<std::thread> threads;
        for (size_t w = 0; w < workers; ++w)
            threads.emplace_back([&, w] {
                const size_t begin = n * w / workers, end = n * (w + 1) / workers;
                store->interpolate_batch(end - begin, &points[3 * begin], 12, &hints[begin], 4, &split[27 * begin], 108,
                                         BatchSettings{}, nullptr);
            });
        for (std::thread& t : threads) t.join();
        CHECK(std::memcmp(split.data(), whole.data(), split.size() * sizeof(float)) == 0);
        CHECK(hints == whole_hints);
    }
}

TEST_CASE("weights batches equal single locates, strided", "[batch]") {
    const auto store = build(families::random_cloud(400, 5).positions);
    const size_t n = 2 * 4096 + 3;
    const std::vector<float> points = path(n, 12.0f);
    struct Out {
        uint32_t probes[4];
        float pad;
        float weights[4];
    };
    std::vector<Out> out(n);
    REQUIRE(store->weights_batch(n, points.data(), 12, nullptr, 0, out[0].probes, sizeof(Out), out[0].weights,
                                 sizeof(Out), BatchSettings{}, nullptr) == Status::ok);
    for (size_t i = 0; i < n; ++i) {
        const Location loc = store->locate(&points[3 * i], -1);
        for (int k = 0; k < 4; ++k) {
            REQUIRE(out[i].probes[k] == loc.probes[k]);
            REQUIRE(out[i].weights[k] == loc.weights[k]);
        }
    }
}

TEST_CASE("a batch outside a store without extrapolation names its first query and answers zero", "[batch]") {
    const auto store = build(families::random_cloud(200, 9).positions, kFlagNoExtrapolation);
    const size_t n = 2 * 4096;
    std::vector<float> points = path(n, 5.0f);  // inside the cloud's hull...
    const size_t first = 5000, second = 7000;    // ...but for these two, far out
    for (size_t i : {first, second}) points[3 * i] = 100.0f;
    std::vector<float> sh(n * 27, -1.0f);
    size_t first_outside = 0;
    CHECK(store->interpolate_batch(n, points.data(), 12, nullptr, 0, sh.data(), 108, BatchSettings{}, &first_outside) ==
          Status::outside);
    CHECK(first_outside == first);
    for (size_t i : {first, second})
        for (int c = 0; c < 27; ++c) CHECK(sh[27 * i + c] == 0.0f);
}
