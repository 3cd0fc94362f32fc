// Probe volumes (core/volume_sampling): every point of a volume is bit for bit the store's single query there,
// replayed in the documented walk order with the carried hint (tetrahedra, flat, line and point stores, leak
// control, points beyond the hull, a store without extrapolation); the formats are the documented repackings of
// the same SH; the strides are honoured byte for byte; the Unity constants evaluate (ShadeSH9) to irradiance / pi;
// bad grids are refused.
#include <catch2/catch.hpp>

#include "probe_families.h"

#include "bake/scene.h"
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/sh.h"
#include "core/store.h"
#include "core/store_data.h"
#include "core/unity_sh_constants.h"
#include "core/volume_sampling.h"

#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace tetprobe;

namespace {

std::vector<float> random_sh(size_t probes, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<float> sh(27 * probes);
    for (float& v : sh) v = u(rng);
    return sh;
}

std::unique_ptr<Store> build(const std::vector<float>& positions, uint32_t flags = 0, const Scene* scene = nullptr) {
    const size_t count = positions.size() / 3;
    const std::vector<float> sh = random_sh(count, uint32_t(count) * 7 + flags);
    BuildSettings settings;
    settings.flags = flags;
    settings.scene = scene;
    const std::vector<uint8_t> blob = write_store_blob(build_store_data(positions.data(), 12, sh.data(), 108, count, settings));
    return Store::load(blob.data(), blob.size());
}

// The walk order of the header, written out independently: slices ascending, rows alternating per slice,
// points alternating per row walked.
std::vector<std::array<uint32_t, 3>> walk_order(const uint32_t dims[3]) {
    std::vector<std::array<uint32_t, 3>> order;
    uint32_t row = 0;
    for (uint32_t z = 0; z < dims[2]; ++z)
        for (uint32_t j = 0; j < dims[1]; ++j, ++row) {
            const uint32_t y = z % 2 ? dims[1] - 1 - j : j;
            for (uint32_t i = 0; i < dims[0]; ++i) order.push_back({row % 2 ? dims[0] - 1 - i : i, y, z});
        }
    return order;
}

struct Replay {
    std::vector<float> sh;         // 27 per point, [z][y][x]
    std::vector<Status> status;    // per point
    int32_t first_cell = -1;
};

// Single queries in the walk order, carrying the hint from start_hint.
Replay replay(const Store& store, const VolumeGrid& g, int32_t start_hint) {
    const size_t n = size_t(g.dims[0]) * g.dims[1] * g.dims[2];
    Replay r;
    r.sh.assign(27 * n, NAN);
    r.status.assign(n, Status::ok);
    int32_t hint = start_hint;
    bool first = true;
    for (const auto& p : walk_order(g.dims)) {
        float world[3];
        for (int a = 0; a < 3; ++a)
            world[a] = float(double(g.origin[a]) + double(p[a]) * double(g.cell_size[a]));
        const size_t i = p[0] + g.dims[0] * (p[1] + size_t(g.dims[1]) * p[2]);
        r.status[i] = store.interpolate(world, &hint, &r.sh[27 * i]);
        if (first) r.first_cell = hint, first = false;
    }
    return r;
}

VolumeStrides packed(const VolumeGrid& g, VolumeFormat format) {
    VolumeStrides s;
    s.unit = volume_unit_floats(format) * sizeof(float);
    s.point = s.unit * volume_units_per_point(format);
    s.row = s.point * g.dims[0];
    s.slice = s.row * g.dims[1];
    return s;
}

// Runs a volume in the plain L2 format and checks it against the replay, bit for bit, and the statuses.
void check_volume_equals_single_queries(const Store& store, const VolumeGrid& g, int32_t start_hint) {
    const size_t n = size_t(g.dims[0]) * g.dims[1] * g.dims[2];
    const Replay expected = replay(store, g, start_hint);
    std::vector<float> out(27 * n, -7.0f);
    int32_t hint = start_hint;
    uint32_t failed[3] = {99, 99, 99};
    const Status status = sample_volume(store, g, VolumeFormat::sh_l2, packed(g, VolumeFormat::sh_l2), &hint, out.data(), failed);
    REQUIRE(std::memcmp(out.data(), expected.sh.data(), out.size() * sizeof(float)) == 0);
    CHECK(hint == expected.first_cell);
    // The status is the first failure in walk order, naming its point.
    Status first = Status::ok;
    std::array<uint32_t, 3> first_point{};
    for (const auto& p : walk_order(g.dims)) {
        const Status s = expected.status[p[0] + g.dims[0] * (p[1] + size_t(g.dims[1]) * p[2])];
        if (s != Status::ok) {
            first = s, first_point = p;
            break;
        }
    }
    CHECK(status == first);
    if (first != Status::ok)
        for (int a = 0; a < 3; ++a) CHECK(failed[a] == first_point[a]);
}

}  // namespace

