#include "bake/outer_cells.h"

#include "core/error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace tetprobe {

namespace {

using Row = Eigen::Vector4d;  // xyz . p + w

Row affine_row(const Eigen::Vector3d& xyz, double w) { return Row(xyz.x(), xyz.y(), xyz.z(), w); }

// f(t) = ((P1(t)-P0(t)) x (P2(t)-P0(t))) . (p - P0(t)) with P_k(t) = P_k + t N_k: cubic in t, affine in p.
std::array<Row, 4> polynomial_rows_3d(const Eigen::Vector3d P[3], const Eigen::Vector3d N[3]) {
    const Eigen::Vector3d A = P[1] - P[0], B = P[2] - P[0];
    const Eigen::Vector3d dA = N[1] - N[0], dB = N[2] - N[0];
    const Eigen::Vector3d C0 = A.cross(B);
    const Eigen::Vector3d C1 = A.cross(dB) + dA.cross(B);
    const Eigen::Vector3d C2 = dA.cross(dB);
    return {affine_row(Eigen::Vector3d::Zero(), -C2.dot(N[0])),
            affine_row(C2, -C2.dot(P[0]) - C1.dot(N[0])),
            affine_row(C1, -C1.dot(P[0]) - C0.dot(N[0])),
            affine_row(C0, -C0.dot(P[0]))};
}

// f(t) = det[P1(t)-P0(t), p-P0(t), n]: quadratic in t, blind to p's offset along the plane normal n.
std::array<Row, 4> polynomial_rows_2d(const Eigen::Vector3d P[2], const Eigen::Vector3d N[2],
                                      const Eigen::Vector3d& n) {
    const Eigen::Vector3d A = P[1] - P[0], dA = N[1] - N[0];
    const Eigen::Vector3d nA = n.cross(A), ndA = n.cross(dA);
    return {affine_row(Eigen::Vector3d::Zero(), 0.0),
            affine_row(Eigen::Vector3d::Zero(), -dA.cross(N[0]).dot(n)),
            affine_row(ndA, -ndA.dot(P[0]) - A.cross(N[0]).dot(n)),
            affine_row(nA, -nA.dot(P[0]))};
}

uint64_t edge_key(uint32_t a, uint32_t b) {
    if (a > b) std::swap(a, b);
    return (uint64_t(a) << 32) | b;
}

}  // namespace

OuterCells build_outer_cells(SimplexMesh& inner, const Hull& hull, const std::vector<Eigen::Vector3d>& positions,
                             const std::vector<Eigen::Vector3d>& normals, const Eigen::Vector3d& plane_normal) {
    OuterCells outer;
    const uint32_t d = inner.dimension;
    const uint32_t first = uint32_t(inner.cell_count());
    const size_t count = hull.facets.size();
    outer.vertices.resize(count, kNoSlots);
    outer.neighbours.resize(count, kNoSlots);
    outer.matrices.resize(count);

    for (size_t i = 0; i < count; ++i) {
        const HullFacet& facet = hull.facets[i];
        for (uint32_t k = 0; k < d; ++k) outer.vertices[i][k] = facet.probes[k];
        outer.vertices[i][d] = kOuter32;
        outer.neighbours[i][d] = facet.inner_cell;
        inner.neighbours[facet.inner_cell][facet.inner_slot] = first + uint32_t(i);

        std::array<Row, 4> rows;
        if (d == 3) {
            // Rows relative to the slot-0 probe (store_format.h).
            const Eigen::Vector3d& origin = positions[facet.probes[0]];
            const Eigen::Vector3d P[3] = {Eigen::Vector3d::Zero(), positions[facet.probes[1]] - origin,
                                          positions[facet.probes[2]] - origin};
            const Eigen::Vector3d N[3] = {normals[facet.probes[0]], normals[facet.probes[1]], normals[facet.probes[2]]};
            rows = polynomial_rows_3d(P, N);
        } else if (d == 2) {
            const Eigen::Vector3d P[2] = {Eigen::Vector3d::Zero(), positions[facet.probes[1]] - positions[facet.probes[0]]};
            const Eigen::Vector3d N[2] = {normals[facet.probes[0]], normals[facet.probes[1]]};
            rows = polynomial_rows_2d(P, N, plane_normal);
        } else {
            const Eigen::Vector3d& N = normals[facet.probes[0]];
            rows = {Row::Zero(), Row::Zero(), Row::Zero(), affine_row(N, 0.0)};
        }
        // One positive factor for all rows: the largest coefficient becomes 1, which keeps every
        // coefficient within float range at any scale of the set (1D rows are already unit).
        double scale = 0;
        for (const Row& row : rows) scale = std::max(scale, row.cwiseAbs().maxCoeff());
        if (!(scale > 0) || !std::isfinite(scale)) throw Error(TP_ERROR_INTERNAL, "degenerate hull facet");
        if (d == 1) scale = 1;
        for (int r = 0; r < 4; ++r) {
            for (int c = 0; c < 4; ++c) outer.matrices[i][size_t(r * 4 + c)] = rows[size_t(r)][c] / scale;
        }
    }

    // Neighbours across the rays: two outer cells are adjacent where their facets share d-1 probes.
    if (d == 3) {
        std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> edges;  // edge -> (cell, slot) seen first
        edges.reserve(count * 2);
        for (uint32_t i = 0; i < count; ++i) {
            for (uint32_t k = 0; k < 3; ++k) {
                const uint64_t key = edge_key(outer.vertices[i][(k + 1) % 3], outer.vertices[i][(k + 2) % 3]);
                auto it = edges.find(key);
                if (it == edges.end()) {
                    edges.emplace(key, std::make_pair(i, k));
                } else {
                    outer.neighbours[i][k] = first + it->second.first;
                    outer.neighbours[it->second.first][it->second.second] = first + i;
                }
            }
        }
    } else if (d == 2) {
        std::unordered_map<uint32_t, std::pair<uint32_t, uint32_t>> ends;  // probe -> (cell, slot) seen first
        ends.reserve(count);
        for (uint32_t i = 0; i < count; ++i) {
            for (uint32_t k = 0; k < 2; ++k) {
                const uint32_t shared = outer.vertices[i][1 - k];
                auto it = ends.find(shared);
                if (it == ends.end()) {
                    ends.emplace(shared, std::make_pair(i, k));
                } else {
                    outer.neighbours[i][k] = first + it->second.first;
                    outer.neighbours[it->second.first][it->second.second] = first + i;
                }
            }
        }
    }
    for (uint32_t i = 0; i < count; ++i) {
        for (uint32_t k = 0; k < d && d >= 2; ++k) {
            if (outer.neighbours[i][k] == kNone32) throw Error(TP_ERROR_INTERNAL, "hull is not closed");
        }
    }
    return outer;
}

}  // namespace tetprobe
