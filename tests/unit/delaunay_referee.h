// The exact referee of a Delaunay tessellation under TetGen's perturbation (core/insphere.h), for the
// tests of core's triangulations and of TetGen's: every cell positively oriented, neighbours
// symmetric across shared facets, every probe used, the covered volume (area) the hull's, and every
// facet locally Delaunay: no probe across an inner facet is in conflict with the cell on the other
// side, and the hull is locally convex with coplanar neighbouring hull facets decided by the inner cell
// behind them (what a cell at infinity decides). Locally Delaunay everywhere, such a triangulation is
// the Delaunay tessellation of the perturbed points, which is unique.
#pragma once

#include "core/insphere.h"
#include "core/orientation.h"
#include "core/simplex_mesh.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace referee {

using tetprobe::CellSlots;
using tetprobe::kNone32;
using tetprobe::SimplexMesh;

// The first failure of a check, or empty when the mesh is the Delaunay tessellation.
inline std::string delaunay_failure_3d(const SimplexMesh& mesh, const float* positions, uint32_t count) {
    auto p = [&](uint32_t v) { return positions + size_t(v) * 3; };
    std::ostringstream why;
    if (mesh.dimension != 3) return "not a dimension-3 mesh";
    std::vector<char> used(count, 0);
    double volume = 0;
    for (uint32_t c = 0; c < mesh.cell_count(); ++c) {
        const CellSlots& v = mesh.vertices[c];
        for (uint32_t k = 0; k < 4; ++k) {
            if (v[k] >= count) return "cell " + std::to_string(c) + " names no probe";
            used[v[k]] = 1;
        }
        if (tetprobe::orient3d(p(v[0]), p(v[1]), p(v[2]), p(v[3])) <= 0) return "cell " + std::to_string(c) + " is not positive";
        double e[3][3];
        for (int r = 0; r < 3; ++r)
            for (int a = 0; a < 3; ++a) e[r][a] = double(p(v[r + 1])[a]) - p(v[0])[a];
        volume += (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                   e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6;
    }
    for (uint32_t i = 0; i < count; ++i)
        if (!used[i]) return "probe " + std::to_string(i) + " is in no cell";
    static const int kFacet[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    // Hull facets wound outward, keyed by their edges for the convexity checks.
    struct HullFacet {
        std::array<uint32_t, 3> probes;
        uint32_t cell;
    };
    std::vector<HullFacet> hull;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edge_facets;
    double hull_volume = 0;
    for (uint32_t c = 0; c < mesh.cell_count(); ++c) {
        const CellSlots& v = mesh.vertices[c];
        for (uint32_t k = 0; k < 4; ++k) {
            const uint32_t n = mesh.neighbours[c][k];
            if (n == kNone32) {
                HullFacet f{{v[kFacet[k][0]], v[kFacet[k][1]], v[kFacet[k][2]]}, c};
                for (int j = 0; j < 3; ++j) {
                    const uint32_t a = f.probes[j], b = f.probes[(j + 1) % 3];
                    edge_facets[{std::min(a, b), std::max(a, b)}].push_back(uint32_t(hull.size()));
                }
                const float *x = p(f.probes[0]), *y = p(f.probes[1]), *z = p(f.probes[2]);
                hull_volume += (double(x[0]) * (double(y[1]) * z[2] - double(y[2]) * z[1]) -
                                double(x[1]) * (double(y[0]) * z[2] - double(y[2]) * z[0]) +
                                double(x[2]) * (double(y[0]) * z[1] - double(y[1]) * z[0])) / 6;
                hull.push_back(f);
                continue;
            }
            if (n >= mesh.cell_count()) return "cell " + std::to_string(c) + " has a bad neighbour";
            // The neighbour shares the facet opposite k and links back; its far vertex is outside.
            uint32_t back = 4, far = kNone32;
            for (uint32_t j = 0; j < 4; ++j) {
                const uint32_t w = mesh.vertices[n][j];
                if (std::find(v.begin(), v.end(), w) == v.end()) {
                    if (far != kNone32) return "cells " + std::to_string(c) + " and " + std::to_string(n) + " share no facet";
                    far = w;
                    back = j;
                }
            }
            if (far == kNone32 || mesh.neighbours[n][back] != c) return "neighbours of cell " + std::to_string(c) + " are not symmetric";
            const float* const points[5] = {p(v[0]), p(v[1]), p(v[2]), p(v[3]), p(far)};
            const uint32_t indices[5] = {v[0], v[1], v[2], v[3], far};
            if (tetprobe::insphere_perturbed(points, indices) > 0)
                return "probe " + std::to_string(far) + " is inside the sphere of cell " + std::to_string(c);
        }
    }
    for (const auto& entry : edge_facets) {
        if (entry.second.size() != 2) return "the hull is not closed";
        for (int side = 0; side < 2; ++side) {
            const HullFacet& f = hull[entry.second[side]];
            const HullFacet& g = hull[entry.second[1 - side]];
            uint32_t y = kNone32;
            for (uint32_t w : g.probes)
                if (w != entry.first.first && w != entry.first.second) y = w;
            const int o = tetprobe::orient3d(p(f.probes[0]), p(f.probes[1]), p(f.probes[2]), p(y));
            if (o > 0) return "the hull is not convex at probe " + std::to_string(y);
            if (o == 0) {
                const CellSlots& v = mesh.vertices[f.cell];
                const float* const points[5] = {p(v[0]), p(v[1]), p(v[2]), p(v[3]), p(y)};
                const uint32_t indices[5] = {v[0], v[1], v[2], v[3], y};
                if (tetprobe::insphere_perturbed(points, indices) > 0)
                    return "coplanar hull probe " + std::to_string(y) + " is inside the sphere of cell " + std::to_string(f.cell);
            }
        }
    }
    // Locally convex and positive, the cells could still cover the hull more than once.
    if (!(std::fabs(volume - hull_volume) <= 1e-6 * std::fabs(hull_volume))) return "the cells do not tile the hull";
    return "";
}

// The 2D referee, in the plane coordinates uv (2 floats per probe).
inline std::string delaunay_failure_2d(const SimplexMesh& mesh, const float* uv, uint32_t count) {
    auto p = [&](uint32_t v) { return uv + size_t(v) * 2; };
    if (mesh.dimension != 2) return "not a dimension-2 mesh";
    std::vector<char> used(count, 0);
    double area = 0, hull_area = 0;
    std::map<uint32_t, std::vector<std::pair<uint32_t, uint32_t>>> hull_edges_at;  // probe -> (edge, cell)
    std::vector<std::array<uint32_t, 3>> hull;                                      // (a, b, cell)
    for (uint32_t c = 0; c < mesh.cell_count(); ++c) {
        const CellSlots& v = mesh.vertices[c];
        for (uint32_t k = 0; k < 3; ++k) {
            if (v[k] >= count) return "cell " + std::to_string(c) + " names no probe";
            used[v[k]] = 1;
        }
        if (tetprobe::orient2d(p(v[0]), p(v[1]), p(v[2])) <= 0) return "cell " + std::to_string(c) + " is not positive";
        area += ((double(p(v[1])[0]) - p(v[0])[0]) * (double(p(v[2])[1]) - p(v[0])[1]) -
                 (double(p(v[1])[1]) - p(v[0])[1]) * (double(p(v[2])[0]) - p(v[0])[0])) / 2;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t n = mesh.neighbours[c][k];
            if (n == kNone32) {
                const uint32_t a = v[(k + 2) % 3], b = v[(k + 1) % 3];
                hull_edges_at[a].push_back({uint32_t(hull.size()), c});
                hull_edges_at[b].push_back({uint32_t(hull.size()), c});
                // Hull edges run clockwise (the cell on their right): minus the shoelace sum.
                hull_area -= (double(p(a)[0]) * p(b)[1] - double(p(a)[1]) * p(b)[0]) / 2;
                hull.push_back({a, b, c});
                continue;
            }
            uint32_t back = 3, far = kNone32;
            for (uint32_t j = 0; j < 3; ++j) {
                const uint32_t w = mesh.vertices[n][j];
                if (w != v[0] && w != v[1] && w != v[2]) {
                    if (far != kNone32) return "cells share no edge";
                    far = w;
                    back = j;
                }
            }
            if (far == kNone32 || mesh.neighbours[n][back] != c) return "neighbours are not symmetric";
            const float* const points[4] = {p(v[0]), p(v[1]), p(v[2]), p(far)};
            const uint32_t indices[4] = {v[0], v[1], v[2], far};
            if (tetprobe::incircle_perturbed(points, indices) > 0)
                return "probe " + std::to_string(far) + " is inside the circle of cell " + std::to_string(c);
        }
    }
    for (uint32_t i = 0; i < count; ++i)
        if (!used[i]) return "probe " + std::to_string(i) + " is in no cell";
    for (const auto& entry : hull_edges_at) {
        if (entry.second.size() != 2) return "the hull is not closed";
        for (int side = 0; side < 2; ++side) {
            const auto& f = hull[entry.second[side].first];
            const auto& g = hull[entry.second[1 - side].first];
            const uint32_t y = g[0] == entry.first ? g[1] : g[0];
            const int o = tetprobe::orient2d(p(f[0]), p(f[1]), p(y));
            if (o > 0) return "the hull is not convex at probe " + std::to_string(y);
            if (o == 0) {
                const CellSlots& v = mesh.vertices[f[2]];
                const float* const points[4] = {p(v[0]), p(v[1]), p(v[2]), p(y)};
                const uint32_t indices[4] = {v[0], v[1], v[2], y};
                if (tetprobe::incircle_perturbed(points, indices) > 0)
                    return "collinear hull probe " + std::to_string(y) + " is inside the circle of cell " + std::to_string(f[2]);
            }
        }
    }
    if (!(std::fabs(area - hull_area) <= 1e-6 * std::fabs(hull_area))) return "the cells do not tile the hull";
    return "";
}

// The cells of a mesh as a sorted list (for comparing two tessellations in canonical form).
inline std::vector<CellSlots> sorted_cells(const SimplexMesh& mesh) {
    std::vector<CellSlots> cells = mesh.vertices;
    std::sort(cells.begin(), cells.end());
    return cells;
}

}  // namespace referee