TEST_CASE("volume: the walk visits every point once, each a neighbour of the one before", "[volume]") {
    const uint32_t dims[3] = {5, 4, 3};
    const auto order = walk_order(dims);
    REQUIRE(order.size() == 60);
    std::vector<int> seen(60, 0);
    for (size_t k = 0; k < order.size(); ++k) {
        ++seen[order[k][0] + 5 * (order[k][1] + 4 * order[k][2])];
        if (k == 0) continue;
        int moved = 0;
        for (int a = 0; a < 3; ++a) moved += std::abs(int(order[k][a]) - int(order[k - 1][a]));
        CHECK(moved == 1);
    }
    for (int s : seen) CHECK(s == 1);
}

TEST_CASE("volume: every point is bit for bit the single query with the carried hint (tetrahedra)", "[volume]") {
    const families::ProbeSet cloud = families::random_cloud(300, 11, 5);
    const std::unique_ptr<Store> store = build(cloud.positions);
    VolumeGrid g;
    // Inside, across the hull and well beyond it (the outer cells), with unequal sides and spacings.
    const float origins[3][3] = {{-2, -1.5f, -1}, {3, 3, 3}, {-9, -4, 2}};
    const float cells[3][3] = {{0.25f, 0.2f, 0.3f}, {0.4f, 0.3f, 0.35f}, {0.7f, 0.5f, 0.9f}};
    const uint32_t dims[3][3] = {{16, 16, 16}, {7, 9, 11}, {32, 3, 1}};
    for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) g.origin[a] = origins[c][a], g.cell_size[a] = cells[c][a], g.dims[a] = dims[c][a];
        check_volume_equals_single_queries(*store, g, -1);
        check_volume_equals_single_queries(*store, g, 17);  // a start hint far from the volume
    }
}

TEST_CASE("volume: a lattice whose points fall on facets (ties decided by the carried hint) matches too", "[volume]") {
    // Grid points on the probes' own lattice: many lie on facets and at probes, where the cell found depends on
    // the walk's start; the replay with the same hint decides the same.
    const families::ProbeSet lattice = families::lattice(5, 5, 5, 1.0);
    const std::unique_ptr<Store> store = build(lattice.positions);
    VolumeGrid g;
    for (int a = 0; a < 3; ++a) g.origin[a] = -1, g.cell_size[a] = 0.5f, g.dims[a] = 13;
    check_volume_equals_single_queries(*store, g, -1);
}

