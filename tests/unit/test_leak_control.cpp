// Leak control (core/leak_control, core/leak_plane, bake/leak_edges): the side of a wall plane is decided
// exactly; the stored planes are the wall's; cells without a blocked probe pair answer bit for bit as
// without leak control; inside a blocked cell the weights are those of a slow reference (a probe on the
// query's side of the wall keeps its weight, one behind it loses the share its partner holds over where
// the wall crosses) on either side of the wall, and sum to 1; they stay continuous across every facet of
// a blocked cell; a query at a probe still weighs it exactly 1; the probes behind a wall lose their
// weight; a step in the floor is no wall; and on the two-rooms scene the leak error against a bake at the
// path points drops by a clear margin.
#include <catch2/catch.hpp>

#include "bake/leak_edges.h"
#include "bake/lighting_bake.h"
#include "bake/scene.h"
#include "bake/scene_file.h"
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/leak_control.h"
#include "core/leak_plane.h"
#include "core/octahedral_normal.h"
#include "core/store.h"
#include "core/store_data.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace tetprobe;

namespace {

constexpr float kWallX = 0.37f, kWallTop = 0.6f;

// A two-sided wall in the plane x = kWallX, below y = kWallTop (the lattice's upper cells see past it).
Scene wall_scene() {
    Scene scene;
    const float v[12] = {kWallX, -10, -10, kWallX, kWallTop, -10, kWallX, kWallTop, 10, kWallX, -10, 10};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    Material m;
    m.two_sided = true;
    scene.add_mesh(v, 4, indices, 2, {m}, nullptr);
    return scene;
}

std::vector<float> lattice_probes() {
    std::vector<float> p;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
            for (int k = 0; k < 5; ++k) p.insert(p.end(), {float(i - 2), float(j - 2), float(k - 2)});
    return p;
}

std::unique_ptr<Store> load(const StoreData& data) {
    const std::vector<uint8_t> blob = write_store_blob(data);
    return Store::load(blob.data(), blob.size());
}

bool blocked(const StoreData& d, uint32_t a, uint32_t b) {
    if (a == b || d.leak_offsets.empty()) return false;
    if (a > b) std::swap(a, b);
    for (uint32_t i = d.leak_offsets[a]; i < d.leak_offsets[a + 1]; ++i)
        if (d.leak_edges[i].partner == b) return true;
    return false;
}

bool has_blocked_pair(const StoreData& d, const uint32_t probes[4]) {
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            if (blocked(d, probes[i], probes[j])) return true;
    return false;
}

// Weight per stored probe (unused slots repeat a probe with weight 0).
std::map<uint32_t, double> by_probe(const Location& loc) {
    std::map<uint32_t, double> w;
    for (int k = 0; k < 4; ++k) w[loc.probes[k]] += loc.weights[k];
    return w;
}

double largest_difference(const Location& a, const Location& b) {
    std::map<uint32_t, double> wa = by_probe(a), wb = by_probe(b);
    double worst = 0;
    for (const auto& [probe, w] : wa) worst = std::fmax(worst, std::fabs(w - (wb.count(probe) ? wb[probe] : 0.0)));
    for (const auto& [probe, w] : wb) worst = std::fmax(worst, std::fabs(w - (wa.count(probe) ? wa[probe] : 0.0)));
    return worst;
}

struct WallStores {
    StoreData plain_data, leak_data;
    std::unique_ptr<Store> plain, leak;
};

WallStores wall_stores() {
    const Scene scene = wall_scene();
    const std::vector<float> probes = lattice_probes();
    WallStores s;
    s.plain_data = build_store_data(probes.data(), 12, nullptr, 12, probes.size() / 3, BuildSettings());
    BuildSettings settings;
    settings.scene = &scene;
    s.leak_data = build_store_data(probes.data(), 12, nullptr, 12, probes.size() / 3, settings);
    s.plain = load(s.plain_data);
    s.leak = load(s.leak_data);
    return s;
}

}  // namespace

