// The rebuilt layout (core/store_rebuild.h): a blob without cells, neighbours or start grid loads into
// exactly the store the compact layout gives for the same build (with the rebuilt layout's coarser start
// grid): on every hard-case family, with and without extrapolation, float and quantised positions, the
// same cells and neighbours index for index and the same answers bit for bit (cell, probes, weights,
// walk steps from the start grid, blended SH).
// A blob whose probes do not tessellate into its header's counts, or whose header asks for more work
// than the layout allows, is refused; the builder refuses sets the loader would.
#include "hard_families.h"
#include "probe_families.h"

#include "bake/store_builder.h"
#include "core/cell_rebuild.h"
#include "core/error.h"
#include "core/start_grid.h"
#include "core/store.h"
#include "core/store_data.h"
#include "core/store_format.h"
#include "core/store_rebuild.h"

#include <catch2/catch.hpp>

#include <cstring>
#include <array>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace tetprobe;

namespace {

StoreData build(const families::ProbeSet& set, StoreLayout layout, uint32_t flags, bool quantize) {
    BuildSettings settings;
    settings.flags = flags;
    settings.layout = layout;
    settings.quantize_positions = quantize;
    settings.sh_encoding = kShUnorm8;
    std::vector<float> sh(set.count() * 27);
    std::mt19937 rng(uint32_t(set.count()));
    std::uniform_real_distribution<float> u(0.2f, 1.0f);
    for (size_t p = 0; p < set.count(); ++p)
        for (int c = 0; c < 27; ++c) sh[27 * p + size_t(c)] = c % 9 == 0 ? 1.0f + u(rng) : 0.3f * (u(rng) - 0.6f);
    return build_store_data(set.positions.data(), 12, sh.data(), 108, set.count(), settings);
}

std::unique_ptr<Store> load(const StoreData& d) {
    const std::vector<uint8_t> blob = write_store_blob(d);
    return Store::load(blob.data(), blob.size());
}

// Query points: every stored probe, and points spread over the bounds and beyond them.
std::vector<std::array<float, 3>> query_points(const Store& store) {
    const StoreHeader& h = store.header();
    std::vector<std::array<float, 3>> points;
    for (uint32_t j = 0; j < h.probe_count; ++j) {
        const float* p = store.probe_position(j);
        points.push_back({float(h.origin[0] + p[0]), float(h.origin[1] + p[1]), float(h.origin[2] + p[2])});
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.25, 1.25);
    for (int i = 0; i < 200; ++i) {
        std::array<float, 3> p;
        for (int k = 0; k < 3; ++k)
            p[size_t(k)] = float(h.origin[k] + h.bounds_min[k] + u(rng) * (double(h.bounds_max[k]) - h.bounds_min[k]));
        points.push_back(p);
    }
    return points;
}

// The rebuilt store is the compact one: header counts, every cell record, every answer bit for bit.
void require_same_store(const Store& compact, const Store& rebuilt, const StoreData& built) {
    const StoreHeader &a = compact.header(), &b = rebuilt.header();
    REQUIRE(a.layout == kLayoutCompact);
    REQUIRE(b.layout == kLayoutRebuilt);
    REQUIRE(b.cell_count == a.cell_count);
    REQUIRE(b.inner_cell_count == a.inner_cell_count);
    REQUIRE(std::memcmp(a.grid, b.grid, sizeof a.grid) == 0);
    REQUIRE(rebuilt.blob_size() < compact.blob_size());
    for (uint32_t c = 0; c < a.cell_count; ++c) {
        uint32_t va[4], na[4], vb[4], nb[4];
        compact.cell(c, va, na);
        rebuilt.cell(c, vb, nb);
        INFO("cell " << c);
        REQUIRE(std::memcmp(va, vb, sizeof va) == 0);
        REQUIRE(std::memcmp(na, nb, sizeof na) == 0);
        REQUIRE(std::memcmp(vb, &built.cell_vertices[4 * size_t(c)], sizeof vb) == 0);
        REQUIRE(std::memcmp(nb, &built.cell_neighbours[4 * size_t(c)], sizeof nb) == 0);
    }
    int32_t hint_a = -1, hint_b = -1;
    for (const auto& p : query_points(compact)) {
        // Without a hint (the walk starts from the start grid: equal steps mean equal grid cells), then
        // chained from the previous answer.
        for (const bool hinted : {false, true}) {
            const Location la = compact.locate(p.data(), hinted ? hint_a : -1);
            const Location lb = rebuilt.locate(p.data(), hinted ? hint_b : -1);
            REQUIRE(la.status == lb.status);
            REQUIRE(la.cell == lb.cell);
            REQUIRE(la.steps == lb.steps);
            REQUIRE(la.fallback == lb.fallback);
            REQUIRE(std::memcmp(la.probes, lb.probes, sizeof la.probes) == 0);
            REQUIRE(std::memcmp(la.weights, lb.weights, sizeof la.weights) == 0);
        }
        float sa[27], sb[27];
        const Status sta = compact.interpolate(p.data(), &hint_a, sa, nullptr);
        const Status stb = rebuilt.interpolate(p.data(), &hint_b, sb, nullptr);
        REQUIRE(sta == stb);
        if (sta == Status::ok) REQUIRE(std::memcmp(sa, sb, sizeof sa) == 0);
    }
}

// The compact store with the rebuilt layout's start grid, which is coarser (start_grid.h): the builder
// chose its dimensions at one entry per kRebuiltStartGridCellsPerEntry inner cells.
StoreData with_grid_of(StoreData compact, const StoreData& rebuilt) {
    uint32_t expected[3], stored[3];
    start_grid_dimensions(rebuilt.bounds_min, rebuilt.bounds_max, rebuilt.inner_cell_count,
                          kRebuiltStartGridCellsPerEntry, expected);
    start_grid_dimensions(compact.bounds_min, compact.bounds_max, compact.inner_cell_count,
                          kStoredStartGridCellsPerEntry, stored);
    REQUIRE(std::memcmp(rebuilt.grid, expected, sizeof expected) == 0);
    REQUIRE(std::memcmp(compact.grid, stored, sizeof stored) == 0);
    std::copy(rebuilt.grid, rebuilt.grid + 3, compact.grid);
    fill_start_grid(compact);
    return compact;
}

std::vector<uint8_t> with_word(std::vector<uint8_t> blob, size_t offset, uint32_t value) {
    std::memcpy(blob.data() + offset, &value, 4);
    const uint64_t sum = store_checksum(blob.data(), blob.size());
    std::memcpy(blob.data() + kChecksumOffset, &sum, sizeof sum);
    return blob;
}

Status try_load(const std::vector<uint8_t>& blob, std::string* message) {
    try {
        Store::load(blob.data(), blob.size());
        return Status::ok;
    } catch (const Error& e) {
        *message = e.what();
        return e.status();
    }
}

}  // namespace