TEST_CASE("volume: flat, line and single-probe stores, and a store without extrapolation", "[volume]") {
    std::vector<float> flat, line, point = {1, 2, 3};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-3, 3);
    for (int i = 0; i < 40; ++i) flat.insert(flat.end(), {u(rng), 0.5f, u(rng)});
    for (int i = 0; i < 12; ++i) line.insert(line.end(), {float(i) * 0.7f - 3, 1, -2});
    VolumeGrid g;
    for (int a = 0; a < 3; ++a) g.origin[a] = -4, g.cell_size[a] = 0.45f, g.dims[a] = 19;
    for (const std::vector<float>* set : {&flat, &line, &point}) {
        const std::unique_ptr<Store> store = build(*set);
        check_volume_equals_single_queries(*store, g, -1);
    }
    // Without extrapolation: the points beyond the hull fail as single queries do (zero SH), the walk goes on
    // and the first failure in walk order is reported.
    const families::ProbeSet cloud = families::random_cloud(200, 3, 2);
    const std::unique_ptr<Store> bounded = build(cloud.positions, kFlagNoExtrapolation);
    check_volume_equals_single_queries(*bounded, g, -1);
    for (int a = 0; a < 3; ++a) g.origin[a] = -1, g.cell_size[a] = 0.1f, g.dims[a] = 8;  // all inside
    check_volume_equals_single_queries(*bounded, g, -1);
}

TEST_CASE("volume: leak control weighs the volume's points as single queries", "[volume][leak]") {
    Scene scene;
    const float v[12] = {0.37f, -10, -10, 0.37f, 0.6f, -10, 0.37f, 0.6f, 10, 0.37f, -10, 10};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    Material m;
    m.two_sided = true;
    scene.add_mesh(v, 4, indices, 2, {m}, nullptr);
    const families::ProbeSet lattice = families::lattice(5, 5, 5, 1.0);
    std::vector<float> probes = lattice.positions;
    for (float& p : probes) p -= 2;
    const std::unique_ptr<Store> store = build(probes, 0, &scene);
    REQUIRE(store->header().leak_edge_count > 0);
    VolumeGrid g;
    for (int a = 0; a < 3; ++a) g.origin[a] = -2.2f, g.cell_size[a] = 0.3f, g.dims[a] = 16;
    check_volume_equals_single_queries(*store, g, -1);
}

TEST_CASE("volume: the L1 and Unity formats are the documented repackings of the L2 SH", "[volume]") {
    const families::ProbeSet cloud = families::random_cloud(100, 8, 3);
    const std::unique_ptr<Store> store = build(cloud.positions);
    VolumeGrid g;
    for (int a = 0; a < 3; ++a) g.origin[a] = -2, g.cell_size[a] = 0.5f + 0.1f * a, g.dims[a] = 4 + a;
    const size_t n = size_t(g.dims[0]) * g.dims[1] * g.dims[2];
    uint32_t failed[3];
    std::vector<float> l2(27 * n);
    int32_t hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::sh_l2, packed(g, VolumeFormat::sh_l2), &hint, l2.data(), failed) == Status::ok);
    std::vector<float> l1(12 * n), u1(12 * n), u2(28 * n);
    hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::sh_l1, packed(g, VolumeFormat::sh_l1), &hint, l1.data(), failed) == Status::ok);
    hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::unity_l1, packed(g, VolumeFormat::unity_l1), &hint, u1.data(), failed) == Status::ok);
    hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::unity_l2, packed(g, VolumeFormat::unity_l2), &hint, u2.data(), failed) == Status::ok);
    // The scale factors as the header writes them, rounded to float here independently.
    const double pi = 3.14159265358979323846, sp = std::sqrt(pi);
    const float s0 = float(1 / (2 * sp)), s1 = float(std::sqrt(3.0) / (3 * sp)), s2 = float(std::sqrt(15.0) / (8 * sp)),
                s20 = float(std::sqrt(5.0) / (16 * sp)), s22 = float(std::sqrt(15.0) / (16 * sp));
    for (size_t p = 0; p < n; ++p) {
        const float* c = &l2[27 * p];
        for (int ch = 0; ch < 3; ++ch) {
            for (int i = 0; i < 4; ++i) CHECK(l1[12 * p + 4 * ch + i] == c[9 * ch + i]);
            const float* k = c + 9 * ch;
            const float u[9] = {k[0] * s0, k[1] * s1, k[2] * s1, k[3] * s1, k[4] * s2, k[5] * s2, k[6] * s20, k[7] * s2, k[8] * s22};
            const float a1[4] = {u[3], u[1], u[2], u[0]};
            const float a2[4] = {u[3], u[1], u[2], u[0] - u[6]};
            const float b2[4] = {u[4], u[5], 3 * u[6], u[7]};
            CHECK(std::memcmp(&u1[12 * p + 4 * ch], a1, sizeof a1) == 0);
            CHECK(std::memcmp(&u2[28 * p + 4 * ch], a2, sizeof a2) == 0);
            CHECK(std::memcmp(&u2[28 * p + 12 + 4 * ch], b2, sizeof b2) == 0);
            CHECK(u2[28 * p + 24 + ch] == u[8]);
        }
        CHECK(u2[28 * p + 27] == 1.0f);
    }
}