TEST_CASE("leak: a wall plane's side is decided exactly, where double rounding alone would say 0", "[leak]") {
    // Code (16384, 0): N = (16384, 0, 16383). At (1, 0, z) against the offset 16384, N . p - offset is
    // 16383 z exactly: a double sum of the terms loses z beside 16384 and would give 0.
    const int16_t code[2] = {16384, 0};
    int32_t n[3];
    leak_plane_normal(code, n);
    CHECK((n[0] == 16384 && n[1] == 0 && n[2] == 16383));
    for (float z : {1e-30f, 1e-45f, 3e-8f}) {
        const float above[3] = {1.0f, 0.0f, z}, below[3] = {1.0f, 0.0f, -z};
        CHECK(leak_plane_side(code, 16384.0f, above) == 1);
        CHECK(leak_plane_side(code, 16384.0f, below) == -1);
    }
    const float on[3] = {1.0f, 0.0f, 0.0f};
    CHECK(leak_plane_side(code, 16384.0f, on) == 0);
    // Against a reference exact in double: coordinates on a 2^-8 grid below 2^12 (products below 2^27,
    // sums exact), the offset on the same grid; every code, the folded ones included.
    std::mt19937 random(41);
    std::uniform_int_distribution<int> code_part(-32768, 32767), grid(-(1 << 20), 1 << 20);
    for (int i = 0; i < 20000; ++i) {
        const int16_t c[2] = {int16_t(code_part(random)), int16_t(code_part(random))};
        leak_plane_normal(c, n);
        REQUIRE((std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]) >= 32767));
        float direction[3];
        decode_normal(c, direction);  // the same direction, normalised
        const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
        for (int k = 0; k < 3; ++k) REQUIRE(direction[k] == float(n[k] / length));
        const float p[3] = {float(grid(random)) / 256, float(grid(random)) / 256, float(grid(random)) / 256};
        double exact = double(n[0]) * p[0] + double(n[1]) * p[1] + double(n[2]) * p[2];
        const float offset = i % 4 == 0 ? float(exact) : float(grid(random)) / 256;  // on the plane, often
        if (i % 4 == 0 && double(offset) != exact) continue;
        exact -= offset;
        REQUIRE(leak_plane_side(c, offset, p) == (exact > 0) - (exact < 0));
    }
}

TEST_CASE("leak: a stored wall plane separates its pair exactly and passes by the crossing", "[leak]") {
    std::mt19937 random(43);
    std::uniform_real_distribution<double> u(-1.0, 1.0), t(0.01, 0.99);
    size_t grazing = 0;
    for (int i = 0; i < 5000; ++i) {
        float own[3], other[3];
        double normal[3], crossing[3];
        for (int k = 0; k < 3; ++k) {
            own[k] = float(100 * u(random));
            other[k] = float(own[k] + 3 * u(random));
            normal[k] = u(random);
        }
        const double at = t(random);
        for (int k = 0; k < 3; ++k) crossing[k] = own[k] + at * (double(other[k]) - own[k]);
        if (i % 10 == 0) {  // a wall almost along the segment: the code cannot separate, the segment's direction is used
            const double d[3] = {double(other[0]) - own[0], double(other[1]) - own[1], double(other[2]) - own[2]};
            normal[0] = d[1], normal[1] = -d[0], normal[2] = 1e-9;
            ++grazing;
        }
        int16_t code[2];
        float offset;
        REQUIRE(make_leak_plane(normal, crossing, own, other, code, &offset));
        REQUIRE(leak_plane_side(code, offset, own) == 1);
        REQUIRE(leak_plane_side(code, offset, other) == -1);
        int32_t n[3];
        leak_plane_normal(code, n);
        const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
        const double distance = (n[0] * crossing[0] + n[1] * crossing[1] + n[2] * crossing[2] - offset) / length;
        INFO("the crossing lies " << distance << " from the plane");
        CHECK(std::fabs(distance) < 1e-4);  // float offsets near 100 * 56755: a few float steps over |N|
    }
    CHECK(grazing > 0);
}

