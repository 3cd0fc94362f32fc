// Occlusion probes (bake/occlusion_bake): mixed lights' visibility per probe against analytic
// occluders (a half-space wall, a sphere), their interpolation in a store (the barycentric blend of
// the quantised bytes), what a mixed light adds to the baked SH (its bounced light only, as a
// realtime light), and the limit of four mixed lights.
#include <catch2/catch.hpp>

#include "bake/lighting_bake.h"
#include "bake/occlusion_bake.h"
#include "bake/scene.h"
#include "bake/store_builder.h"
#include "core/error.h"
#include "core/store.h"
#include "core/store_data.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

using namespace tetprobe;

namespace {

constexpr double kPi = 3.14159265358979323846;

LightDescription mixed_directional(float x, float y, float z) {
    LightDescription light;
    light.type = LightType::directional;
    light.direction = {x, y, z};
    light.mode = LightMode::mixed;
    return light;
}

LightDescription mixed_point(float x, float y, float z) {
    LightDescription light;
    light.type = LightType::point;
    light.position = {x, y, z};
    light.mode = LightMode::mixed;
    return light;
}

// The plane x = 0 as a two-sided square of half size 100 (a half-space wall for probes near the origin).
void add_wall(Scene& scene) {
    const float v[12] = {0, -100, -100, 0, 100, -100, 0, 100, 100, 0, -100, 100};
    const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    Material m;
    m.two_sided = true;
    scene.add_mesh(v, 4, indices, 2, {m}, nullptr);
}

// A UV sphere of radius r at c: its faces lie between r cos(pi/16)cos(pi/32) and r from the centre.
void add_sphere(Scene& scene, const double c[3], double r) {
    const int rings = 16, segments = 32;
    std::vector<float> v;
    for (int i = 0; i <= rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2 * kPi * j / segments;
            v.push_back(float(c[0] + r * std::sin(theta) * std::cos(phi)));
            v.push_back(float(c[1] + r * std::cos(theta)));
            v.push_back(float(c[2] + r * std::sin(theta) * std::sin(phi)));
        }
    }
    std::vector<uint32_t> indices;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const uint32_t a = uint32_t(i * segments + j), b = uint32_t(i * segments + (j + 1) % segments);
            const uint32_t c2 = a + segments, d = b + segments;
            indices.insert(indices.end(), {a, c2, b, b, c2, d});
        }
    Material m;
    m.two_sided = true;
    scene.add_mesh(v.data(), v.size() / 3, indices.data(), indices.size() / 3, {m}, nullptr);
}

std::vector<float> lattice(int n, float lo, float hi, float offset_x = 0) {
    std::vector<float> p;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const float step = (hi - lo) / float(n - 1);
                p.insert(p.end(), {lo + step * i + offset_x, lo + step * j, lo + step * k});
            }
    return p;
}

// The smallest distance from c to the segment p -> q.
double segment_distance(const double p[3], const double q[3], const double c[3]) {
    double d[3], w[3], dd = 0, wd = 0;
    for (int k = 0; k < 3; ++k) {
        d[k] = q[k] - p[k];
        w[k] = c[k] - p[k];
        dd += d[k] * d[k];
        wd += w[k] * d[k];
    }
    const double t = std::fmax(0.0, std::fmin(1.0, wd / dd));
    double s = 0;
    for (int k = 0; k < 3; ++k) s += (p[k] + t * d[k] - c[k]) * (p[k] + t * d[k] - c[k]);
    return std::sqrt(s);
}

}  // namespace