TEST_CASE("volume: ShadeSH9 of the Unity constants is the irradiance divided by pi", "[volume]") {
    const std::vector<float> sh = random_sh(1, 99);
    float l2[kUnityL2Floats], l1[kUnityL1Floats];
    unity_sh_constants(sh.data(), true, l2);
    unity_sh_constants(sh.data(), false, l1);
    std::vector<float> l1_only(sh);  // band 2 cleared: what the L1 constants hold
    for (int c = 0; c < 3; ++c)
        for (int i = 4; i < 9; ++i) l1_only[9 * c + i] = 0;
    std::mt19937 rng(4);
    std::normal_distribution<double> g;
    const double pi = 3.14159265358979323846;
    for (int t = 0; t < 200; ++t) {
        double n[3] = {g(rng), g(rng), g(rng)};
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (double& v : n) v /= len;
        const float nf[3] = {float(n[0]), float(n[1]), float(n[2])};
        float e2[3], e1[3];
        sh_eval_irradiance(sh.data(), nf, e2);
        sh_eval_irradiance(l1_only.data(), nf, e1);
        for (int c = 0; c < 3; ++c) {
            // UnityCG.cginc: dot(SHA, (n, 1)) + dot(SHB, n.xyzz * n.yzzx) + SHC.c (x^2 - y^2).
            const float* a = l2 + 4 * c;
            const float* b = l2 + 12 + 4 * c;
            const double shade9 = a[0] * n[0] + a[1] * n[1] + a[2] * n[2] + a[3] + b[0] * n[0] * n[1] + b[1] * n[1] * n[2] +
                                  b[2] * n[2] * n[2] + b[3] * n[2] * n[0] + l2[24 + c] * (n[0] * n[0] - n[1] * n[1]);
            CHECK(shade9 == Approx(e2[c] / pi).margin(1e-5));
            const float* a1 = l1 + 4 * c;
            const double shade4 = a1[0] * n[0] + a1[1] * n[1] + a1[2] * n[2] + a1[3];
            CHECK(shade4 == Approx(e1[c] / pi).margin(1e-5));
        }
    }
}