TEST_CASE("leak: the edges crossing a wall are found, each side's plane the wall's", "[leak]") {
    const WallStores s = wall_stores();
    REQUIRE((s.leak->header().flags & kFlagLeakControl) != 0);
    REQUIRE((s.plain->header().flags & kFlagLeakControl) == 0);
    REQUIRE(s.leak->header().leak_edge_count == s.leak_data.leak_edges.size());
    size_t edges = 0;
    const double wall = kWallX - s.leak_data.origin[0];  // local
    for (uint32_t a = 0; a < s.leak_data.probe_count(); ++a) {
        for (uint32_t i = s.leak_data.leak_offsets[a]; i < s.leak_data.leak_offsets[a + 1]; ++i, ++edges) {
            const LeakEdge& e = s.leak_data.leak_edges[i];
            const float* pa = &s.leak_data.positions[3 * a];
            const float* pb = &s.leak_data.positions[3 * e.partner];
            REQUIRE((pa[0] - wall) * (pb[0] - wall) < 0);  // on either side of the wall
            const double crossing = (wall - pa[0]) / (pb[0] - pa[0]);
            const double crossing_y = pa[1] + crossing * (pb[1] - pa[1]) + s.leak_data.origin[1];
            REQUIRE(crossing_y <= kWallTop + 1e-6);  // through the wall, not over it
            const float* ends[2] = {pa, pb};
            for (int side = 0; side < 2; ++side) {
                // A wall without thickness: both planes are x = wall, each facing its probe.
                const int16_t code[2] = {e.normal[side][0], e.normal[side][1]};
                int32_t n[3];
                leak_plane_normal(code, n);
                const int facing = ends[side][0] < wall ? -1 : 1;
                CHECK((n[0] == facing * 32767 && n[1] == 0 && n[2] == 0));
                CHECK(double(e.offset[side]) / n[0] == Approx(wall).margin(1e-6));
                CHECK(leak_plane_side(code, e.offset[side], ends[side]) == 1);
                CHECK(leak_plane_side(code, e.offset[side], ends[1 - side]) == -1);
                const double reach = side == 0 ? crossing : 1 - crossing;
                CHECK(e.reach[side] / 65535.0 == Approx(reach).margin(1e-5));
            }
        }
    }
    CHECK(edges > 20);
}

TEST_CASE("leak: inside a blocked cell the weights on each side of the wall are the reference's", "[leak]") {
    // The slow reference: the plain barycentric weights w; a probe k behind the wall from the query (on the
    // other side of x = kWallX) is kept by 1 - min(1, sum of w_j / reach_k(j)) over its blocked partners j on
    // the query's side (reach_k(j): the fraction of the edge from k to the wall); every probe then by
    // (kept + kLeakFloor), renormalised to sum 1. A probe on the query's side keeps its weight (its share
    // grows by the common renormalisation only). Inverting the side test, or testing the wrong probe's
    // plane, fails this.
    const WallStores s = wall_stores();
    const double* origin = s.leak->header().origin;
    std::mt19937 random(47);
    std::uniform_real_distribution<float> x(kWallX - 0.63f, kWallX + 0.63f), y(-2.0f, 0.5f), z(-2.0f, 2.0f);
    std::map<int32_t, int> sides_seen;  // per blocked cell: bit 0 a query left of the wall, bit 1 right
    size_t checked = 0;
    for (int q = 0; q < 20000; ++q) {
        const float p[3] = {x(random), y(random), z(random)};
        if (std::fabs(p[0] - kWallX) < 1e-3f) continue;
        const bool left = p[0] < kWallX;
        const Location a = s.plain->locate(p, -1), b = s.leak->locate(p, -1);
        REQUIRE(a.cell == b.cell);
        if (!has_blocked_pair(s.leak_data, b.probes)) continue;
        ++checked;
        std::map<uint32_t, double> w = by_probe(a), got = by_probe(b);
        std::map<uint32_t, double> kept;
        for (const auto& [k, wk] : w) {
            kept[k] = 1;
            const double xk = s.leak->probe_position(k)[0] + origin[0];
            if ((xk < kWallX) == left) continue;  // on the query's side
            for (const auto& [j, wj] : w) {
                if (!blocked(s.leak_data, k, j)) continue;
                const double xj = s.leak->probe_position(j)[0] + origin[0];
                const double reach = (xk - kWallX) / (xk - xj);
                kept[k] -= wj / reach;
            }
            kept[k] = std::fmax(0.0, kept[k]);
        }
        double total = 0;
        for (const auto& [k, wk] : w) total += wk * (kept[k] + kLeakFloor);
        double sum = 0, own_side_ratio = -1;
        for (const auto& [k, wk] : w) {
            const double expected = wk * (kept[k] + kLeakFloor) / total;
            INFO("query (" << p[0] << ", " << p[1] << ", " << p[2] << "), probe " << k);
            REQUIRE(got[k] == Approx(expected).margin(2e-4));
            sum += got[k];
            const double xk = s.leak->probe_position(k)[0] + origin[0];
            if ((xk < kWallX) == left && wk > 0.05) {  // the query's side: one common ratio, at least 1
                const double ratio = got[k] / wk;
                REQUIRE(ratio >= 1 - 1e-6);
                if (own_side_ratio >= 0) REQUIRE(ratio == Approx(own_side_ratio).epsilon(1e-5));
                own_side_ratio = ratio;
            }
        }
        REQUIRE(sum == Approx(1.0).margin(1e-6));
        sides_seen[b.cell] |= left ? 1 : 2;
    }
    size_t both = 0;
    for (const auto& [cell, seen] : sides_seen) both += seen == 3;
    INFO(checked << " queries in blocked cells, " << both << " cells queried on both sides of the wall");
    CHECK(checked > 3000);
    CHECK(both > 20);
}