TEST_CASE("store rebuild: every hard-case family loads into the compact store's cells and answers, bit for bit",
          "[store_rebuild]") {
    for (const families::ProbeSet& set : families::hard_families()) {
        for (const uint32_t flags : {0u, uint32_t(kFlagNoExtrapolation)}) {
            for (const bool quantize : {false, true}) {
                INFO(set.name << (flags ? ", no extrapolation" : "") << (quantize ? ", quantised" : ""));
                const StoreData compact = build(set, kLayoutCompact, flags, quantize);
                const StoreData rebuilt = build(set, kLayoutRebuilt, flags, quantize);
                REQUIRE(rebuilt.positions == compact.positions);
                const StoreData regridded = with_grid_of(compact, rebuilt);
                require_same_store(*load(regridded), *load(rebuilt), regridded);
            }
        }
    }
}

TEST_CASE("store rebuild: 11,000 probes (32-bit indices) load into the compact store", "[store_rebuild]") {
    const families::ProbeSet set = families::random_cloud(11000, 18);
    const StoreData compact = build(set, kLayoutCompact, 0, true);
    REQUIRE(compact.cell_count() > 65535);
    const StoreData rebuilt = build(set, kLayoutRebuilt, 0, true);
    const StoreData regridded = with_grid_of(compact, rebuilt);
    // One entry per 8 inner cells instead of 4: about half the entries.
    const double entries = double(rebuilt.grid[0]) * rebuilt.grid[1] * rebuilt.grid[2];
    REQUIRE(entries < 0.6 * double(compact.grid[0]) * compact.grid[1] * compact.grid[2]);
    require_same_store(*load(regridded), *load(rebuilt), regridded);
}

