// libFuzzer target: building a store from arbitrary point sets must never crash (TetGen must never
// see input that kills it), and every store that builds, written in the fast or the compact layout
// (mode bit 32), must load and answer every probe's position with valid weights. Decisions are exact
// orientation predicates on the stored floats, so every input probe whose survivor is stored exactly
// at the probe's own local position (not merged from elsewhere, not moved onto a fitted plane or
// line) is answered by that probe alone, with weight exactly 1, on every set that builds. Coordinates
// come either from small integers times a scale plus an offset, so that duplicates, lines, planes and
// lattices are common, or (mode bit 16) from raw float bits (denormals next to 1e19, tiny gaps).
// Mode bit 64 adds scene data: occlusion bytes and a wall through the middle of the set (leak
// control), which must keep every answer valid and every probe's own answer exact. Every store that
// builds rebuilds its cells, neighbours and start grid from its stored probes exactly
// (core/cell_rebuild.h), whatever ties or magnitudes the set holds.
#include "bake/scene.h"
#include "bake/store_builder.h"
#include "core/cell_rebuild.h"
#include "core/error.h"
#include "core/store.h"
#include "core/store_format.h"

#include <cmath>
#include <cstring>
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
    settings.flags = (mode & 32) ? tetprobe::kFlagCompact : 0u;
    const bool scene_data = mode & 64;
    std::vector<uint8_t> occlusion(count * 4);
    for (size_t b = 0; b < occlusion.size(); ++b) occlusion[b] = uint8_t(b * 37 + (mode >> 1));
    tetprobe::Scene scene;
    if (scene_data) {
        settings.occlusion = occlusion.data();
        settings.occlusion_lights = 1 + uint32_t(count % 4);
        // A two-sided square in the plane x = (middle of the set), reaching well past its bounds.
        float lo[3] = {positions[0], positions[1], positions[2]}, hi[3] = {lo[0], lo[1], lo[2]};
        for (size_t p = 0; p < count; ++p)
            for (int k = 0; k < 3; ++k) lo[k] = std::fmin(lo[k], positions[3 * p + k]), hi[k] = std::fmax(hi[k], positions[3 * p + k]);
        const float x = 0.5f * lo[0] + 0.5f * hi[0], r = 1.0f + (hi[1] - lo[1]) + (hi[2] - lo[2]);
        const float cy = 0.5f * lo[1] + 0.5f * hi[1], cz = 0.5f * lo[2] + 0.5f * hi[2];
        const float v[12] = {x, cy - r, cz - r, x, cy + r, cz - r, x, cy + r, cz + r, x, cy - r, cz + r};
        const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
        tetprobe::Material m;
        m.two_sided = true;
        try {
            scene.add_mesh(v, 4, indices, 2, {m}, nullptr);
            settings.scene = &scene;
        } catch (const tetprobe::Error&) {
            // a set whose extent overflows the wall: no leak control, occlusion only
        }
    }
    tetprobe::StoreData d;
    try {
        d = tetprobe::build_store_data(positions.data(), 12, sh.data(), 108, count, settings);
    } catch (const tetprobe::Error&) {
        return 0;  // refused with a status: fine, as long as the process is alive
    }
    // A store that keeps no cells would rebuild these exactly.
    try {
        const tetprobe::RebuiltCells r =
            tetprobe::rebuild_cells(d.positions.data(), d.probe_count(), d.dimension, d.axis,
                                    !(d.flags & tetprobe::kFlagNoExtrapolation), d.bounds_min, d.bounds_max, d.grid);
        if (r.inner_cell_count != d.inner_cell_count || r.cell_vertices != d.cell_vertices ||
            r.cell_neighbours != d.cell_neighbours || r.grid_cells != d.grid_cells)
            __builtin_trap();
    } catch (const tetprobe::Error&) {
        __builtin_trap();
    }
    // What builds must write and load (the loader validates orientations and neighbours too).
    std::unique_ptr<tetprobe::Store> store;
    try {
        std::vector<uint8_t> blob = tetprobe::write_store_blob(d);
        store = tetprobe::Store::load(blob.data(), blob.size());
    } catch (const tetprobe::Error&) {
        __builtin_trap();
    }
    if (((store->header().flags & tetprobe::kFlagCompact) != 0) != ((mode & 32) != 0)) __builtin_trap();
    // Every query succeeds with weights in [0, 1] summing to 1; a probe stored where it was given
    // weighs exactly 1 at its own position.
    int32_t hint = -1;
    for (size_t p = 0; p < count; ++p) {
        tetprobe::Location loc = store->locate(&positions[3 * p], hint);
        if (loc.status != tetprobe::Status::ok) __builtin_trap();
        hint = loc.cell;
        float sum = 0;
        for (int k = 0; k < 4; ++k) {
            if (!(loc.weights[k] >= 0.0f && loc.weights[k] <= 1.0f)) __builtin_trap();
            sum += loc.weights[k];
        }
        if (!(std::fabs(sum - 1.0f) < 1e-5f)) __builtin_trap();
        float answer[27], visible[4];
        if (store->interpolate(&positions[3 * p], nullptr, answer, visible) != tetprobe::Status::ok) __builtin_trap();
        for (float o : visible)
            if (!(o >= 0.0f && o <= 1.0f)) __builtin_trap();
        const uint32_t survivor = store->input_to_stored(uint32_t(p));
        const float* stored = store->probe_position(survivor);
        bool as_given = true;
        for (int k = 0; k < 3; ++k)
            as_given &= float(double(positions[3 * p + k]) - store->header().origin[k]) == stored[k];
        if (!as_given) continue;  // merged from elsewhere or moved onto the fitted plane or line
        float w = 0;
        for (int k = 0; k < 4; ++k)
            if (loc.probes[k] == survivor) w += loc.weights[k];
        if (w != 1.0f) __builtin_trap();
    }
    return 0;
}