TEST_CASE("leak: cells without a blocked pair answer bit for bit as without leak control", "[leak]") {
    const WallStores s = wall_stores();
    std::mt19937 random(17);
    std::uniform_real_distribution<float> u(-2.6f, 2.6f);
    size_t unblocked = 0, blocked_cells = 0, changed = 0;
    int32_t plain_hint = -1, leak_hint = -1;
    for (int q = 0; q < 20000; ++q) {
        const float p[3] = {u(random), u(random), u(random)};
        const Location a = s.plain->locate(p, -1), b = s.leak->locate(p, -1);
        REQUIRE(a.cell == b.cell);
        float sa[27], sb[27];
        REQUIRE(s.plain->interpolate(p, &plain_hint, sa) == Status::ok);
        REQUIRE(s.leak->interpolate(p, &leak_hint, sb) == Status::ok);
        if (!has_blocked_pair(s.leak_data, b.probes)) {
            ++unblocked;
            for (int k = 0; k < 4; ++k) {
                REQUIRE(a.probes[k] == b.probes[k]);
                REQUIRE(a.weights[k] == b.weights[k]);
            }
        } else {
            ++blocked_cells;
            double sum = 0;
            for (int k = 0; k < 4; ++k) {
                REQUIRE(b.weights[k] >= 0.0f);
                sum += b.weights[k];
            }
            if (b.kind == CellKind::inner) REQUIRE(sum == Approx(1.0).margin(1e-6));
            if (largest_difference(a, b) > 0.1) ++changed;
        }
    }
    CHECK(unblocked > 5000);
    CHECK(blocked_cells > 2000);
    CHECK(changed > 500);
}

TEST_CASE("leak: weights are continuous across every facet of a blocked cell", "[leak]") {
    const WallStores s = wall_stores();
    const Store& store = *s.leak;
    std::mt19937 random(23);
    std::uniform_real_distribution<double> u(0.02, 1.0);
    const double* origin = store.header().origin;
    const double step = 2e-5;  // either side of the facet
    double worst = 0;
    size_t facets = 0;
    for (uint32_t c = 0; c < store.header().inner_cell_count; ++c) {
        uint32_t vertices[4], neighbours[4];
        store.cell(c, vertices, neighbours);
        if (!has_blocked_pair(s.leak_data, vertices)) continue;
        for (int k = 0; k < 4; ++k) {
            if (neighbours[k] == kNone32) continue;
            ++facets;
            for (int sample = 0; sample < 8; ++sample) {
                double b[3] = {u(random), u(random), u(random)};
                const double total = b[0] + b[1] + b[2];
                double on_facet[3] = {0, 0, 0}, towards[3];
                for (int j = 0, m = 0; j < 4; ++j) {
                    if (j == k) continue;
                    for (int a = 0; a < 3; ++a) on_facet[a] += b[m] / total * store.probe_position(vertices[j])[a];
                    ++m;
                }
                double length = 0;
                for (int a = 0; a < 3; ++a) {
                    towards[a] = store.probe_position(vertices[k])[a] - on_facet[a];
                    length += towards[a] * towards[a];
                }
                length = std::sqrt(length);
                float inside[3], outside[3];
                for (int a = 0; a < 3; ++a) {
                    inside[a] = float(origin[a] + on_facet[a] + step * towards[a] / length);
                    outside[a] = float(origin[a] + on_facet[a] - step * towards[a] / length);
                }
                // The weights may jump where a wall's plane is crossed (x = kWallX, the one plane here): not
                // across a facet.
                if ((inside[0] < kWallX) != (outside[0] < kWallX) || inside[0] == kWallX || outside[0] == kWallX) continue;
                worst = std::fmax(worst, largest_difference(store.locate(inside, -1), store.locate(outside, -1)));
            }
        }
    }
    INFO("largest jump across " << facets << " facets: " << worst);
    CHECK(facets > 50);
    // The steepest share is w_j / reach with reach >= 0.37 / 1.5 of an edge: its slope, a few per unit,
    // over the 4e-5 between the two sides bounds the honest change; a jump would be of order 0.1 to 1.
    CHECK(worst < 1e-3);
}