TEST_CASE("occlusion: a half-space wall hides a mixed light from the probes behind it", "[occlusion]") {
    Scene scene;
    add_wall(scene);
    scene.add_light(mixed_directional(1, 0, 0));   // travels +x: lights the x < 0 side
    scene.add_light(mixed_point(-3, 0.2f, 0.1f));  // on the x < 0 side too
    scene.add_light(mixed_point(2.5f, 0, 0));      // on the x > 0 side
    REQUIRE(scene.mixed_light_count() == 3);
    const std::vector<float> probes = lattice(4, -1.5f, 1.5f, 0.1f);  // x = -1.4 .. 1.6, none on the wall
    uint32_t lights = 0;
    const std::vector<uint8_t> occlusion = bake_occlusion(scene, probes, BakeSettings(), &lights);
    REQUIRE(lights == 3);
    for (size_t i = 0; i < probes.size() / 3; ++i) {
        const bool lit_side = probes[3 * i] < 0;
        CHECK(occlusion[4 * i + 0] == (lit_side ? 255 : 0));
        CHECK(occlusion[4 * i + 1] == (lit_side ? 255 : 0));
        CHECK(occlusion[4 * i + 2] == (lit_side ? 0 : 255));
        CHECK(occlusion[4 * i + 3] == 255);  // no fourth light
    }

    // Interpolated occlusion is the blend of the stored bytes with the query's own weights.
    BuildSettings settings;
    settings.occlusion = occlusion.data();
    settings.occlusion_lights = lights;
    const StoreData data = build_store_data(probes.data(), 12, nullptr, 12, probes.size() / 3, settings);
    const std::vector<uint8_t> blob = write_store_blob(data);
    const std::unique_ptr<Store> store = Store::load(blob.data(), blob.size());
    REQUIRE(store->header().occlusion_lights == 3);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> inside(-1.4f, 1.6f), beyond(-4.0f, 4.0f);
    int32_t hint = -1;
    for (int q = 0; q < 400; ++q) {
        const float p[3] = {q < 300 ? inside(random) : beyond(random), inside(random), inside(random)};
        float sh[27], visible[4];
        const Location loc = store->locate(p, -1);
        REQUIRE(store->interpolate(p, &hint, sh, visible) == Status::ok);
        for (uint32_t l = 0; l < 4; ++l) {
            double expected = 0;
            for (int k = 0; k < 4; ++k) {
                uint8_t bytes[4];
                store->probe_occlusion(loc.probes[k], bytes);
                expected += double(loc.weights[k]) * bytes[l] / 255.0;
            }
            expected = std::fmin(1.0, std::fmax(0.0, expected));
            REQUIRE(visible[l] == Approx(expected).margin(1e-6));
        }
        // Cells entirely on one side answer that side's visibility exactly.
        bool all_lit = true, all_dark = true;
        for (int k = 0; k < 4; ++k) {
            if (loc.weights[k] == 0) continue;
            const bool lit = store->probe_position(loc.probes[k])[0] + store->header().origin[0] < 0;
            all_lit &= lit;
            all_dark &= !lit;
        }
        if (all_lit) REQUIRE(visible[0] == Approx(1.0f).margin(1e-6));  // the weights sum to 1 within rounding
        if (all_dark) REQUIRE(visible[0] == 0.0f);
        REQUIRE(visible[3] == 1.0f);
    }
    // A store without occlusion answers 1 (nothing known to shadow).
    const StoreData plain = build_store_data(probes.data(), 12, nullptr, 12, probes.size() / 3, BuildSettings());
    const std::vector<uint8_t> plain_blob = write_store_blob(plain);
    const std::unique_ptr<Store> plain_store = Store::load(plain_blob.data(), plain_blob.size());
    float sh[27], visible[4];
    const float p[3] = {0.3f, 0.2f, 0.1f};
    REQUIRE(plain_store->interpolate(p, nullptr, sh, visible) == Status::ok);
    for (float v : visible) CHECK(v == 1.0f);
    CHECK(plain.occlusion.empty());
    // 4 bytes a probe, give or take the alignment padding of the section.
    CHECK(double(blob.size()) == Approx(double(plain_blob.size() + 4 * data.probe_count())).margin(15));
}

