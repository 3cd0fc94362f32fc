// Batches: the same answers as one query at a time (SH bytes, weights, hints), on one thread or
// several, with hints, without, and chained; queries outside a store without extrapolation are
// reported by their first index and answered with zeros. Tagged [threads]: `make tsan` runs them.
#include "probe_families.h"

#include "bake/store_builder.h"
#include "core/store.h"
#include "core/store_data.h"

#include <catch2/catch.hpp>

#include <cstring>
#include <random>
#include <vector>

using namespace tetprobe;

namespace {

std::unique_ptr<Store> build(const std::vector<float>& positions, uint32_t flags = 0) {
    std::vector<float> sh(positions.size() / 3 * 27);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    for (float& v : sh) v = u(rng);
    BuildSettings settings;
    settings.flags = flags;
    const StoreData data = build_store_data(positions.data(), 12, sh.data(), 108, positions.size() / 3, settings);
    const std::vector<uint8_t> blob = write_store_blob(data);
    return Store::load(blob.data(), blob.size());
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

}  // namespace

// The serial answers: each query cold, or (chain) from the previous query's cell, restarting cold at
// every range start of a batch split `threads` ways, as the batch does.
void serial(const Store& store, const std::vector<float>& points, bool chain, size_t threads, std::vector<float>& sh,
            std::vector<int32_t>& cells) {
    const size_t n = points.size() / 3;
    sh.assign(n * 27, 0.0f);
    cells.assign(n, -1);
    int32_t hint = -1;
    size_t next_range = 0, range = 0;
    for (size_t i = 0; i < n; ++i) {
        if (i == next_range) {
            hint = -1;
            next_range = n * ++range / threads;
        }
        if (!chain) hint = -1;
        REQUIRE(store.interpolate(&points[3 * i], &hint, &sh[27 * i]) == Status::ok);
        cells[i] = hint;
    }
}

TEST_CASE("batches answer as single queries, on any number of threads, with or without hints", "[batch][threads]") {
    const auto store = build(families::random_cloud(600, 3).positions);
    const size_t n = 3 * 4096 + 17;  // enough for three threads of the batch
    const std::vector<float> points = path(n, 14.0f);  // inside the hull and beyond it
    std::vector<float> expected;
    std::vector<int32_t> expected_cells;
    for (uint32_t threads : {1u, 2u, 3u}) {
        BatchSettings settings;
        settings.threads = threads;
        serial(*store, points, false, threads, expected, expected_cells);
        std::vector<float> sh(n * 27, -1.0f);
        std::vector<int32_t> hints(n, -1);
        size_t first_outside = 0;
        REQUIRE(store->interpolate_batch(n, points.data(), 12, hints.data(), 4, sh.data(), 108, settings,
                                         &first_outside) == Status::ok);
        CHECK(first_outside == n);
        CHECK(std::memcmp(sh.data(), expected.data(), sh.size() * sizeof(float)) == 0);
        CHECK(hints == expected_cells);

        settings.chain_hints = true;
        serial(*store, points, true, threads, expected, expected_cells);
        std::vector<float> chained(n * 27, -1.0f);
        REQUIRE(store->interpolate_batch(n, points.data(), 12, nullptr, 4, chained.data(), 108, settings, nullptr) ==
                Status::ok);
        CHECK(std::memcmp(chained.data(), expected.data(), chained.size() * sizeof(float)) == 0);
    }
}

TEST_CASE("weights batches equal single locates, strided, on two threads", "[batch][threads]") {
    const auto store = build(families::random_cloud(400, 5).positions);
    const size_t n = 2 * 4096 + 3;
    const std::vector<float> points = path(n, 12.0f);
    struct Out {
        uint32_t probes[4];
        float pad;
        float weights[4];
    };
    std::vector<Out> out(n);
    BatchSettings settings;
    settings.threads = 2;
    REQUIRE(store->weights_batch(n, points.data(), 12, nullptr, 0, out[0].probes, sizeof(Out), out[0].weights,
                                 sizeof(Out), settings, nullptr) == Status::ok);
    for (size_t i = 0; i < n; ++i) {
        const Location loc = store->locate(&points[3 * i], -1);
        for (int k = 0; k < 4; ++k) {
            REQUIRE(out[i].probes[k] == loc.probes[k]);
            REQUIRE(out[i].weights[k] == loc.weights[k]);
        }
    }
}

TEST_CASE("a batch outside a store without extrapolation names its first query and answers zero", "[batch][threads]") {
    const auto store = build(families::random_cloud(200, 9).positions, kFlagNoExtrapolation);
    const size_t n = 2 * 4096;
    std::vector<float> points = path(n, 5.0f);  // inside the cloud's hull...
    const size_t first = 5000, second = 7000;    // ...but for these two, far out
    for (size_t i : {first, second}) points[3 * i] = 100.0f;
    std::vector<float> sh(n * 27, -1.0f);
    BatchSettings settings;
    settings.threads = 2;
    size_t first_outside = 0;
    CHECK(store->interpolate_batch(n, points.data(), 12, nullptr, 0, sh.data(), 108, settings, &first_outside) ==
          Status::outside);
    CHECK(first_outside == first);
    for (size_t i : {first, second})
        for (int c = 0; c < 27; ++c) CHECK(sh[27 * i + c] == 0.0f);
}