TEST_CASE("leak: a query at a probe weighs it exactly 1; behind the wall the far probes lose their weight", "[leak]") {
    const WallStores s = wall_stores();
    const double* origin = s.leak->header().origin;
    for (uint32_t probe = 0; probe < s.leak->header().probe_count; ++probe) {
        float p[3];
        for (int a = 0; a < 3; ++a) p[a] = float(origin[a] + s.leak->probe_position(probe)[a]);
        const Location loc = s.leak->locate(p, -1);
        std::map<uint32_t, double> w = by_probe(loc);
        REQUIRE(w[probe] == 1.0);
        for (const auto& [other, weight] : w)
            if (other != probe) REQUIRE(weight == 0.0);
    }
    // Just right of the wall, below its top: the weight of probes left of it, with and without leak control.
    std::mt19937 random(29);
    std::uniform_real_distribution<float> x(kWallX + 0.07f, kWallX + 0.5f), y(-2.0f, 0.0f), z(-2.0f, 2.0f);
    double plain_far = 0, leak_far = 0;
    for (int q = 0; q < 2000; ++q) {
        const float p[3] = {x(random), y(random), z(random)};
        const Location a = s.plain->locate(p, -1), b = s.leak->locate(p, -1);
        for (int k = 0; k < 4; ++k) {
            if (s.plain->probe_position(a.probes[k])[0] + origin[0] < kWallX) plain_far += a.weights[k];
            if (s.leak->probe_position(b.probes[k])[0] + origin[0] < kWallX) leak_far += b.weights[k];
        }
    }
    INFO("weight behind the wall: " << plain_far / 2000 << " without, " << leak_far / 2000 << " with leak control");
    CHECK(plain_far > 0.2 * 2000);
    CHECK(leak_far < 0.1 * plain_far);
}

TEST_CASE("leak: on the two-rooms scene the leak error along a path through the wall drops", "[leak][two_rooms]") {
    const Scene scene = load_scene_file(TP_SOURCE_DIR "/samples/scenes/two_rooms.json");
    const std::vector<float>& probes = scene.probes();
    // The path: across the dividing wall (x = 4) at a table's height, 0.8 from the door, between the probe
    // columns either side of it (x = 3.5 and 4.7: the cells whose edges cross the wall).
    std::vector<float> path;
    for (int i = 0; i <= 40; ++i) {
        const float x = 3.5f + 0.03f * float(i);  // between the probe columns either side of the wall
        if (std::fabs(x - 4.0f) < 0.03f) continue;  // inside the wall
        path.insert(path.end(), {x, 1.2f, 3.3f});
    }
    BakeSettings settings;
    settings.rays = 96;
    settings.bounces = 1;
    settings.seed = 4;
    settings.threads = 2;
    const std::vector<float> probe_sh = bake_lighting(scene, probes, settings);
    const std::vector<float> reference = bake_lighting(scene, path, settings);
    BuildSettings plain_settings, leak_settings;
    leak_settings.scene = &scene;
    const size_t count = probes.size() / 3;
    const std::unique_ptr<Store> plain =
        load(build_store_data(probes.data(), 12, probe_sh.data(), 108, count, plain_settings));
    const std::unique_ptr<Store> leak = load(build_store_data(probes.data(), 12, probe_sh.data(), 108, count, leak_settings));
    REQUIRE(leak->header().leak_edge_count > 0);
    double plain_error = 0, leak_error = 0, level = 0;
    for (size_t i = 0; i < path.size() / 3; ++i) {
        float a[27], b[27];
        REQUIRE(plain->interpolate(&path[3 * i], nullptr, a) == Status::ok);
        REQUIRE(leak->interpolate(&path[3 * i], nullptr, b) == Status::ok);
        for (int c = 0; c < 3; ++c) {  // the constant term of each channel: mean radiance over directions
            plain_error += std::fabs(a[9 * c] - reference[27 * i + 9 * c]);
            leak_error += std::fabs(b[9 * c] - reference[27 * i + 9 * c]);
            level += std::fabs(reference[27 * i + 9 * c]);
        }
    }
    WARN("two rooms, mean relative error of the constant term along the path: " << plain_error / level
         << " without, " << leak_error / level << " with leak control (" << leak->header().leak_edge_count
         << " blocked pairs)");
    CHECK(leak_error < 0.7 * plain_error);  // measured 0.43 -> 0.23
}