TEST_CASE("occlusion: a sphere casts the analytic shadow cone of a point light", "[occlusion]") {
    const double centre[3] = {0, 0, 0}, radius = 1.0;
    const double light[3] = {0, 0, -4};
    Scene scene;
    add_sphere(scene, centre, radius);
    scene.add_light(mixed_point(float(light[0]), float(light[1]), float(light[2])));
    LightDescription no_shadows = mixed_point(0, 0, 4);
    no_shadows.shadows = false;
    scene.add_light(no_shadows);
    std::vector<float> probes;
    std::mt19937 random(11);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    while (probes.size() < 3 * 2000) {
        const float p[3] = {u(random), u(random), u(random) + 1.5f};
        if (std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]) < 1.05 * radius) continue;
        probes.insert(probes.end(), p, p + 3);
    }
    uint32_t lights = 0;
    const std::vector<uint8_t> occlusion = bake_occlusion(scene, probes, BakeSettings(), &lights);
    REQUIRE(lights == 2);
    // Analytic: shadowed where the segment to the light passes within the radius. The tessellated sphere
    // lies between 0.98 r and r, so the band between is not judged.
    const double inner = radius * std::cos(kPi / 16) * std::cos(kPi / 32);
    size_t shadowed = 0, lit = 0;
    for (size_t i = 0; i < probes.size() / 3; ++i) {
        const double p[3] = {probes[3 * i], probes[3 * i + 1], probes[3 * i + 2]};
        const double d = segment_distance(p, light, centre);
        if (d < inner * 0.999) {
            REQUIRE(occlusion[4 * i] == 0);
            ++shadowed;
        } else if (d > radius * 1.001) {
            REQUIRE(occlusion[4 * i] == 255);
            ++lit;
        }
        REQUIRE(occlusion[4 * i + 1] == 255);  // casts no shadows
    }
    CHECK(shadowed > 100);
    CHECK(lit > 1000);
}

TEST_CASE("occlusion: a mixed light bakes only its bounced light, as a realtime one; five are refused", "[occlusion]") {
    auto scene_with = [](LightMode mode) {
        Scene scene;
        const float lo[3] = {-2, -1, -2}, hi[3] = {2, 2, 2};
        std::vector<float> v;
        for (int corner = 0; corner < 8; ++corner)
            for (int a = 0; a < 3; ++a) v.push_back(corner & (1 << a) ? hi[a] : lo[a]);
        const uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
        std::vector<uint32_t> indices;
        for (const auto& f : faces) indices.insert(indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
        Material m;
        m.albedo = {0.6f, 0.6f, 0.6f};
        scene.add_mesh(v.data(), 8, indices.data(), 12, {m}, nullptr);
        LightDescription light = mixed_point(0.5f, 1.5f, 0.2f);
        light.mode = mode;
        light.intensity = 5;
        scene.add_light(light);
        return scene;
    };
    const std::vector<float> probes = {0, 0, 0, 1, 0.5f, -1, -1, 1, 1};
    BakeSettings settings;
    settings.rays = 32;
    settings.bounces = 1;
    settings.seed = 3;
    settings.threads = 1;
    const std::vector<float> mixed = bake_lighting(scene_with(LightMode::mixed), probes, settings);
    const std::vector<float> realtime = bake_lighting(scene_with(LightMode::realtime), probes, settings);
    const std::vector<float> baked = bake_lighting(scene_with(LightMode::baked), probes, settings);
    REQUIRE(mixed == realtime);
    CHECK(mixed != baked);
    CHECK(mixed[0] > 0);  // bounced light

    Scene scene;
    for (int l = 0; l < 4; ++l) scene.add_light(mixed_point(float(l), 0, 0));
    try {
        scene.add_light(mixed_point(5, 0, 0));
        FAIL("a fifth mixed light was accepted");
    } catch (const Error& e) {
        CHECK(e.status() == Status::scene);
        CHECK(std::string(e.what()).find("fifth mixed light") != std::string::npos);
    }
    LightDescription baked_light = mixed_point(5, 0, 0);
    baked_light.mode = LightMode::baked;
    CHECK(scene.add_light(baked_light) == 4);  // other modes are still welcome
}

TEST_CASE("occlusion: the same bytes on 1, 2 and 3 threads", "[occlusion][threads]") {
    Scene scene;
    add_wall(scene);
    const double centre[3] = {-1.0, 0.3, 0.2};
    add_sphere(scene, centre, 0.5);
    scene.add_light(mixed_directional(1, 0, 0));
    scene.add_light(mixed_point(-3, 0.2f, 0.1f));
    const std::vector<float> probes = lattice(9, -2.0f, 2.0f, 0.05f);
    std::vector<std::vector<uint8_t>> results;
    for (uint32_t threads : {1u, 2u, 3u}) {
        BakeSettings settings;
        settings.threads = threads;
        results.push_back(bake_occlusion(scene, probes, settings, nullptr));
    }
    // Some probes are shadowed and some are not, so equal bytes say something.
    CHECK(std::count(results[0].begin(), results[0].end(), uint8_t(0)) > 0);
    CHECK(std::count(results[0].begin(), results[0].end(), uint8_t(255)) > 0);
    CHECK(results[1] == results[0]);
    CHECK(results[2] == results[0]);
}
