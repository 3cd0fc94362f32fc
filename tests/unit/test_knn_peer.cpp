// The benchmark's K-nearest peer (samples/bench/knn_peer): the bucket search finds exactly the nearest
// probes, a query at a probe returns that probe, inverse distance weights keep a constant field, and the
// temporal damping converges to the undamped value on a still object.
#include "knn_peer.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

using bench::KnnPeer;
using bench::TemporalDamping;

namespace {

std::vector<float> random_positions(size_t n, uint32_t seed, bool flat) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 10);
    std::vector<float> p;
    for (size_t i = 0; i < n; ++i) p.insert(p.end(), {u(rng), flat ? 1.0f : u(rng), u(rng)});
    return p;
}

// Small integers: exact in half.
std::vector<float> integer_sh(size_t n) {
    std::vector<float> sh(27 * n);
    for (size_t i = 0; i < sh.size(); ++i) sh[i] = float(int(i % 97) - 40);
    return sh;
}

}  // namespace

TEST_CASE("the bucket search returns the same nearest probes as a brute-force search", "[knn_peer]") {
    for (bool flat : {false, true}) {
        const std::vector<float> positions = random_positions(300, flat ? 3 : 4, flat);
        const KnnPeer knn(positions, integer_sh(300));
        std::mt19937 rng(9);
        std::uniform_real_distribution<float> u(-3, 13);  // inside and outside the probes' box
        for (int trial = 0; trial < 300; ++trial) {
            const float q[3] = {u(rng), u(rng), u(rng)};
            std::vector<float> d2(300);
            for (size_t p = 0; p < 300; ++p) {
                float s = 0;
                for (int k = 0; k < 3; ++k) s += (positions[3 * p + k] - q[k]) * (positions[3 * p + k] - q[k]);
                d2[p] = s;
            }
            std::vector<float> sorted = d2;
            std::sort(sorted.begin(), sorted.end());
            uint32_t probes[4];
            float distances[4];
            REQUIRE(knn.nearest(q, probes, distances) == 4);
            for (int i = 0; i < 4; ++i) {
                REQUIRE(d2[probes[i]] == sorted[i]);  // same float arithmetic: the same squared distances
                REQUIRE(distances[i] == std::sqrt(sorted[i]));
            }
        }
    }
}

TEST_CASE("a query at a probe returns that probe's SH exactly", "[knn_peer]") {
    const std::vector<float> positions = random_positions(50, 7, false);
    const std::vector<float> sh = integer_sh(50);
    const KnnPeer knn(positions, sh);
    for (size_t p = 0; p < 50; ++p) {
        float out[27];
        knn.interpolate(&positions[3 * p], out);
        for (int i = 0; i < 27; ++i) REQUIRE(out[i] == sh[27 * p + i]);
    }
}

TEST_CASE("inverse distance weights keep a constant field and stay between the neighbours' values", "[knn_peer]") {
    const std::vector<float> positions = random_positions(80, 11, false);
    std::vector<float> constant(27 * 80, 3.0f), ramp(27 * 80);
    for (size_t p = 0; p < 80; ++p)
        for (int i = 0; i < 27; ++i) ramp[27 * p + i] = float(p);
    const KnnPeer flat_field(positions, constant), ramp_field(positions, ramp);
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(0, 10);
    for (int trial = 0; trial < 200; ++trial) {
        const float q[3] = {u(rng), u(rng), u(rng)};
        float out[27];
        flat_field.interpolate(q, out);
        for (float v : out) REQUIRE(v == Approx(3.0f).epsilon(1e-6));
        uint32_t probes[4];
        float distances[4];
        ramp_field.nearest(q, probes, distances);
        ramp_field.interpolate(q, out);
        const float lo = float(*std::min_element(probes, probes + 4)), hi = float(*std::max_element(probes, probes + 4));
        REQUIRE(out[0] >= lo * (1 - 1e-6f));
        REQUIRE(out[0] <= hi * (1 + 1e-6f));
    }
}

TEST_CASE("temporal damping passes the first frame and converges to the undamped value on a still object",
          "[knn_peer]") {
    TemporalDamping damping(6.0);
    REQUIRE(damping.alpha() == Approx(1 - std::exp(-1.0 / 6.0)));
    float start[27], still[27], out[27];
    for (int i = 0; i < 27; ++i) start[i] = float(i), still[i] = float(100 - i);
    damping.update(start, out);
    for (int i = 0; i < 27; ++i) REQUIRE(out[i] == start[i]);
    double previous_gap = INFINITY;
    for (int frame = 1; frame <= 300; ++frame) {
        damping.update(still, out);
        const double gap = std::fabs(double(out[0]) - still[0]);
        REQUIRE(gap <= previous_gap);
        if (frame == 6) REQUIRE(gap == Approx(100.0 * std::exp(-1.0)).epsilon(1e-4));  // one time constant
        previous_gap = gap;
    }
    for (int i = 0; i < 27; ++i) REQUIRE(out[i] == Approx(still[i]).margin(1e-4));
    damping.reset();
    damping.update(start, out);
    for (int i = 0; i < 27; ++i) REQUIRE(out[i] == start[i]);
}