TEST_CASE("leak: a step in the floor between two probes is not a wall; a wall is", "[leak]") {
    // Probes 0.15 above a floor at y = 0 (x < 0) and above a 0.3 step (x > 0): the straight segment between
    // them meets the step's riser, the parallel segments above it do not. A wall 3 high in the same place
    // blocks every one of them.
    auto solid_box = [](Scene& scene, const float lo[3], const float hi[3]) {
        std::vector<float> v;
        for (int corner = 0; corner < 8; ++corner)
            for (int a = 0; a < 3; ++a) v.push_back(corner & (1 << a) ? hi[a] : lo[a]);
        const uint32_t indices[36] = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                      2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
        Material m;
        m.two_sided = false;
        scene.add_mesh(v.data(), 8, indices, 12, {m}, nullptr);
    };
    const std::vector<float> probes = {-1.0f, 0.15f, 0.0f, 1.0f, 0.45f, 0.0f, -1.0f, 0.15f, 1.5f, 1.0f, 0.45f, 1.5f,
                                       0.0f, 2.5f, 0.75f};
    auto blocked_pair = [&](const Scene& scene) {
        BuildSettings settings;
        settings.scene = &scene;
        const StoreData d = build_store_data(probes.data(), 12, nullptr, 12, probes.size() / 3, settings);
        return blocked(d, d.input_remap[0], d.input_remap[1]);
    };
    const float floor_lo[3] = {-5, -1, -5}, floor_hi[3] = {0, 0, 5};
    Scene step;
    solid_box(step, floor_lo, floor_hi);
    const float step_lo[3] = {0, -1, -5}, step_hi[3] = {5, 0.3f, 5};
    solid_box(step, step_lo, step_hi);
    CHECK_FALSE(blocked_pair(step));
    Scene wall = step;
    const float wall_lo[3] = {-0.05f, 0, -5}, wall_hi[3] = {0.05f, 3, 5};
    solid_box(wall, wall_lo, wall_hi);
    CHECK(blocked_pair(wall));
}

TEST_CASE("leak: a wall plane at its probe (the smallest reach) still gives finite weights summing to 1", "[leak]") {
    WallStores s = wall_stores();
    for (LeakEdge& e : s.leak_data.leak_edges) e.reach[0] = e.reach[1] = 1;
    const std::unique_ptr<Store> store = load(s.leak_data);
    std::mt19937 random(31);
    std::uniform_real_distribution<float> u(-2.2f, 2.2f);
    const std::vector<float> probes = lattice_probes();
    for (size_t q = 0; q < 5000 + probes.size() / 3; ++q) {
        float p[3] = {u(random), u(random), u(random)};
        if (q >= 5000) std::copy_n(&probes[3 * (q - 5000)], 3, p);
        const Location loc = store->locate(p, -1);
        double sum = 0;
        for (int k = 0; k < 4; ++k) {
            REQUIRE(std::isfinite(loc.weights[k]));
            REQUIRE(loc.weights[k] >= 0.0f);
            sum += loc.weights[k];
        }
        REQUIRE(sum == Approx(1.0).margin(1e-5));
    }
}

TEST_CASE("leak: the blocked pairs do not depend on the thread count, and the build reports them", "[leak][threads]") {
    const Scene scene = load_scene_file(TP_SOURCE_DIR "/samples/scenes/two_rooms.json");
    const std::vector<float>& probes = scene.probes();
    const size_t count = probes.size() / 3;
    std::vector<std::vector<uint8_t>> blobs;
    for (uint32_t threads : {1u, 2u, 3u}) {
        BuildSettings settings;
        settings.scene = &scene;
        settings.threads = threads;
        const StoreData data = build_store_data(probes.data(), 12, nullptr, 108, count, settings);
        REQUIRE(!data.leak_edges.empty());
        blobs.push_back(write_store_blob(data));
    }
    CHECK(blobs[1] == blobs[0]);
    CHECK(blobs[2] == blobs[0]);

    // Leak control reports in its own slice of the build's progress, in order, and can be cancelled there.
    struct Log {
        std::vector<float> fractions;
        std::vector<std::string> stages;
        bool cancel = false;
    } log;
    BuildSettings settings;
    settings.scene = &scene;
    settings.progress.user = &log;
    settings.progress.callback = [](void* user, float fraction, const char* stage) {
        Log& l = *static_cast<Log*>(user);
        l.fractions.push_back(fraction);
        l.stages.push_back(stage);
        return l.cancel && l.stages.back() == "leak control" ? 1 : 0;
    };
    build_store_data(probes.data(), 12, nullptr, 108, count, settings);
    CHECK(std::is_sorted(log.fractions.begin(), log.fractions.end()));
    CHECK(log.fractions.back() == 1.0f);
    REQUIRE(std::count(log.stages.begin(), log.stages.end(), "leak control") >= 1);
    for (size_t i = 0; i < log.stages.size(); ++i)
        if (log.stages[i] == "leak control") CHECK((log.fractions[i] >= 0.87f && log.fractions[i] <= 0.9f));
    log = Log();
    log.cancel = true;
    try {
        build_store_data(probes.data(), 12, nullptr, 108, count, settings);
        FAIL("the build was not cancelled");
    } catch (const Error& e) {
        CHECK(e.status() == Status::cancelled);
        CHECK(std::string(e.what()) == "cancelled by the progress callback during leak control");
    }
}

