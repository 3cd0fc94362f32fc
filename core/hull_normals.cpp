#include "core/hull_normals.h"

#include "core/hull_cells.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <utility>

namespace tetprobe {

namespace {

struct Hull {
    std::vector<HullFacet> facets;
    std::vector<Eigen::Vector3d> vertex_normals;
};

// The hull facets of finished cells in stored order: each outer cell's, or without outer cells each
// inner cell's facet without neighbour.
std::vector<HullFacet> stored_hull_facets(const StoreData& data) {
    std::vector<HullFacet> facets;
    const uint32_t d = data.dimension, inner = data.inner_cell_count, cells = data.cell_count();
    if (d == 0) return facets;
    if (cells == inner) {
        for (uint32_t c = 0; c < inner; ++c)
            for (uint32_t k = 0; k <= d; ++k) {
                if (data.cell_neighbours[size_t(c) * 4 + k] != kNone32) continue;
                HullFacet facet;
                facet.probes = hull_facet_probes(&data.cell_vertices[size_t(c) * 4], k, d);
                facet.inner_cell = c;
                facet.inner_slot = k;
                facets.push_back(facet);
            }
        return facets;
    }
    // Outer cell o holds its facet's probes and rests on inner cell neighbour d, whose slot links back.
    for (uint32_t o = inner; o < cells; ++o) {
        HullFacet facet;
        for (uint32_t k = 0; k < d; ++k) facet.probes[k] = data.cell_vertices[size_t(o) * 4 + k];
        facet.inner_cell = data.cell_neighbours[size_t(o) * 4 + d];
        for (uint32_t k = 0; k <= d; ++k)
            if (data.cell_neighbours[size_t(facet.inner_cell) * 4 + k] == o) facet.inner_slot = k;
        facets.push_back(facet);
    }
    return facets;
}

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

void add_normals_3d(const std::vector<Eigen::Vector3d>& p, Hull& hull) {
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

// The two stored coordinates other than axis, in increasing axis order (the run time's (u, v)).
Eigen::Vector2d plane_coordinates(const Eigen::Vector3d& p, uint32_t axis) {
    return axis == 0 ? Eigen::Vector2d(p.y(), p.z()) : axis == 1 ? Eigen::Vector2d(p.x(), p.z()) : Eigen::Vector2d(p.x(), p.y());
}

void add_normals_2d(const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& n, uint32_t axis, Hull& hull) {
    for (const HullFacet& f : hull.facets) {
        const uint32_t a = f.probes[0], b = f.probes[1];
        // In-plane normal of the edge, turned to the positive (left) side of a -> b in (u, v).
        Eigen::Vector3d outward = n.cross(p[b] - p[a]).normalized();
        const Eigen::Vector2d e = plane_coordinates(p[b], axis) - plane_coordinates(p[a], axis);
        const Eigen::Vector2d w = plane_coordinates(outward, axis);
        if (-e.y() * w.x() + e.x() * w.y() < 0) outward = -outward;
        hull.vertex_normals[a] += outward;
        hull.vertex_normals[b] += outward;
    }
}

void add_normals_1d(const StoreData& data, const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& u, Hull& hull) {
    for (const HullFacet& f : hull.facets) {
        const uint32_t end = f.probes[0], inner = data.cell_vertices[size_t(f.inner_cell) * 4 + f.inner_slot];
        hull.vertex_normals[end] = (p[end] - p[inner]).dot(u) > 0 ? u : Eigen::Vector3d(-u);
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

std::vector<Eigen::Vector3d> hull_vertex_normals(const StoreData& data, const Eigen::Vector3d& set_direction) {
    std::vector<Eigen::Vector3d> positions(data.probe_count());
    for (size_t j = 0; j < positions.size(); ++j)
        positions[j] = Eigen::Vector3d(data.positions[3 * j], data.positions[3 * j + 1], data.positions[3 * j + 2]);
    Hull hull;
    hull.vertex_normals.assign(positions.size(), Eigen::Vector3d::Zero());
    hull.facets = stored_hull_facets(data);
    switch (data.dimension) {
        case 3: add_normals_3d(positions, hull); break;
        case 2: add_normals_2d(positions, set_direction, data.axis, hull); break;
        case 1: add_normals_1d(data, positions, set_direction, hull); break;
        default: return hull.vertex_normals;
    }
    for (auto& normal : hull.vertex_normals) {
        const double length = normal.norm();
        if (length > 0) normal /= length;
    }
    if (data.dimension == 3) untangle_vertex_normals(hull, positions);
    return hull.vertex_normals;
}

}  // namespace tetprobe