TEST_CASE("volume: strides are honoured byte for byte (a Light Probe Proxy Volume atlas)", "[volume]") {
    const families::ProbeSet cloud = families::random_cloud(100, 9, 3);
    const std::unique_ptr<Store> store = build(cloud.positions);
    VolumeGrid g;
    for (int a = 0; a < 3; ++a) g.origin[a] = -1, g.cell_size[a] = 0.3f, g.dims[a] = 5 + a;
    const uint32_t nx = g.dims[0], ny = g.dims[1], nz = g.dims[2];
    const size_t n = size_t(nx) * ny * nz;
    uint32_t failed[3];
    std::vector<float> packed_u1(12 * n);
    int32_t hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::unity_l1, packed(g, VolumeFormat::unity_l1), &hint, packed_u1.data(),
                          failed) == Status::ok);
    // The atlas: 4 x nx texels a row (SHAr, SHAg, SHAb, occlusion blocks), float4 texels; the occlusion block and a
    // pad after each slice must stay untouched.
    VolumeStrides s;
    s.unit = 16 * nx;
    s.point = 16;
    s.row = 64 * nx;
    s.slice = 64 * nx * ny + 12;  // a pad between slices
    std::vector<unsigned char> atlas(s.slice * nz, 0xAB);
    hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::unity_l1, s, &hint, atlas.data(), failed) == Status::ok);
    std::vector<char> written(atlas.size(), 0);
    for (uint32_t z = 0; z < nz; ++z)
        for (uint32_t y = 0; y < ny; ++y)
            for (uint32_t x = 0; x < nx; ++x)
                for (uint32_t k = 0; k < 3; ++k) {
                    const size_t at = z * s.slice + y * s.row + x * s.point + k * s.unit;
                    const size_t p = x + nx * (y + size_t(ny) * z);
                    CHECK(std::memcmp(&atlas[at], &packed_u1[12 * p + 4 * k], 16) == 0);
                    std::memset(&written[at], 1, 16);
                }
    size_t untouched = 0;
    for (size_t i = 0; i < atlas.size(); ++i)
        if (!written[i]) {
            CHECK(atlas[i] == 0xAB);
            ++untouched;
        }
    CHECK(untouched == nz * (16 * nx * ny + 12));
    // Plain L2 interleaved with another array: 27 floats then 5 foreign floats per point.
    VolumeStrides t = packed(g, VolumeFormat::sh_l2);
    t.point = 32 * sizeof(float);
    t.row = t.point * nx;
    t.slice = t.row * ny;
    std::vector<float> interleaved(32 * n, 123.0f), plain(27 * n);
    hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::sh_l2, t, &hint, interleaved.data(), failed) == Status::ok);
    hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::sh_l2, packed(g, VolumeFormat::sh_l2), &hint, plain.data(), failed) == Status::ok);
    for (size_t p = 0; p < n; ++p) {
        CHECK(std::memcmp(&interleaved[32 * p], &plain[27 * p], 108) == 0);
        for (int k = 27; k < 32; ++k) CHECK(interleaved[32 * p + k] == 123.0f);
    }
    // L2 at an odd byte address (legal: no stride or buffer needs alignment) is copied, not blended in place:
    // the same bytes.
    std::vector<unsigned char> odd(108 * n + 1, 0xAB);
    hint = -1;
    REQUIRE(sample_volume(*store, g, VolumeFormat::sh_l2, packed(g, VolumeFormat::sh_l2), &hint, odd.data() + 1, failed) ==
            Status::ok);
    CHECK(odd[0] == 0xAB);
    CHECK(std::memcmp(odd.data() + 1, plain.data(), 108 * n) == 0);
}

TEST_CASE("volume: bad grids are refused with a message naming the value", "[volume]") {
    VolumeGrid g;
    auto refused = [&](const std::string& needle, uint32_t format = 0) {
        try {
            validate_volume(g, format);
        } catch (const Error& e) {
            CHECK(e.status() == Status::invalid_argument);
            CHECK(std::string(e.what()).find(needle) != std::string::npos);
            return;
        }
        FAIL("accepted: " + needle);
    };
    validate_volume(g, 0);
    g.dims[1] = 0;
    refused("dims[1] is 0");
    g.dims[1] = 33;
    refused("dims[1] (33) is above 32");
    g.dims[1] = 32;
    validate_volume(g, 3);
    refused("unknown volume format 4", 4);
    g.origin[2] = NAN;
    refused("origin[2]");
    g.origin[2] = 0;
    g.cell_size[0] = INFINITY;
    refused("cell_size[0]");
    g.cell_size[0] = 0;
    refused("cell_size[0]");
    g.cell_size[0] = -1;
    refused("cell_size[0]");
    g.cell_size[0] = 3e37f;
    validate_volume(g, 0);  // one point along x: no far corner beyond the origin
    g.dims[0] = 32;
    refused("far corner along axis 0");
}