TEST_CASE("leak: pairs farther apart than kLeakLongestPair are not flagged, nearer ones across the wall are",
          "[leak]") {
    // Two probes either side of the wall at each distance, two more off to the side so that there is a volume:
    // the wall-crossing pair is flagged exactly when it is at most kLeakLongestPair apart.
    const Scene scene = wall_scene();
    for (double half : {0.5, 1.4, 1.6, 3.0}) {
        const double d = 2 * half;
        const std::vector<float> probes = {float(kWallX - half), -1.0f, 0.0f, float(kWallX + half), -1.0f, 0.0f,
                                           float(kWallX - half), -1.0f, 1.5f, float(kWallX - half), -2.5f, -1.0f};
        BuildSettings settings;
        settings.scene = &scene;
        const StoreData data = build_store_data(probes.data(), 12, nullptr, 12, 4, settings);
        // The stored order is canonical: find the pair by position.
        uint32_t a = 4, b = 4;
        for (uint32_t p = 0; p < 4; ++p) {
            const double x = data.positions[3 * p] + data.origin[0], y = data.positions[3 * p + 1] + data.origin[1];
            const double z = data.positions[3 * p + 2] + data.origin[2];
            if (std::fabs(y + 1.0) < 1e-4 && std::fabs(z) < 1e-4) (x < kWallX ? a : b) = p;
        }
        REQUIRE(a < 4);
        REQUIRE(b < 4);
        INFO("pair " << d << " apart");
        CHECK(blocked(data, a, b) == (d <= kLeakLongestPair));
    }
}

TEST_CASE("leak: batches weigh by visibility as single queries do, bit for bit", "[leak][batch]") {
    const WallStores s = wall_stores();
    std::mt19937 random(23);
    std::uniform_real_distribution<float> u(-2.2f, 2.2f);
    const size_t n = 3000;
    std::vector<float> points(3 * n);
    for (float& x : points) x = u(random);
    std::vector<int32_t> hints(n, -1);
    std::vector<float> sh(27 * n), weights(4 * n);
    std::vector<uint32_t> probes(4 * n);
    REQUIRE(s.leak->interpolate_batch(n, points.data(), 12, hints.data(), 4, sh.data(), 108, BatchSettings{}, nullptr) ==
            Status::ok);
    REQUIRE(s.leak->weights_batch(n, points.data(), 12, nullptr, 0, probes.data(), 16, weights.data(), 16,
                                  BatchSettings{}, nullptr) == Status::ok);
    size_t weighed = 0;
    for (size_t i = 0; i < n; ++i) {
        const Location loc = s.leak->locate(&points[3 * i], -1);
        float single[27];
        int32_t hint = -1;
        REQUIRE(s.leak->interpolate(&points[3 * i], &hint, single) == Status::ok);
        REQUIRE(hint == hints[i]);
        REQUIRE(std::memcmp(single, &sh[27 * i], sizeof single) == 0);
        REQUIRE(std::memcmp(loc.weights, &weights[4 * i], sizeof loc.weights) == 0);
        const Location plain = s.plain->locate(&points[3 * i], -1);
        weighed += std::memcmp(plain.weights, loc.weights, sizeof loc.weights) != 0;
    }
    CHECK(weighed > 100);  // the wall changes many answers: the batch did weigh them
}

namespace {

// The probes with random distinct SH (so that a wrong weight shows in an answer), built with leak control
// against the scene and without it.
struct LeakAndPlain {
    std::unique_ptr<Store> leak, plain;
};
LeakAndPlain leak_and_plain_stores(const Scene& scene, const std::vector<float>& probes, std::mt19937& random) {
    const size_t count = probes.size() / 3;
    std::uniform_real_distribution<float> value(-1.0f, 1.0f);
    std::vector<float> sh(27 * count);
    for (float& x : sh) x = value(random);
    BuildSettings settings;
    settings.scene = &scene;
    return {load(build_store_data(probes.data(), 12, sh.data(), 108, count, settings)),
            load(build_store_data(probes.data(), 12, sh.data(), 108, count, BuildSettings()))};
}

}  // namespace