TEST_CASE("store rebuild: a blob whose probes do not make its header's cells is refused, naming why",
          "[store_rebuild]") {
    const StoreData d = build(families::random_cloud(60, 3), kLayoutRebuilt, 0, false);
    const std::vector<uint8_t> blob = write_store_blob(d);
    std::string message;
    REQUIRE(try_load(blob, &message) == Status::ok);
    // One more or one fewer inner cell than the probes make.
    for (const int delta : {-1, 1}) {
        std::vector<uint8_t> forged = with_word(blob, offsetof(StoreHeader, inner_cell_count), d.inner_cell_count + delta);
        forged = with_word(forged, offsetof(StoreHeader, cell_count), d.cell_count() + delta);
        REQUIRE(try_load(forged, &message) == Status::invalid_blob);
        CHECK(message.find("its probes tessellate into " + std::to_string(d.inner_cell_count) + " inner") != std::string::npos);
    }
    // Without extrapolation the probes make no outer cells, which the header has.
    REQUIRE(try_load(with_word(blob, offsetof(StoreHeader, flags), d.flags | kFlagNoExtrapolation), &message) ==
            Status::invalid_blob);
    // Two probes at one point cannot be tessellated (two probes inside the bounds, which stay as they are).
    auto inside = [&](uint32_t j) {
        for (int k = 0; k < 3; ++k) {
            const float x = d.positions[3 * size_t(j) + size_t(k)];
            if (x == d.bounds_min[k] || x == d.bounds_max[k]) return false;
        }
        return true;
    };
    uint32_t first = 0;
    while (!inside(first)) ++first;
    uint32_t second = first + 1;
    while (!inside(second)) ++second;
    std::vector<uint8_t> twins = blob;
    SectionEntry positions;
    std::memcpy(&positions, blob.data() + sizeof(StoreHeader) + kSectionPositions * sizeof(SectionEntry), sizeof positions);
    std::memcpy(twins.data() + positions.offset + 12 * second, twins.data() + positions.offset + 12 * first, 12);
    REQUIRE(try_load(with_word(twins, offsetof(StoreHeader, reserved), 0), &message) == Status::invalid_blob);
    CHECK(message.find("cannot be tessellated again") != std::string::npos);
}

