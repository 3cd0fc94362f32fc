// libFuzzer target: building a store from arbitrary point sets must never crash (TetGen must never
// see input that kills it) and every store that builds must be exact at its probes. Coordinates
// come from small integers times a scale so that duplicates, lines, planes and lattices are common.
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/store.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 2) return 0;
    const uint8_t mode = data[0];
    const float scales[4] = {1.0f, 1e-4f, 1e5f, 0.37f};
    const float scale = scales[mode & 3];
    const float offset = (mode & 4) ? 1e6f : ((mode & 8) ? 1e3f : 0.0f);
    const bool raw_floats = mode & 16;
    std::vector<float> positions;
    size_t i = 1;
    if (raw_floats) {
        for (; i + 4 <= size && positions.size() < 3 * 64; i += 4) {
            float v;
            std::memcpy(&v, data + i, 4);
            positions.push_back(v);
        }
    } else {
        for (; i < size && positions.size() < 3 * 96; ++i)
            positions.push_back(offset + scale * float(int8_t(data[i]) % 5));
    }
    const size_t count = positions.size() / 3;
    if (count == 0) return 0;
    std::vector<float> sh(count * 27);
    for (size_t p = 0; p < count; ++p)
        for (int c = 0; c < 27; ++c) sh[p * 27 + c] = float((p * 7 + c) % 11);

    tetprobe::BuildSettings settings;
    std::unique_ptr<tetprobe::Store> store;
    std::vector<float> stored;  // the stored probes' local positions (a line or flat set projected)
    try {
        tetprobe::StoreData d = tetprobe::build_store_data(positions.data(), 12, sh.data(), 108, count, settings);
        stored = d.positions;
        std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
        store = tetprobe::Store::load(blob.data(), blob.size());
    } catch (const tetprobe::Error&) {
        return 0;  // refused with a status: fine, as long as the process is alive
    }
    // Every input probe is reproduced exactly by its survivor (weight 1 at the survivor), up to the
    // float32 resolution of the stored local positions (a grid of about extent * 2^-24) and the
    // walk's inside tolerance (1e-5 of a cell, which may be as wide as the set), both coarse next
    // to a stored probe whose nearest neighbour is much closer than the set is wide (measured
    // between stored positions: a line set's gaps are along the line).
    const tetprobe::StoreHeader& header = store->header();
    double extent = 0;
    for (int a = 0; a < 3; ++a)
        extent = std::max(extent, std::fabs(double(header.bounds_max[a]) - double(header.bounds_min[a])));
    int32_t hint = -1;
    for (size_t p = 0; p < count; ++p) {
        const uint32_t own = store->input_to_stored(uint32_t(p));
        double nearest = HUGE_VAL;
        for (size_t q = 0; q < stored.size() / 3; ++q) {
            if (q == own) continue;
            double d2 = 0;
            for (int a = 0; a < 3; ++a) d2 += std::pow(double(stored[3 * own + a]) - double(stored[3 * q + a]), 2);
            nearest = std::min(nearest, std::sqrt(d2));
        }
        const double tolerance = std::max(1e-3, (16 * std::ldexp(1.0, -24) + 2e-5) * extent / nearest);
        tetprobe::Location loc = store->locate(&positions[3 * p], hint);
        if (loc.status != TP_OK) __builtin_trap();
        hint = loc.cell;
        // Closer than 1e-4 of the set's extent (a dense room in a level is 3e-4), a big neighbouring
        // cell can hold a probe within its float rounding: exactness is not claimed there (README).
        if (nearest < 1e-4 * extent) continue;
        const uint32_t survivor = store->input_to_stored(uint32_t(p));
        float w = 0;
        for (int k = 0; k < 4; ++k)
            if (loc.probes[k] == survivor) w += loc.weights[k];
        if (!(std::fabs(w - 1.0f) < tolerance)) __builtin_trap();
    }
    return 0;
}
