#include "core/canonical_cells.h"

#include "core/orientation.h"

#include <utility>

namespace tetprobe {

int cell_orientation(const CellSlots& v, uint32_t dimension, uint32_t axis, const float* positions) {
    auto p = [&](uint32_t slot) { return positions + size_t(v[slot]) * 3; };
    switch (dimension) {
        case 3: return orient3d(p(0), p(1), p(2), p(3));
        case 2: {
            const uint32_t u = axis == 0 ? 1 : 0, w = axis == 2 ? 1 : 2;
            const float a[2] = {p(0)[u], p(0)[w]}, b[2] = {p(1)[u], p(1)[w]}, c[2] = {p(2)[u], p(2)[w]};
            return orient2d(a, b, c);
        }
        case 1: return (p(1)[axis] > p(0)[axis]) - (p(1)[axis] < p(0)[axis]);
        default: return 1;
    }
}

void canonicalise_cell(CellSlots& vertices, CellSlots& neighbours, uint32_t dimension, int orientation) {
    // A sorting network over slots 0..d (conditional moves, no data-dependent branch: a Delaunay
    // rebuild sorts every cell), tracking the permutation's parity. On local copies: the two arrays
    // may alias as far as the compiler knows, so sorting them in place went through memory at every
    // step (a fifth of a rebuild's extraction).
    uint32_t v[4] = {vertices[0], vertices[1], vertices[2], vertices[3]};
    uint32_t nb[4] = {neighbours[0], neighbours[1], neighbours[2], neighbours[3]};
    uint32_t odd = 0;
    auto order = [&](size_t i, size_t j) {
        const uint32_t a = v[i], b = v[j], m = nb[i], n = nb[j];
        const uint32_t swap = uint32_t(a > b), mask = 0u - swap;
        v[i] = a ^ ((a ^ b) & mask);
        v[j] = b ^ ((a ^ b) & mask);
        nb[i] = m ^ ((m ^ n) & mask);
        nb[j] = n ^ ((m ^ n) & mask);
        odd ^= swap;
    };
    switch (dimension) {
        case 3: order(0, 1), order(2, 3), order(0, 2), order(1, 3), order(1, 2); break;
        case 2: order(0, 1), order(1, 2), order(0, 1); break;
        case 1: order(0, 1); break;
        default: return;
    }
    // An odd sort of a positive cell (or an even one of a negative) swaps slots 0 and 1 back: no
    // branch either, since the parity is a coin toss.
    const uint32_t back = 0u - uint32_t(orientation * (odd ? -1 : 1) < 0);
    const uint32_t v01 = (v[0] ^ v[1]) & back, n01 = (nb[0] ^ nb[1]) & back;
    v[0] ^= v01, v[1] ^= v01, nb[0] ^= n01, nb[1] ^= n01;
    for (size_t k = 0; k < 4; ++k) {
        vertices[k] = v[k];
        neighbours[k] = nb[k];
    }
}

size_t canonicalise_cells(SimplexMesh& mesh, const float* positions, uint32_t axis) {
    size_t flat = 0;
    for (size_t c = 0; c < mesh.cell_count(); ++c) {
        const int orientation = cell_orientation(mesh.vertices[c], mesh.dimension, axis, positions);
        flat += orientation == 0;
        canonicalise_cell(mesh.vertices[c], mesh.neighbours[c], mesh.dimension, orientation);
    }
    return flat;
}

}  // namespace tetprobe
