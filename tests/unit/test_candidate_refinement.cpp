// Refinement's pairs: neighbours whose light differs beyond its noise, the largest difference first.
#include <catch2/catch.hpp>

#include "bake/candidate_refinement.h"

#include <vector>

using namespace tetprobe;

namespace {

// Candidates a spacing apart along x, each with the same value for all normals.
PointSignal line_signal(const std::vector<double>& values, double noise) {
    PointSignal s;
    for (double v : values) {
        for (int k = 0; k < kSignalSize; ++k) s.value.push_back(float(v));
        s.noise.push_back(float(noise));
    }
    return s;
}

std::vector<float> line(size_t n, double gap) {
    std::vector<float> p;
    for (size_t i = 0; i < n; ++i) p.insert(p.end(), {float(gap * double(i)), 1.0f, 0.0f});
    return p;
}

}  // namespace

TEST_CASE("refinement: only a change far beyond the noise makes a pair, the largest first", "[placement]") {
    // A step of 4 between the 3rd and 4th, of 1 between the 5th and 6th: 6 x 16 and 6 x 1 squared.
    const std::vector<float> p = line(6, 1.0);
    const PointSignal quiet = line_signal({1, 1, 1, 5, 5, 6}, 0.01);
    ChangingPairs pairs = changing_pairs(p, quiet, 1.0, 10);
    REQUIRE(pairs.a.size() == 6);
    CHECK(pairs.a[0] == 2.0f);
    CHECK(pairs.b[0] == 3.0f);
    CHECK(pairs.a[3] == 4.0f);
    CHECK(pairs.b[3] == 5.0f);
    pairs = changing_pairs(p, quiet, 1.0, 1);  // the limit keeps the largest
    REQUIRE(pairs.a.size() == 3);
    CHECK(pairs.a[0] == 2.0f);
    // Noise variance 0.5 per point: the small step (6 < 16 x 1) is noise, the large one (96) is not.
    pairs = changing_pairs(p, line_signal({1, 1, 1, 5, 5, 6}, 0.5), 1.0, 10);
    REQUIRE(pairs.a.size() == 3);
    CHECK(pairs.a[0] == 2.0f);
    // Noise variance 4 per point: no step stands out (96 < 16 x 8).
    CHECK(changing_pairs(p, line_signal({1, 1, 1, 5, 5, 6}, 4.0), 1.0, 10).a.empty());
    // Candidates 2 spacings apart are no neighbours.
    CHECK(changing_pairs(line(6, 2.0), quiet, 1.0, 10).a.empty());
}
