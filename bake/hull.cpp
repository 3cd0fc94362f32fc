#include "bake/hull.h"

#include "core/error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

namespace tetprobe {

namespace {

// A facet whose 2 area / longest edge^2 is below this (an equilateral one has 0.87) is a sliver: it
// counts in the vertex normals in proportion to that shape, and takes its flat region's direction.
constexpr double kSliverShape = 0.05;

// Neighbouring facets whose normals differ by less than this (radians) belong to one flat region.
constexpr double kFlatRegionAngle = 1e-4;

// 2 area / longest edge^2 of triangle (a, b, c): 0.87 equilateral, 0 degenerate.
double facet_shape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double area2 = (b - a).cross(c - a).norm();
    return longest2 > 0 ? area2 / longest2 : 0.0;
}

// Per hull facet, the normal of the flat region it lies in: facets joined across edges while their
// normals differ by less than kFlatRegionAngle (slivers, whose own direction is rounding noise, join
// the region of a neighbour), each region's normal the area-weighted mean of its facets'. A side of
// the hull that is flat up to rounding (a rotated lattice's, rounded to float) thus gives all its
// probes exactly the same normal, so that its outer cells sweep straight out and never turn over.
std::vector<Eigen::Vector3d> flat_region_normals(const Hull& hull, const std::vector<Eigen::Vector3d>& p) {
    const size_t n = hull.facets.size();
    std::vector<Eigen::Vector3d> area_normal(n);
    std::vector<bool> sliver(n);
    std::vector<std::pair<uint64_t, uint32_t>> edges;  // (sorted probe pair, facet)
    edges.reserve(3 * n);
    for (uint32_t i = 0; i < n; ++i) {
        const auto& v = hull.facets[i].probes;
        area_normal[i] = (p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]);
        sliver[i] = !(facet_shape(p[v[0]], p[v[1]], p[v[2]]) >= kSliverShape);
        for (int k = 0; k < 3; ++k) {
            const uint64_t a = v[size_t(k)], b = v[size_t((k + 1) % 3)];
            edges.push_back({a < b ? (a << 32 | b) : (b << 32 | a), i});
        }
    }
    std::sort(edges.begin(), edges.end());
    std::vector<std::vector<uint32_t>> across(n);
    for (size_t e = 0; e + 1 < edges.size(); ++e) {
        if (edges[e].first != edges[e + 1].first) continue;
        across[edges[e].second].push_back(edges[e + 1].second);
        across[edges[e + 1].second].push_back(edges[e].second);
    }
    auto unit = [&](uint32_t i) { return area_normal[i].normalized(); };
    std::vector<int64_t> region(n, -1);
    std::vector<Eigen::Vector3d> sums;
    // Regions grow from well-shaped facets, then slivers join a neighbouring region (repeatedly, so
    // that a run of slivers joins too); a sliver with no region beside it keeps its own normal.
    for (uint32_t seed = 0; seed < n; ++seed) {
        if (region[seed] >= 0 || sliver[seed]) continue;
        const int64_t id = int64_t(sums.size());
        sums.push_back(Eigen::Vector3d::Zero());
        std::vector<uint32_t> stack{seed};
        region[seed] = id;
        while (!stack.empty()) {
            const uint32_t i = stack.back();
            stack.pop_back();
            sums[size_t(id)] += area_normal[i];
            for (uint32_t j : across[i]) {
                if (region[j] >= 0 || sliver[j]) continue;
                if (!(unit(i).dot(unit(j)) >= std::cos(kFlatRegionAngle))) continue;
                region[j] = id;
                stack.push_back(j);
            }
        }
    }
    for (bool joined = true; joined;) {
        joined = false;
        for (uint32_t i = 0; i < n; ++i) {
            if (region[i] >= 0) continue;
            for (uint32_t j : across[i]) {
                if (region[j] < 0) continue;
                region[i] = region[j];
                joined = true;
                break;
            }
        }
    }
    std::vector<Eigen::Vector3d> normals(n);
    for (uint32_t i = 0; i < n; ++i) {
        const Eigen::Vector3d own = area_normal[i].norm() > 0 ? unit(i) : Eigen::Vector3d::Zero();
        normals[i] = region[i] >= 0 ? sums[size_t(region[i])].normalized() : own;
        // A facet whose region faces away from it (only a badly misled sliver) keeps its own.
        if (!(normals[i].dot(area_normal[i]) > 0)) normals[i] = own;
    }
    return normals;
}

// Angle at corner a of triangle (a, b, c).
double corner_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d u = b - a, v = c - a;
    return std::atan2(u.cross(v).norm(), u.dot(v));
}