TEST_CASE("store rebuild: the header bounds the rebuild's work; the builder refuses sets beyond it", "[store_rebuild]") {
    const StoreData d = build(families::random_cloud(60, 3), kLayoutRebuilt, 0, false);
    const std::vector<uint8_t> blob = write_store_blob(d);
    std::string message;
    const uint32_t too_many = uint32_t(kMaxRebuiltCellsPerProbe * d.probe_count() + kRebuiltCellSlack + 1);
    REQUIRE(try_load(with_word(blob, offsetof(StoreHeader, cell_count), too_many), &message) == Status::invalid_blob);
    CHECK(message.find("exceeds the rebuilt layout's 16 cells a probe") != std::string::npos);
    for (const uint32_t side : {uint32_t(kMaxStartGridCells) + 1, 2049u}) {
        std::vector<uint8_t> forged = with_word(blob, offsetof(StoreHeader, grid), side);
        forged = with_word(forged, offsetof(StoreHeader, grid) + 4, 2048);
        REQUIRE(try_load(forged, &message) == Status::invalid_blob);
        CHECK(message.find("start grid has more than") != std::string::npos);
    }
    // Within that limit, a grid beyond the builder's finest dimensions for the bounds and cells (those of the
    // stored layouts) would make a few bytes cost millions of walks: refused too; one more entry along an axis
    // (another platform's rounding) is not, nor the finest grid itself (this layout's blobs of earlier builders).
    uint32_t finest[3];
    start_grid_dimensions(d.bounds_min, d.bounds_max, d.inner_cell_count, kStoredStartGridCellsPerEntry, finest);
    REQUIRE(uint64_t(finest[0]) * finest[1] * finest[2] > uint64_t(d.grid[0]) * d.grid[1] * d.grid[2]);
    {
        std::vector<uint8_t> forged = with_word(blob, offsetof(StoreHeader, grid), 1024);
        forged = with_word(forged, offsetof(StoreHeader, grid) + 4, 1024);
        forged = with_word(forged, offsetof(StoreHeader, grid) + 8, 4);
        REQUIRE(try_load(forged, &message) == Status::invalid_blob);
        CHECK(message.find("is larger than the builder's finest " + std::to_string(finest[0]) + " x " +
                           std::to_string(finest[1]) + " x " + std::to_string(finest[2])) != std::string::npos);
        REQUIRE(try_load(with_word(blob, offsetof(StoreHeader, grid) + 4, finest[1] + 1), &message) == Status::ok);
        std::vector<uint8_t> earlier = blob;
        for (int a = 0; a < 3; ++a) earlier = with_word(earlier, offsetof(StoreHeader, grid) + 4 * size_t(a), finest[a]);
        REQUIRE(try_load(earlier, &message) == Status::ok);
        const StoreData compact = build(families::random_cloud(60, 3), kLayoutCompact, 0, false);
        REQUIRE(std::memcmp(compact.grid, finest, sizeof finest) == 0);
        require_same_store(*load(compact), *Store::load(earlier.data(), earlier.size()), compact);
    }
    // Probes on two skew lines: a Delaunay tessellation of n^2 / 4 cells, over 16 a probe at 80 probes.
    families::ProbeSet skew{"two skew lines", {}};
    for (int i = 0; i < 40; ++i) skew.add(i, 0, 0), skew.add(0, i + 0.5, 10);
    const StoreData compact = build(skew, kLayoutCompact, 0, false);
    REQUIRE(compact.cell_count() > kMaxRebuiltCellsPerProbe * compact.probe_count() + kRebuiltCellSlack);
    try {
        build(skew, kLayoutRebuilt, 0, false);
        FAIL("built");
    } catch (const Error& e) {
        CHECK(e.status() == Status::invalid_argument);
        CHECK(std::string(e.what()).find("build it with the compact layout") != std::string::npos);
    }
    // Forged as the rebuilt layout with the compact store's counts: refused before any rebuilding.
    StoreData forged = compact;
    forged.layout = kLayoutRebuilt;
    REQUIRE(try_load(write_store_blob(forged), &message) == Status::invalid_blob);
    CHECK(message.find("cells a probe") != std::string::npos);
}

TEST_CASE("store rebuild: the tessellation stops at its cell budget", "[store_rebuild]") {
    const families::ProbeSet set = families::random_cloud(500, 4);
    const StoreData d = build(set, kLayoutCompact, 0, false);
    // The loader's budget for the header's count rebuilds; a budget below the cells the probes make stops.
    REQUIRE(rebuild_cells(d.positions.data(), d.probe_count(), d.dimension, d.axis, true, d.bounds_min, d.bounds_max,
                          d.grid, rebuilt_cell_budget(d.cell_count()))
                .cell_vertices == d.cell_vertices);
    REQUIRE_THROWS_AS(rebuild_cells(d.positions.data(), d.probe_count(), d.dimension, d.axis, true, d.bounds_min,
                                    d.bounds_max, d.grid, d.cell_count() / 2),
                      Error);
}
