// The store blob: writer and validating loader. Round trips are byte-identical, a committed golden
// blob pins format version 1, and no truncation or single-byte change gets past the loader unsafely.
//
// The golden file tests/unit/golden/tiny_store_v1.bin is written once, on purpose, by
//   tetprobe_tests "[.write-golden]"
// and committed; the tests below only read it.
#include "hand_built_stores.h"

#include "core/error.h"
#include "core/store.h"
#include "core/store_data.h"
#include "core/store_format.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace tetprobe;

namespace {

// Debug and sanitizer builds try fewer byte changes so that each case stays within seconds.
#if defined(__SANITIZE_ADDRESS__) || !defined(NDEBUG)
const std::vector<uint8_t> kFlips = {0x01, 0xFF};
#else
const std::vector<uint8_t> kFlips = {0x01, 0x02, 0x10, 0x80, 0xFF, 0x7F};
#endif

const char* const kGoldenPath = TP_SOURCE_DIR "/tests/unit/golden/tiny_store_v1.bin";

// A fixed store whose every value is a literal: a tetrahedron without extrapolation, five input
// probes of which one was merged, a non-zero origin.
StoreData golden_store_data() {
    StoreData d;
    d.flags = kFlagNoExtrapolation;
    d.dimension = 3;
    d.origin[0] = 10.0;
    d.origin[1] = -20.0;
    d.origin[2] = 30.5;
    d.input_probe_count = 5;
    d.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    d.normals.assign(12, 0.0f);
    for (int i = 0; i < 4 * 27; ++i) d.sh.push_back(float(i % 23) * 0.25f - 2.0f);
    d.probe_source = {0, 1, 2, 4};
    d.input_remap = {0, 1, 2, 1, 3};
    d.inner_cell_count = 1;
    d.cell_vertices = {0, 1, 2, 3};
    d.cell_neighbours = {kNone32, kNone32, kNone32, kNone32};
    d.inner_matrices = {-1, -1, -1, 1, 1, 0, 0, 0, 0, 1, 0, 0};
    d.grid[0] = d.grid[1] = d.grid[2] = 1;
    d.grid_cells = {0};
    for (int k = 0; k < 3; ++k) {
        d.bounds_min[k] = 0.0f;
        d.bounds_max[k] = 1.0f;
    }
    return d;
}

std::vector<uint8_t> read_bytes(const char* path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void repair_checksum(std::vector<uint8_t>& blob) {
    if (blob.size() < kHeaderSize) return;
    const uint64_t sum = store_checksum(blob.data(), blob.size());
    std::memcpy(blob.data() + kChecksumOffset, &sum, sizeof sum);
}

SectionEntry section(const std::vector<uint8_t>& blob, Section id) {
    SectionEntry e;
    std::memcpy(&e, blob.data() + sizeof(StoreHeader) + id * sizeof(SectionEntry), sizeof e);
    return e;
}

// Loads, returning the status (TP_OK when it loaded) and the message.
tp_status try_load(const std::vector<uint8_t>& blob, std::unique_ptr<Store>* out = nullptr, std::string* message = nullptr) {
    try {
        std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
        if (out) *out = std::move(store);
        return TP_OK;
    } catch (const Error& e) {
        if (message) *message = e.what();
        return e.status();
    }
}

// Queries a store that loaded from corrupted bytes: they must end, stay in bounds, and give finite
// weights and SH when they succeed.
void query_safely(const Store& store) {
    const StoreHeader& h = store.header();
    const float fractions[][3] = {{0.5f, 0.5f, 0.5f}, {-1, 2, 0.25f}, {3, -2, 7}, {0, 0, 0}, {1e6f, -1e6f, 1e6f}};
    int32_t hint = -1;
    for (const auto& f : fractions) {
        float p[3];
        for (int k = 0; k < 3; ++k) p[k] = float(h.origin[k] + h.bounds_min[k] + f[k] * (h.bounds_max[k] - h.bounds_min[k]));
        const Location loc = store.locate(p, hint);
        if (loc.status == TP_OK) {
            float sum = 0;
            for (int k = 0; k < 4; ++k) {
                REQUIRE(std::isfinite(loc.weights[k]));
                REQUIRE(loc.probes[k] < h.probe_count);
                sum += loc.weights[k];
            }
            REQUIRE(std::fabs(sum - 1.0f) < 1e-4f);
        }
        float sh[27];
        if (store.interpolate(p, &hint, sh) == TP_OK)
            for (float x : sh) REQUIRE(std::isfinite(x));
        hint = int32_t(h.cell_count) - 1;
    }
}

std::vector<std::vector<uint8_t>> sample_blobs() {
    std::vector<std::vector<uint8_t>> blobs;
    const std::array<hand_built::Vec, 4> corners = {hand_built::Vec(0, 0, 0), hand_built::Vec(1, 0, 0),
                                                    hand_built::Vec(0, 1, 0), hand_built::Vec(0, 0, 1)};
    StoreData tet = hand_built::tetrahedron_store(corners, true);
    blobs.push_back(write_store_blob(tet));
    tet.flags |= kFlagIndex32;
    blobs.push_back(write_store_blob(tet));
    blobs.push_back(write_store_blob(hand_built::line_store({0, 1, 3}, true)));
    blobs.push_back(write_store_blob(golden_store_data()));
    return blobs;
}

}  // namespace

TEST_CASE("write the golden blob (run on purpose only)", "[.write-golden]") {
    const std::vector<uint8_t> blob = write_store_blob(golden_store_data());
    std::ofstream out(kGoldenPath, std::ios::binary);
    out.write(reinterpret_cast<const char*>(blob.data()), std::streamsize(blob.size()));
    REQUIRE(out.good());
}

TEST_CASE("the writer reproduces the committed golden blob byte for byte", "[store_blob]") {
    const std::vector<uint8_t> golden = read_bytes(kGoldenPath);
    REQUIRE(!golden.empty());
    const std::vector<uint8_t> blob = write_store_blob(golden_store_data());
    REQUIRE(blob.size() == golden.size());
    REQUIRE(std::memcmp(blob.data(), golden.data(), blob.size()) == 0);
}

TEST_CASE("the golden blob loads and answers as its data says", "[store_blob]") {
    const std::vector<uint8_t> golden = read_bytes(kGoldenPath);
    std::unique_ptr<Store> store = Store::load(golden.data(), golden.size());
    const StoreHeader& h = store->header();
    CHECK(h.format_version == 1);
    CHECK(h.probe_count == 4);
    CHECK(h.input_probe_count == 5);
    CHECK((h.flags & kFlagIndex32) == 0);
    CHECK(store->input_to_stored(3) == 1);
    CHECK(store->probe_source(3) == 4);
    // At world (10.1, -19.8, 30.8) the local point is (0.1, 0.2, 0.3): weights 0.4, 0.1, 0.2, 0.3.
    const float p[3] = {10.1f, -19.8f, 30.8f};
    const Location loc = store->locate(p, -1);
    REQUIRE(loc.status == TP_OK);
    const float expected[4] = {0.4f, 0.1f, 0.2f, 0.3f};
    for (int k = 0; k < 4; ++k) {
        CHECK(loc.probes[k] == uint32_t(k));
        CHECK(loc.weights[k] == Approx(expected[k]).margin(1e-5));
    }
    float sh[27], probe[27];
    store->probe_sh(2, probe);
    for (int i = 0; i < 27; ++i) CHECK(probe[i] == float((2 * 27 + i) % 23) * 0.25f - 2.0f);
    const float far[3] = {12, -18, 33};
    int32_t hint = -1;
    CHECK(store->interpolate(far, &hint, sh) == TP_ERROR_OUTSIDE);
}

TEST_CASE("write -> load -> blob is byte-identical", "[store_blob]") {
    for (const std::vector<uint8_t>& blob : sample_blobs()) {
        std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
        REQUIRE(store->blob_size() == blob.size());
        REQUIRE(std::memcmp(store->blob_data(), blob.data(), blob.size()) == 0);
        REQUIRE(reinterpret_cast<uintptr_t>(store->blob_data()) % kSectionAlignment == 0);
    }
}

TEST_CASE("layout: aligned sections, zero padding, 16-bit reserved values", "[store_blob]") {
    const std::vector<uint8_t> blob = write_store_blob(hand_built::tetrahedron_store(
        {hand_built::Vec(0, 0, 0), hand_built::Vec(1, 0, 0), hand_built::Vec(0, 1, 0), hand_built::Vec(0, 0, 1)}, true));
    uint64_t end = kHeaderSize;
    for (uint32_t s = 0; s < kSectionCount; ++s) {
        const SectionEntry e = section(blob, Section(s));
        REQUIRE(e.offset % 16 == 0);
        REQUIRE(e.offset >= end);
        for (uint64_t i = end; i < e.offset; ++i) REQUIRE(blob[i] == 0);
        end = e.offset + e.size;
    }
    REQUIRE(end == blob.size());
    // Outer cell 1: vertices {1, 2, 3, outer}; the inner cell's slot above... none in 3D, so check
    // the outer marker and, in the neighbours, an outer cell's inner neighbour.
    const SectionEntry vertices = section(blob, kSectionCellVertices);
    REQUIRE(vertices.size == 5 * 4 * 2);
    uint16_t v[4];
    std::memcpy(v, blob.data() + vertices.offset + 4 * 2, sizeof v);
    CHECK(v[3] == kOuter16);
    const std::vector<uint8_t> line = write_store_blob(hand_built::line_store({0, 1}, false));
    const SectionEntry line_vertices = section(line, kSectionCellVertices);
    std::memcpy(v, line.data() + line_vertices.offset, sizeof v);
    CHECK(v[0] == 0);
    CHECK(v[1] == 1);
    CHECK(v[2] == kNone16);
    CHECK(v[3] == kNone16);
}

TEST_CASE("every truncated prefix and any trailing byte is rejected", "[store_blob]") {
    for (const std::vector<uint8_t>& blob : sample_blobs()) {
        for (size_t cut = 0; cut < blob.size(); ++cut) {
            const std::vector<uint8_t> prefix(blob.begin(), blob.begin() + cut);
            REQUIRE(try_load(prefix) == TP_ERROR_INVALID_BLOB);
        }
        std::vector<uint8_t> longer = blob;
        longer.push_back(0);
        REQUIRE(try_load(longer) == TP_ERROR_INVALID_BLOB);
        repair_checksum(longer);
        std::string message;
        REQUIRE(try_load(longer, nullptr, &message) == TP_ERROR_INVALID_BLOB);
        CHECK(message.find("trailing") != std::string::npos);
    }
}

TEST_CASE("every single-byte change is rejected by the checksum", "[store_blob]") {
    for (const std::vector<uint8_t>& original : sample_blobs()) {
        std::vector<uint8_t> blob = original;
        for (size_t i = 0; i < blob.size(); ++i) {
            for (uint8_t flip : {0x01, 0x80, 0xFF}) {
                blob[i] ^= flip;
                const tp_status status = try_load(blob);
                // A changed version byte is reported as such; everything else is an invalid blob.
                REQUIRE((status == TP_ERROR_INVALID_BLOB || status == TP_ERROR_VERSION));
                blob[i] ^= flip;
            }
        }
    }
}

TEST_CASE("every single-byte change with a repaired checksum is rejected or loads safely", "[store_blob]") {
    size_t loaded = 0, rejected = 0;
    for (const std::vector<uint8_t>& original : sample_blobs()) {
        for (size_t i = 0; i < original.size(); ++i) {
            for (uint8_t flip : kFlips) {
                std::vector<uint8_t> blob = original;
                blob[i] ^= flip;
                repair_checksum(blob);
                std::unique_ptr<Store> store;
                const tp_status status = try_load(blob, &store);
                if (status == TP_OK) {
                    ++loaded;
                    query_safely(*store);
                } else {
                    ++rejected;
                    REQUIRE((status == TP_ERROR_INVALID_BLOB || status == TP_ERROR_VERSION));
                }
            }
        }
    }
    INFO("loaded " << loaded << ", rejected " << rejected);
    CHECK(rejected > loaded / 4);
}

TEST_CASE("the loader names what is wrong", "[store_blob]") {
    const std::vector<uint8_t> original = write_store_blob(hand_built::tetrahedron_store(
        {hand_built::Vec(0, 0, 0), hand_built::Vec(1, 0, 0), hand_built::Vec(0, 1, 0), hand_built::Vec(0, 0, 1)}, true));
    auto expect = [&](std::vector<uint8_t> blob, tp_status status, const char* words) {
        repair_checksum(blob);
        std::string message;
        REQUIRE(try_load(blob, nullptr, &message) == status);
        INFO(message);
        CHECK(message.find(words) != std::string::npos);
    };
    {
        std::vector<uint8_t> blob = original;
        const uint32_t version = 2;
        std::memcpy(blob.data() + offsetof(StoreHeader, format_version), &version, 4);
        expect(blob, TP_ERROR_VERSION, "version 2");
    }
    {
        std::vector<uint8_t> blob = original;
        blob[0] = 'X';
        expect(blob, TP_ERROR_INVALID_BLOB, "magic");
    }
    {
        std::vector<uint8_t> blob = original;
        const uint16_t bad = 4;  // probe_count is 4
        std::memcpy(blob.data() + section(blob, kSectionCellVertices).offset + 2, &bad, 2);
        expect(blob, TP_ERROR_INVALID_BLOB, "cell_vertices[1]");
    }
    {
        std::vector<uint8_t> blob = original;
        const uint16_t bad = 3;  // outer cell 1's inner neighbour (slot 3) must be inner cell 0
        std::memcpy(blob.data() + section(blob, kSectionCellNeighbours).offset + 2 * (4 + 3), &bad, 2);
        expect(blob, TP_ERROR_INVALID_BLOB, "cell_neighbours[7]");
    }
    {
        std::vector<uint8_t> blob = original;
        const float nan = std::nanf("");
        std::memcpy(blob.data() + section(blob, kSectionPositions).offset + 4 * 5, &nan, 4);
        expect(blob, TP_ERROR_INVALID_BLOB, "positions[5]");
    }
    {
        std::vector<uint8_t> blob = original;
        const uint16_t inf_half = 0x7C00;
        std::memcpy(blob.data() + section(blob, kSectionSh).offset + 2 * 30, &inf_half, 2);
        expect(blob, TP_ERROR_INVALID_BLOB, "sh[30]");
    }
    {
        std::vector<uint8_t> blob = original;
        const uint32_t bad = 7;
        std::memcpy(blob.data() + section(blob, kSectionProbeSource).offset, &bad, 4);
        expect(blob, TP_ERROR_INVALID_BLOB, "probe_source[0]");
    }
    {
        std::vector<uint8_t> blob = original;
        const uint64_t offset = section(blob, kSectionNormals).offset + 16;
        std::memcpy(blob.data() + sizeof(StoreHeader) + kSectionNormals * sizeof(SectionEntry), &offset, 8);
        expect(blob, TP_ERROR_INVALID_BLOB, "section 1");
    }
    {
        std::vector<uint8_t> blob = original;
        const uint32_t cells = 9;
        std::memcpy(blob.data() + offsetof(StoreHeader, cell_count), &cells, 4);
        expect(blob, TP_ERROR_INVALID_BLOB, "counts imply");
    }
    {
        std::vector<uint8_t> blob = original;
        // 4 probes of SH take 216 bytes, so 8 bytes of padding precede probe_source.
        const SectionEntry sh = section(blob, kSectionSh);
        REQUIRE(sh.offset + sh.size < section(blob, kSectionProbeSource).offset);
        blob[sh.offset + sh.size] = 1;
        expect(blob, TP_ERROR_INVALID_BLOB, "padding");
    }
    CHECK(try_load(std::vector<uint8_t>()) == TP_ERROR_INVALID_BLOB);
}

TEST_CASE("indices switch to 32 bits when forced or when the counts need it", "[store_blob]") {
    const std::array<hand_built::Vec, 4> corners = {hand_built::Vec(0, 0, 0), hand_built::Vec(2, 0, 0),
                                                    hand_built::Vec(0, 2, 0), hand_built::Vec(0, 0, 2)};
    StoreData data = hand_built::tetrahedron_store(corners, true);
    const std::vector<uint8_t> narrow = write_store_blob(data);
    data.flags |= kFlagIndex32;
    const std::vector<uint8_t> wide = write_store_blob(data);
    std::unique_ptr<Store> a = Store::load(narrow.data(), narrow.size());
    std::unique_ptr<Store> b = Store::load(wide.data(), wide.size());
    CHECK((a->header().flags & kFlagIndex32) == 0);
    CHECK((b->header().flags & kFlagIndex32) != 0);
    CHECK(section(wide, kSectionCellVertices).size == 2 * section(narrow, kSectionCellVertices).size);
    const float points[][3] = {{0.2f, 0.3f, 0.4f}, {3, 3, 3}, {-1, -1, 0.5f}, {0.5f, -4, 0.5f}};
    for (const auto& p : points) {
        const Location la = a->locate(p, -1), lb = b->locate(p, -1);
        REQUIRE(la.cell == lb.cell);
        for (int k = 0; k < 4; ++k) {
            REQUIRE(la.probes[k] == lb.probes[k]);
            REQUIRE(la.weights[k] == lb.weights[k]);
        }
    }

    // More cells than 16 bits can index: a line of 70,000 probes switches by itself.
    std::vector<double> xs(70000);
    for (size_t i = 0; i < xs.size(); ++i) xs[i] = double(i) * 0.5;
    const std::vector<uint8_t> big = write_store_blob(hand_built::line_store(xs, true));
    std::unique_ptr<Store> store = Store::load(big.data(), big.size());
    REQUIRE((store->header().flags & kFlagIndex32) != 0);
    REQUIRE(store->header().cell_count > kMaxIndex16);
    int32_t hint = -1;
    for (uint32_t probe : {0u, 1u, 40000u, 65535u, 65536u, 69999u}) {
        const float p[3] = {float(xs[probe]), 0.0f, 0.0f};
        const Location loc = store->locate(p, hint);
        REQUIRE(loc.status == TP_OK);
        float w = 0;
        for (int k = 0; k < 4; ++k)
            if (loc.probes[k] == probe) w += loc.weights[k];
        REQUIRE(w == Approx(1.0f).margin(1e-6));
        hint = loc.cell;
    }
}

TEST_CASE("the writer refuses what the format cannot hold and clamps SH to the half range", "[store_blob]") {
    StoreData data = golden_store_data();
    data.sh[5] = std::nanf("");
    REQUIRE_THROWS_AS(write_store_blob(data), Error);
    data.sh[5] = 1e6f;
    data.sh[6] = -1e6f;
    const std::vector<uint8_t> blob = write_store_blob(data);
    std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
    float sh[27];
    store->probe_sh(0, sh);
    CHECK(sh[5] == 65504.0f);
    CHECK(sh[6] == -65504.0f);

    data = golden_store_data();
    data.normals.pop_back();
    try {
        write_store_blob(data);
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.status() == TP_ERROR_INVALID_ARGUMENT);
        CHECK(std::string(e.what()).find("normals") != std::string::npos);
    }
    data = golden_store_data();
    data.probe_source.clear();
    data.positions.clear();
    data.normals.clear();
    data.sh.clear();
    REQUIRE_THROWS_AS(write_store_blob(data), Error);
}
