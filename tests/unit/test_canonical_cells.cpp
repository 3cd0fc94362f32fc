// Canonical cells (core/canonical_cells.h): every slot order of a cell, with its neighbours, gives
// one canonical form; it is positively oriented (exactly) for a non-flat cell, increasing up to the
// first two slots, and keeps each neighbour at the slot of the vertex it is opposite.
#include "core/canonical_cells.h"
#include "core/orientation.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using namespace tetprobe;

TEST_CASE("canonical cells: every slot order gives one positive, increasing form", "[canonical_cells]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    for (uint32_t dimension : {1u, 2u, 3u}) {
        for (int trial = 0; trial < 300; ++trial) {
            std::vector<float> positions(3 * 20);
            for (float& x : positions) x = u(rng);
            // A cell of distinct probes, each slot's neighbour named after its vertex.
            std::vector<uint32_t> probes(20);
            for (uint32_t i = 0; i < 20; ++i) probes[i] = i;
            std::shuffle(probes.begin(), probes.end(), rng);
            CellSlots v = kNoSlots, n = kNoSlots;
            for (uint32_t k = 0; k <= dimension; ++k) {
                v[k] = probes[k];
                n[k] = 1000 + probes[k];
            }
            const uint32_t axis = dimension == 3 ? 0 : uint32_t(trial % 3);
            const int orientation = cell_orientation(v, dimension, axis, positions.data());
            REQUIRE(orientation != 0);
            CellSlots expected_v = v, expected_n = n;
            canonicalise_cell(expected_v, expected_n, dimension, orientation);
            REQUIRE(cell_orientation(expected_v, dimension, axis, positions.data()) > 0);
            for (uint32_t k = 2; k <= dimension; ++k) REQUIRE(expected_v[k - 1] < expected_v[k]);
            REQUIRE(std::max(expected_v[0], expected_v[1]) < (dimension >= 2 ? expected_v[2] : kNone32));
            for (uint32_t k = 0; k <= dimension; ++k) REQUIRE(expected_n[k] == 1000 + expected_v[k]);
            // Any permutation of the slots (neighbours alongside) gives the same form.
            std::array<uint32_t, 4> slots = {0, 1, 2, 3};
            do {
                CellSlots w = kNoSlots, m = kNoSlots;
                for (uint32_t k = 0; k <= dimension; ++k) {
                    w[k] = v[slots[k]];
                    m[k] = n[slots[k]];
                }
                canonicalise_cell(w, m, dimension, cell_orientation(w, dimension, axis, positions.data()));
                REQUIRE(w == expected_v);
                REQUIRE(m == expected_n);
            } while (std::next_permutation(slots.begin(), slots.begin() + dimension + 1));
        }
    }
}

TEST_CASE("canonical cells: a flat cell keeps increasing slots; a mesh reports how many it has", "[canonical_cells]") {
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1};
    SimplexMesh mesh;
    mesh.dimension = 3;
    mesh.add_cell({3, 1, 0, 2}, {7, 8, 9, 10});  // four coplanar probes
    mesh.add_cell({4, 1, 0, 2}, {11, 12, 13, 14});
    REQUIRE(canonicalise_cells(mesh, positions.data(), 0) == 1);
    REQUIRE(mesh.vertices[0] == CellSlots{0, 1, 2, 3});
    REQUIRE(mesh.neighbours[0] == CellSlots{9, 8, 10, 7});
    REQUIRE(orient3d(&positions[3 * mesh.vertices[1][0]], &positions[3 * mesh.vertices[1][1]], &positions[3 * mesh.vertices[1][2]],
                     &positions[3 * mesh.vertices[1][3]]) > 0);
}
