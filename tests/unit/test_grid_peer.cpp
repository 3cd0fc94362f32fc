// The benchmark's uniform-grid peer (samples/bench/grid_peer): trilinear interpolation reproduces a linear
// field, clamps outside the grid, handles a flat axis, and the grid sizing respects its probe budget.
#include "grid_peer.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using bench::GridPeer;

namespace {

// Coefficient i of a linear field with small integer slopes: exact in half at integer positions.
float linear_field(int i, const float p[3]) {
    return float((i % 3) - 1) * p[0] + float((i % 5) - 2) * p[1] + float((i % 4) - 1) * p[2] + float(i);
}

std::vector<float> field_at(const std::vector<float>& positions) {
    std::vector<float> sh;
    for (size_t p = 0; p < positions.size() / 3; ++p)
        for (int i = 0; i < 27; ++i) sh.push_back(linear_field(i, &positions[3 * p]));
    return sh;
}

}  // namespace

TEST_CASE("trilinear interpolation on the grid reproduces a linear field", "[grid_peer]") {
    const float lo[3] = {0, 1, -2}, hi[3] = {3, 3, 2};
    const int dims[3] = {4, 3, 5};  // unit spacing: every node value is an integer, exact in half
    GridPeer grid(lo, hi, dims);
    REQUIRE(grid.probe_count() == 60);
    grid.set_sh(field_at(grid.positions()));
    std::mt19937 rng(5);
    for (int trial = 0; trial < 500; ++trial) {
        float p[3], sh[27];
        for (int k = 0; k < 3; ++k) p[k] = std::uniform_real_distribution<float>(lo[k], hi[k])(rng);
        grid.interpolate(p, sh);
        for (int i = 0; i < 27; ++i) REQUIRE(sh[i] == Approx(linear_field(i, p)).margin(1e-4));
    }
}

TEST_CASE("the grid answers a node with that node's SH and clamps points outside onto the grid", "[grid_peer]") {
    const float lo[3] = {0, 0, 0}, hi[3] = {2, 2, 2};
    const int dims[3] = {3, 3, 3};
    GridPeer grid(lo, hi, dims);
    const std::vector<float> nodes = grid.positions();
    grid.set_sh(field_at(nodes));
    float sh[27];
    for (size_t n = 0; n < nodes.size() / 3; ++n) {
        grid.interpolate(&nodes[3 * n], sh);
        for (int i = 0; i < 27; ++i) REQUIRE(sh[i] == linear_field(i, &nodes[3 * n]));
    }
    const float outside[3] = {-5, 1, 9}, clamped[3] = {0, 1, 2};
    grid.interpolate(outside, sh);
    for (int i = 0; i < 27; ++i) REQUIRE(sh[i] == linear_field(i, clamped));
}

TEST_CASE("a grid over a flat probe layer is bilinear and constant across the layer", "[grid_peer]") {
    const float lo[3] = {0, 1, 0}, hi[3] = {4, 1, 2};
    int dims[3];
    bench::grid_dims_for_count(lo, hi, 15, dims);
    REQUIRE(dims[1] == 1);
    REQUIRE(dims[0] * dims[1] * dims[2] <= 15);
    const int unit[3] = {5, 1, 3};
    GridPeer grid(lo, hi, unit);
    grid.set_sh(field_at(grid.positions()));
    const float above[3] = {1.5f, 7.0f, 0.25f}, on_layer[3] = {1.5f, 1.0f, 0.25f};
    float a[27];
    grid.interpolate(above, a);
    for (int i = 0; i < 27; ++i) REQUIRE(a[i] == Approx(linear_field(i, on_layer)).margin(1e-4));
}

TEST_CASE("grid sizing stays within the budget and grows with it", "[grid_peer]") {
    const float lo[3] = {0.5f, 0.5f, 0.5f}, hi[3] = {7.7f, 2.5f, 3.5f};
    size_t previous = 0;
    for (size_t budget : {1, 8, 27, 94, 288, 1000}) {
        int dims[3];
        bench::grid_dims_for_count(lo, hi, budget, dims);
        const size_t count = size_t(dims[0]) * dims[1] * dims[2];
        REQUIRE(count <= budget);
        REQUIRE(count >= previous);
        previous = count;
    }
    REQUIRE(previous > 500);  // a budget of 1000 is mostly used
    // The common spacing alone fits 8 x 2 x 3 = 48 of 94 here; refining the widest axes uses most of it.
    int dims[3];
    bench::grid_dims_for_count(lo, hi, 94, dims);
    REQUIRE(size_t(dims[0]) * dims[1] * dims[2] >= 80);
    REQUIRE(size_t(dims[0]) * dims[1] * dims[2] <= 94);
}