void add_facets_3d(const SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& p, Hull& hull) {
    // The facet opposite slot k, ordered so that orient3d(facet, v[k]) = -orient3d(v0, v1, v2, v3):
    // outward for a positively oriented cell, with no arithmetic (a flat cell's facet included).
    static const int kOthers[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    for (uint32_t c = 0; c < mesh.cell_count(); ++c) {
        for (uint32_t k = 0; k < 4; ++k) {
            if (mesh.neighbours[c][k] != kNone32) continue;
            const CellSlots& v = mesh.vertices[c];
            const uint32_t a = v[size_t(kOthers[k][0])], b = v[size_t(kOthers[k][1])], d = v[size_t(kOthers[k][2])];
            HullFacet facet;
            facet.probes = {a, b, d, kNone32};
            facet.inner_cell = c;
            facet.inner_slot = k;
            hull.facets.push_back(facet);
        }
    }
    // Angle-weighted means of the facets' flat-region normals (see flat_region_normals), with
    // slivers weighted down by their shape: a sliver's middle corner is nearly a straight angle.
    const std::vector<Eigen::Vector3d> region = flat_region_normals(hull, p);
    for (size_t i = 0; i < hull.facets.size(); ++i) {
        const HullFacet& f = hull.facets[i];
        const uint32_t a = f.probes[0], b = f.probes[1], d = f.probes[2];
        const double shape = facet_shape(p[a], p[b], p[d]);
        if (!(shape > 0)) continue;  // a zero-area facet has no direction to contribute
        const double weight = std::min(1.0, shape / kSliverShape);
        hull.vertex_normals[a] += weight * corner_angle(p[a], p[b], p[d]) * region[i];
        hull.vertex_normals[b] += weight * corner_angle(p[b], p[d], p[a]) * region[i];
        hull.vertex_normals[d] += weight * corner_angle(p[d], p[a], p[b]) * region[i];
    }
}

void add_facets_2d(const SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& p, const SetShape& shape,
                   Hull& hull) {
    const Eigen::Vector3d& n = shape.axes.col(2);
    for (uint32_t c = 0; c < mesh.cell_count(); ++c) {
        for (uint32_t k = 0; k < 3; ++k) {
            if (mesh.neighbours[c][k] != kNone32) continue;
            const CellSlots& v = mesh.vertices[c];
            // orient2d(v[k+1], v[k+2], v[k]) = orient2d(v0, v1, v2) > 0, so the reverse edge has the
            // cell on its negative side: outward winding with no arithmetic.
            const uint32_t a = v[(k + 2) % 3], b = v[(k + 1) % 3];
            HullFacet facet;
            facet.probes = {a, b, kNone32, kNone32};
            facet.inner_cell = c;
            facet.inner_slot = k;
            hull.facets.push_back(facet);
            // In-plane normal of the edge, turned to the positive (left) side of a -> b in (u, v).
            Eigen::Vector3d outward = n.cross(p[b] - p[a]).normalized();
            const Eigen::Vector2d e = shape.plane_coordinates(p[b]) - shape.plane_coordinates(p[a]);
            const Eigen::Vector2d w = shape.plane_coordinates(outward);
            if (-e.y() * w.x() + e.x() * w.y() < 0) outward = -outward;
            hull.vertex_normals[a] += outward;
            hull.vertex_normals[b] += outward;
        }
    }
}

void add_facets_1d(const SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& u,
                   Hull& hull) {
    for (uint32_t c = 0; c < mesh.cell_count(); ++c) {
        for (uint32_t k = 0; k < 2; ++k) {
            if (mesh.neighbours[c][k] != kNone32) continue;
            const uint32_t end = mesh.vertices[c][1 - k], inner = mesh.vertices[c][k];
            HullFacet facet;
            facet.probes = {end, kNone32, kNone32, kNone32};
            facet.inner_cell = c;
            facet.inner_slot = k;
            hull.facets.push_back(facet);
            hull.vertex_normals[end] = (p[end] - p[inner]).dot(u) > 0 ? u : Eigen::Vector3d(-u);
        }
    }
}

// How far out, in set diagonals, every outer cell keeps its orientation. Without a bound no float
// normals would do: across nearly coplanar facets (a jittered lattice's sides) the true divergence
// of the normals is as small as their rounding, so far enough out some moved facet turns over.
constexpr double kOuterCellReach = 1e5;

// Whether facet f, moved out along its vertex normals as stored (float) to any t in [0, reach],
// keeps its orientation: (e1 + t d1) x (e2 + t d2) . facet normal = A + B t + C t^2 stays positive,
// so that its outer cell does not fold over its neighbours there.
bool facet_keeps_orientation(const Hull& hull, const HullFacet& f, const std::vector<Eigen::Vector3d>& p,
                             double reach) {
    auto normal = [&](int k) {
        return Eigen::Vector3d(hull.vertex_normals[f.probes[size_t(k)]].cast<float>().cast<double>());
    };
    const Eigen::Vector3d e1 = p[f.probes[1]] - p[f.probes[0]], e2 = p[f.probes[2]] - p[f.probes[0]];
    const Eigen::Vector3d d1 = normal(1) - normal(0), d2 = normal(2) - normal(0);
    const Eigen::Vector3d facet = e1.cross(e2);
    const double area = facet.norm();
    // A zero-area facet has no orientation of its own; its normals' triangle must not be mirrored.
    if (!(area > 0)) return normal(0).dot(normal(1).cross(normal(2))) > 0;
    const Eigen::Vector3d unit = facet / area;
    const double b = unit.dot(e1.cross(d2) + d1.cross(e2)), c = unit.dot(d1.cross(d2));
    auto g = [&](double t) { return area + t * (b + t * c); };
    if (!(g(reach) > 0)) return false;
    const double lowest = c > 0 ? -b / (2 * c) : 0;
    return !(lowest > 0 && lowest < reach) || g(lowest) > 0;
}

// Averaged normals can mirror the normal triangle of a skinny facet next to a nearly coplanar one;
// out there, the outer cells of such facets then fold over their neighbours (a point on a hull
// probe's ray lands in a cell that does not hold the probe). Where that happens, the normals of the
// facet's probes are relaxed towards the mean of their hull neighbours' normals (a spherical
// Laplacian step, which untangles the normal mesh), keeping every ray outward of its own facets.
void untangle_vertex_normals(Hull& hull, const std::vector<Eigen::Vector3d>& p) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
    for (const Eigen::Vector3d& q : p) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    const double reach = kOuterCellReach * (hi - lo).norm();
    std::vector<std::vector<uint32_t>> ring(p.size()), facets_at(p.size());
    for (uint32_t i = 0; i < hull.facets.size(); ++i) {
        const HullFacet& f = hull.facets[i];
        for (int k = 0; k < 3; ++k) {
            ring[f.probes[size_t(k)]].push_back(f.probes[size_t((k + 1) % 3)]);
            facets_at[f.probes[size_t(k)]].push_back(i);
        }
    }
    auto outward = [&](uint32_t v, const Eigen::Vector3d& n) {
        for (uint32_t i : facets_at[v]) {
            const HullFacet& f = hull.facets[i];
            const Eigen::Vector3d facet_normal =
                (p[f.probes[1]] - p[f.probes[0]]).cross(p[f.probes[2]] - p[f.probes[0]]);
            if (!(facet_normal.dot(n) > 0)) return false;
        }
        return true;
    };
    for (int round = 0; round < 64; ++round) {
        std::vector<uint32_t> tangled;
        for (const HullFacet& f : hull.facets) {
            if (facet_keeps_orientation(hull, f, p, reach)) continue;
            tangled.insert(tangled.end(), f.probes.begin(), f.probes.begin() + 3);
        }
        if (tangled.empty()) return;
        std::sort(tangled.begin(), tangled.end());
        tangled.erase(std::unique(tangled.begin(), tangled.end()), tangled.end());
        for (uint32_t v : tangled) {
            Eigen::Vector3d mean = Eigen::Vector3d::Zero();
            for (uint32_t u : ring[v]) mean += hull.vertex_normals[u];
            const Eigen::Vector3d current = hull.vertex_normals[v];
            // Step halfway; halve again while a ray would point into one of the probe's own facets.
            for (double step = 0.5; step > 1e-3; step *= 0.5) {
                const Eigen::Vector3d candidate = ((1 - step) * current + step * mean.normalized()).normalized();
                if (candidate.allFinite() && outward(v, candidate)) {
                    hull.vertex_normals[v] = candidate;
                    break;
                }
            }
        }
    }
}

}  // namespace

Hull find_hull(const SimplexMesh& mesh, const std::vector<Eigen::Vector3d>& positions, const SetShape& shape) {
    Hull hull;
    hull.vertex_normals.assign(positions.size(), Eigen::Vector3d::Zero());
    switch (mesh.dimension) {
        case 3: add_facets_3d(mesh, positions, hull); break;
        case 2: add_facets_2d(mesh, positions, shape, hull); break;
        case 1: add_facets_1d(mesh, positions, shape.axes.col(0), hull); break;
        default: return hull;
    }
    for (auto& normal : hull.vertex_normals) {
        const double length = normal.norm();
        if (length > 0) normal /= length;
    }
    if (mesh.dimension == 3) untangle_vertex_normals(hull, positions);
    return hull;
}

}  // namespace tetprobe
