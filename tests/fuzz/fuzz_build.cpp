// libFuzzer target: building a store from arbitrary point sets must never crash (TetGen must never
// see input that kills it), and every store that builds, written in the fast or the compact layout
// (mode bit 32), must load and answer every probe's position with valid weights. Decisions are exact
// orientation predicates on the stored floats, so every input probe whose survivor is stored exactly
// at the probe's own local position (not merged from elsewhere, not moved onto a fitted plane or
// line) is answered by that probe alone, with weight exactly 1, on every set that builds. Coordinates
// come either from small integers times a scale plus an offset, so that duplicates, lines, planes and
// lattices are common, or (mode bit 16) from raw float bits (denormals next to 1e19, tiny gaps).
// Mode bit 64 adds scene data: occlusion bytes and a wall through the middle of the set (leak
// control), which must keep every answer valid and every probe's own answer exact. Mode bit 128 grows
// a set of up to 600 probes from a few bytes (grow_set: lattices, jittered or not, in 3, 2 or 1
// dimensions, tilted planes, lines, clusters, shells, clouds), which the remaining bytes then edit probe by probe, so that sets of
// hundreds of probes are reached (the byte decoder alone takes 3 bytes a probe).
// Every store that builds rebuilds its cells, neighbours and start grid from its stored probes exactly
// (core/cell_rebuild.h), whatever ties or magnitudes the set holds.
#include "bake/scene.h"
#include "bake/store_builder.h"
#include "core/cell_rebuild.h"
#include "core/error.h"
#include "core/store.h"
#include "core/store_format.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace {

// Deterministic numbers from a seed (splitmix64), so an input always grows the same set.
struct Numbers {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1p-53 * 2.0 - 1.0; }  // [-1, 1)
};

constexpr size_t kMaxGrownProbes = 600;

// Grows a probe set from the 8 bytes at g (positions in units of about 1, before the mode's scale and
// offset): g[0] picks the family, g[1..3] its sizes, g[4] the jitter (2^-g[4] of the spacing; >= 40
// none), g[5..7] the seed. The bytes after them edit single probes, 4 bytes each: a probe, an
// operation (move along an axis by a power of two, copy another probe, or move onto the midpoint of two).
std::vector<float> grow_set(const uint8_t* g, const uint8_t* edits, size_t edit_bytes) {
    Numbers numbers{uint64_t(g[5]) | uint64_t(g[6]) << 8 | uint64_t(g[7]) << 16};
    const double jitter = g[4] >= 40 ? 0.0 : std::ldexp(1.0, -int(g[4]));
    std::vector<double> p;
    auto add = [&](double x, double y, double z) {
        if (p.size() / 3 >= kMaxGrownProbes) return;
        p.push_back(x + jitter * numbers.uniform());
        p.push_back(y + jitter * numbers.uniform());
        p.push_back(z + jitter * numbers.uniform());
    };
    const int a = 1 + g[1] % 12, b = 1 + g[2] % 12, c = 1 + g[3] % 12;
    switch (g[0] % 6) {
        case 0:  // a lattice a x b x c (a line or a grid in a plane when sizes are 1)
            for (int z = 0; z < c; ++z)
                for (int y = 0; y < b; ++y)
                    for (int x = 0; x < a; ++x) add(x, y, z);
            break;
        case 1: {  // a lattice in a tilted plane, slopes of small integers over the sizes
            const double sx = double(int(g[3] % 7) - 3) / a, sy = double(int(g[3] / 7 % 7) - 3) / b;
            for (int y = 0; y < 2 * b; ++y)
                for (int x = 0; x < 2 * a; ++x) add(x, y, sx * x + sy * y);
            break;
        }
        case 2: {  // a clusters of b * 8 probes each, 2^-c wide, spread over 100 units
            for (int k = 0; k < a; ++k) {
                const double cx = 100 * numbers.uniform(), cy = 100 * numbers.uniform(), cz = 100 * numbers.uniform();
                const double r = std::ldexp(1.0, -c);
                for (int i = 0; i < 8 * b; ++i) add(cx + r * numbers.uniform(), cy + r * numbers.uniform(), cz + r * numbers.uniform());
            }
            break;
        }
        case 3: {  // a shell: every probe on the hull, a * b * 4 of them
            for (int i = 0; i < 4 * a * b; ++i) {
                double v[3], n2 = 0;
                for (double& x : v) n2 += (x = numbers.uniform()) * x;
                const double n = n2 > 1e-12 ? std::sqrt(n2) : 1.0;
                add(10 * v[0] / n, 10 * v[1] / n, 10 * v[2] / n);
            }
            break;
        }
        case 4: {  // a line of 8 * (g[1] % 64 + 1) probes along a direction of small integers
            const double dy = double(int(g[2] % 5) - 2), dz = double(int(g[3] % 5) - 2);
            for (int i = 0; i < 8 * (g[1] % 64 + 1); ++i) add(0.25 * i, 0.25 * i * dy, 0.25 * i * dz);
            break;
        }
        default:  // a random cloud of a * b * c probes in a box a x b x c
            for (int i = 0; i < a * b * c; ++i) add(a * numbers.uniform(), b * numbers.uniform(), c * numbers.uniform());
    }
    const size_t count = p.size() / 3;
    for (size_t e = 0; count > 0 && e + 4 <= edit_bytes; e += 4) {
        const size_t probe = edits[e] % count, other = edits[e + 2] % count, axis = edits[e + 3] % 3;
        switch (edits[e + 1] % 4) {
            case 0:
            case 1: p[3 * probe + axis] += (edits[e + 1] & 4 ? -1 : 1) * std::ldexp(1.0, int(edits[e + 1] >> 3) - 24); break;
            case 2: std::copy_n(&p[3 * other], 3, &p[3 * probe]); break;
            default:
                for (size_t k = 0; k < 3; ++k) p[3 * probe + k] = 0.5 * (p[3 * other + k] + p[3 * ((other + 1) % count) + k]);
        }
    }
    return std::vector<float>(p.begin(), p.end());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 2) return 0;
    const uint8_t mode = data[0];
    const float scales[4] = {1.0f, 1e-4f, 1e5f, 0.37f};
    const float scale = scales[mode & 3];
    const float offset = (mode & 4) ? 1e6f : ((mode & 8) ? 1e3f : 0.0f);
    const bool raw_floats = mode & 16;
    std::vector<float> positions;
    size_t i = 1;
    if (mode & 128) {
        if (size < 9) return 0;
        positions = grow_set(data + 1, data + 9, size - 9);
        for (float& x : positions) x = offset + scale * x;
    } else if (raw_floats) {
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
