// libFuzzer target: blob loading (format 6: every layout, SH encoding and position encoding, with and
// without the occlusion and leak-control sections; older formats are refused by version, the rebuilt
// layout as unsupported) must reject or accept any bytes safely, and a store that loads must answer
// queries without reading out of bounds. The first byte picks a mode: bit 0 repairs the checksum first,
// so mutations reach the deeper checks (counts, indices, floats, orientations, neighbours, leak lists,
// maps); bits 1 and 7 flip the header's layout by 1 and 2 (fast, compact, rebuilt), bits 4 and 5 its SH
// encoding, bit 6 its position encoding, so that one seed reaches every other kind's loader; bits 2
// and 3 flip the occlusion and leak-control flags the same way. Every query must end within its cap
// of examined cells (core/walk.cpp, core/exhaustive_search.cpp): a walk of cells + 64 steps past its
// start, a search of 3 x outer cells + 4096; one that gives up says so (invalid_blob). The seeds
// include forged blobs with valid checksums (tests/fuzz/seeds/fuzz_load/forged_*, written by tetprobe_tests "[.write-forged-seeds]").
#include "core/error.h"
#include "core/store.h"
#include "core/store_format.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const bool repair_checksum = data[0] & 1;
    std::vector<uint8_t> blob(data + 1, data + size);
    auto flip = [&](size_t offset, uint32_t bits) {
        uint32_t word;
        std::memcpy(&word, blob.data() + offset, sizeof word);
        word ^= bits;
        std::memcpy(blob.data() + offset, &word, sizeof word);
    };
    if (blob.size() >= sizeof(tetprobe::StoreHeader)) {
        using tetprobe::StoreHeader;
        flip(offsetof(StoreHeader, flags),
             ((data[0] & 4) ? tetprobe::kFlagOcclusion : 0u) | ((data[0] & 8) ? tetprobe::kFlagLeakControl : 0u));
        flip(offsetof(StoreHeader, layout), ((data[0] & 2) ? 1u : 0u) | ((data[0] & 128) ? 2u : 0u));
        flip(offsetof(StoreHeader, sh_encoding), (data[0] >> 4) & 3u);
        flip(offsetof(StoreHeader, position_encoding), (data[0] & 64) ? 1u : 0u);
    }
    if (repair_checksum && blob.size() >= tetprobe::kHeaderSize) {
        uint64_t sum = tetprobe::store_checksum(blob.data(), blob.size());
        std::memcpy(blob.data() + tetprobe::kChecksumOffset, &sum, sizeof sum);
    }
    std::unique_ptr<tetprobe::Store> store;
    try {
        store = tetprobe::Store::load(blob.data(), blob.size());
    } catch (const tetprobe::Error& e) {
        // Only these three, and a blob that names another format version is always a version error.
        if (e.status() != tetprobe::Status::invalid_blob && e.status() != tetprobe::Status::version &&
            e.status() != tetprobe::Status::unsupported)
            __builtin_trap();
        return 0;
    }
    if (store->header().format_version != tetprobe::kStoreFormatVersion) __builtin_trap();
    // A validated store: queries anywhere, with any hint, must terminate and stay in bounds.
    const auto& h = store->header();
    const float lo[3] = {h.bounds_min[0], h.bounds_min[1], h.bounds_min[2]};
    const float hi[3] = {h.bounds_max[0], h.bounds_max[1], h.bounds_max[2]};
    const float probes[][3] = {{0.5f, 0.5f, 0.5f}, {-1.f, 2.f, 0.25f}, {3.f, -2.f, 7.f}, {0.f, 0.f, 0.f}, {1e9f, -1e9f, 1e9f}};
    int32_t hint = -1;
    float sh[27];
    // Every probe's decoded SH is finite.
    for (uint32_t j = 0; j < h.probe_count; ++j) {
        store->probe_sh(j, sh);
        for (float x : sh)
            if (!std::isfinite(x)) __builtin_trap();
    }
    for (const auto& f : probes) {
        float p[3];
        for (int k = 0; k < 3; ++k) p[k] = float(h.origin[k] + lo[k] + f[k] * (hi[k] - lo[k]));
        tetprobe::Location loc = store->locate(p, hint);
        if (uint64_t(loc.steps) > uint64_t(h.cell_count) + 65 ||
            loc.searched > 3 * uint64_t(h.cell_count - h.inner_cell_count) + 4096)
            __builtin_trap();
        if (loc.status != tetprobe::Status::ok && loc.status != tetprobe::Status::outside &&
            loc.status != tetprobe::Status::invalid_blob)
            __builtin_trap();
        if (loc.status == tetprobe::Status::ok) {
            for (int k = 0; k < 4; ++k)
                if (!std::isfinite(loc.weights[k]) || loc.probes[k] >= h.probe_count) __builtin_trap();
            if (loc.cell < 0 || uint32_t(loc.cell) >= h.cell_count) __builtin_trap();
        }
        float visible[4];
        if (store->interpolate(p, &hint, sh, visible) == tetprobe::Status::ok)
            for (float o : visible)
                if (!(o >= 0.0f && o <= 1.0f)) __builtin_trap();
        hint = int32_t(size) - 7;  // arbitrary, possibly invalid hints must be safe too
    }
    return 0;
}