TEST_CASE("leak: interpolations take the fused kernel and answer blocked cells again, as locate-weigh-blend does, "
          "bit for bit", "[leak][batch]") {
    const Scene scene = wall_scene();
    std::mt19937 random(41);
    const LeakAndPlain stores = leak_and_plain_stores(scene, lattice_probes(), random);
    const Store* leak = stores.leak.get();
    const Store* plain = stores.plain.get();
    std::uniform_real_distribution<float> u(-2.2f, 2.2f);
    const size_t n = 3000;
    std::vector<float> points(3 * n);
    for (float& x : points) x = u(random);
    std::vector<int32_t> hints(n, -1);
    std::vector<float> batch(27 * n);
    REQUIRE(leak->interpolate_batch(n, points.data(), 12, hints.data(), 4, batch.data(), 108, BatchSettings{}, nullptr) ==
            Status::ok);
    size_t weighed = 0;
    for (size_t i = 0; i < n; ++i) {
        float single[27], piped[27], occlusion[4], unweighed[27];
        int32_t hint = -1, piped_hint = -1, plain_hint = -1;
        REQUIRE(leak->interpolate(&points[3 * i], &hint, single) == Status::ok);
        // Asking for occlusion takes the pipeline: locate, weigh for leaks, blend.
        REQUIRE(leak->interpolate(&points[3 * i], &piped_hint, piped, occlusion) == Status::ok);
        REQUIRE(hint == piped_hint);
        REQUIRE(hint == hints[i]);
        REQUIRE(std::memcmp(single, piped, sizeof single) == 0);
        REQUIRE(std::memcmp(single, &batch[27 * i], sizeof single) == 0);
        REQUIRE(plain->interpolate(&points[3 * i], &plain_hint, unweighed) == Status::ok);
        weighed += std::memcmp(single, unweighed, sizeof single) != 0;
    }
    CHECK(weighed > 100);  // the wall changes many answers
}

TEST_CASE("leak: from carried hints and far beyond an irregular hull, single and chained batch interpolations "
          "answer as locate-weigh-blend does, bit for bit", "[leak][batch]") {
    // Irregular probes crossed by the wall (outer cells whose sweeps meet in gaps); queries inside and far
    // beyond the hull, each from the previous one's cell as a moving object's hint carries it, and the same
    // as one batch without hints chaining them (the batch's one-after-the-other path).
    const Scene scene = wall_scene();
    const unsigned seed = GENERATE(7u, 8u);
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> jitter(-0.45f, 0.45f), box(-2.5f, 2.5f);
    std::vector<float> probes = lattice_probes();
    for (float& x : probes) x = seed % 2 ? x + jitter(random) : box(random);
    const LeakAndPlain stores = leak_and_plain_stores(scene, probes, random);
    const Store* leak = stores.leak.get();
    const Store* plain = stores.plain.get();
    std::uniform_real_distribution<float> near(-3.0f, 3.0f), far(-40.0f, 40.0f);
    const size_t n = 10003;  // not a whole number of batch groups
    std::vector<float> points(3 * n);
    for (size_t i = 0; i < n; ++i)
        for (int a = 0; a < 3; ++a) points[3 * i + size_t(a)] = i % 2 ? far(random) : near(random);
    BatchSettings chained;
    chained.chain_hints = true;
    std::vector<float> batch(27 * n);
    REQUIRE(leak->interpolate_batch(n, points.data(), 12, nullptr, 0, batch.data(), 108, chained, nullptr) == Status::ok);
    int32_t fused_hint = -1, piped_hint = -1, plain_hint = -1;
    size_t weighed = 0;
    for (size_t i = 0; i < n; ++i) {
        const float* q = &points[3 * i];
        float fused[27], piped[27], occlusion[4], unweighed[27];
        REQUIRE(leak->interpolate(q, &fused_hint, fused) == Status::ok);
        REQUIRE(leak->interpolate(q, &piped_hint, piped, occlusion) == Status::ok);  // the pipeline
        REQUIRE(fused_hint == piped_hint);
        REQUIRE(std::memcmp(fused, piped, sizeof fused) == 0);
        REQUIRE(std::memcmp(fused, &batch[27 * i], sizeof fused) == 0);
        REQUIRE(plain->interpolate(q, &plain_hint, unweighed) == Status::ok);
        weighed += std::memcmp(fused, unweighed, sizeof fused) != 0;
    }
    CHECK(weighed > 100);  // the wall changes many answers
}
