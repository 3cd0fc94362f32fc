#include "bake/leak_edges.h"

#include "bake/parallel_jobs.h"
#include "bake/ray_caster.h"
#include "core/leak_plane.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace tetprobe {

namespace {

// The first surface from `from` towards `to`: its distance as a fraction of theirs (-1 if none) and its
// triangle's normal (not unit, either orientation).
struct Crossing {
    double fraction = -1;
    double normal[3] = {0, 0, 0};
};

Crossing first_crossing(const RayCaster& caster, const float from[3], const float to[3]) {
    Crossing crossing;
    double d[3], length = 0;
    for (int k = 0; k < 3; ++k) {
        d[k] = double(to[k]) - from[k];
        length += d[k] * d[k];
    }
    length = std::sqrt(length);
    // Embree's rays must start within +-1.8e18 and have a finite reach (it asserts otherwise): a pair
    // beyond that range is not tested (and stays unblocked).
    if (!(length > 0) || !(length < kLargestRayCoordinate)) return crossing;
    for (int k = 0; k < 3; ++k)
        if (!(std::fabs(from[k]) < kLargestRayCoordinate)) return crossing;
    const float direction[3] = {float(d[0] / length), float(d[1] / length), float(d[2] / length)};
    RayHit hit;
    if (!caster.intersect(from, direction, 0.0f, float(length), &hit)) return crossing;
    crossing.fraction = std::min(1.0, double(hit.distance) / length);
    const std::vector<float>& v = caster.local_vertices(hit.mesh);
    const std::vector<uint32_t>& indices = caster.local_indices(hit.mesh);
    const uint32_t* tri = &indices[3 * size_t(hit.triangle)];
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = double(v[3 * tri[1] + k]) - v[3 * tri[0] + k];
        e2[k] = double(v[3 * tri[2] + k]) - v[3 * tri[0] + k];
    }
    crossing.normal[0] = e1[1] * e2[2] - e1[2] * e2[1];
    crossing.normal[1] = e1[2] * e2[0] - e1[0] * e2[2];
    crossing.normal[2] = e1[0] * e2[1] - e1[1] * e2[0];
    return crossing;
}

double first_hit(const RayCaster& caster, const float from[3], const float to[3]) {
    return first_crossing(caster, from, to).fraction;
}

// Whether a surface separates a and b rather than grazes their segment: the four segments parallel to
// it, kLeakSeparationOffset of its length away across it and above and below it, are blocked too. A
// step in a floor or the edge of a wall blocks the segment between two probes that see the same light,
// and hiding one from the other then only moves the weight to probes that represent the query worse; a
// wall or a floor between storeys blocks the parallel segments as well.
bool separated(const RayCaster& caster, const float a[3], const float b[3]) {
    double d[3], length = 0;
    for (int k = 0; k < 3; ++k) d[k] = double(b[k]) - a[k], length += d[k] * d[k];
    length = std::sqrt(length);
    if (!(length > 0)) return false;
    for (double& c : d) c /= length;
    // u across the segment (horizontal unless the segment is vertical), v completes the frame.
    double u[3] = {-d[2], 0.0, d[0]};
    double n = std::sqrt(u[0] * u[0] + u[2] * u[2]);
    if (n < 1e-6) u[0] = 1, u[1] = 0, u[2] = 0, n = 1;
    for (double& c : u) c /= n;
    const double v[3] = {d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
    const double r = kLeakSeparationOffset * length;
    const double offsets[4][3] = {{r * u[0], r * u[1], r * u[2]}, {-r * u[0], -r * u[1], -r * u[2]},
                                  {r * v[0], r * v[1], r * v[2]}, {-r * v[0], -r * v[1], -r * v[2]}};
    for (const auto& o : offsets) {
        float from[3], to[3];
        for (int k = 0; k < 3; ++k) from[k] = float(a[k] + o[k]), to[k] = float(b[k] + o[k]);
        if (first_hit(caster, from, to) < 0 && first_hit(caster, to, from) < 0) return false;
    }
    return true;
}

}  // namespace

size_t add_leak_edges(const Scene& scene, StoreData& data, uint32_t threads, const Progress& progress) {
    data.leak_offsets.clear();
    data.leak_edges.clear();
    if (scene.meshes().empty()) return 0;
    // Every distinct probe pair of a cell (outer cells add no new pair: their facet is an inner one).
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    for (size_t c = 0; c < data.inner_cell_count; ++c) {
        const uint32_t* v = &data.cell_vertices[4 * c];
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j)
                if (v[i] < kOuter32 && v[j] < kOuter32 && v[i] != v[j])
                    pairs.emplace_back(std::min(v[i], v[j]), std::max(v[i], v[j]));
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

    const RayCaster caster(scene, data.origin);
    const uint32_t probes = data.probe_count();
    // The first surface from each end of every pair (none for a pair no surface separates), found on
    // worker threads; kept in the pairs' order.
    std::vector<std::pair<Crossing, Crossing>> hits(pairs.size());
    run_jobs(pairs.size(), threads, [&](size_t k) {
        const float* a = &data.positions[3 * size_t(pairs[k].first)];
        const float* b = &data.positions[3 * size_t(pairs[k].second)];
        double squared = 0;
        for (int q = 0; q < 3; ++q) squared += (double(b[q]) - a[q]) * (double(b[q]) - a[q]);
        if (!(squared <= kLeakLongestPair * kLeakLongestPair)) return;  // stays unblocked
        hits[k] = {first_crossing(caster, a, b), first_crossing(caster, b, a)};
        if ((hits[k].first.fraction >= 0 || hits[k].second.fraction >= 0) && !separated(caster, a, b))
            hits[k] = {Crossing(), Crossing()};
    }, progress, "leak control");
    std::vector<LeakEdge> edges;
    std::vector<uint32_t> owners;
    for (size_t k = 0; k < pairs.size(); ++k) {
        const auto& pair = pairs[k];
        Crossing from[2] = {hits[k].first, hits[k].second};
        if (from[0].fraction < 0 && from[1].fraction < 0) continue;
        // A surface found one way only (one-sided geometry seen from behind is still hit; a ray starting
        // inside a solid is not) is a wall of no thickness: the same plane from both probes.
        for (int side = 0; side < 2; ++side)
            if (from[side].fraction < 0) {
                from[side] = from[1 - side];
                from[side].fraction = 1.0 - from[side].fraction;
            }
        const float* ends[2] = {&data.positions[3 * size_t(pair.first)], &data.positions[3 * size_t(pair.second)]};
        LeakEdge edge;
        edge.partner = pair.second;
        bool placed = true;
        for (int side = 0; side < 2 && placed; ++side) {
            const float* own = ends[side];
            const float* other = ends[1 - side];
            const double t = from[side].fraction;
            double crossing[3];
            for (int q = 0; q < 3; ++q) crossing[q] = double(own[q]) + t * (double(other[q]) - own[q]);
            int16_t code[2];
            float offset;
            placed = make_leak_plane(from[side].normal, crossing, own, other, code, &offset);
            edge.normal[side][0] = code[0];
            edge.normal[side][1] = code[1];
            edge.offset[side] = offset;
            // Where the plane crosses the segment, rounded to 1/65535 and kept above zero (a wall touching
            // the probe still hides it only as the partner's weight grows).
            edge.reach[side] = uint16_t(std::max(1.0, std::min(65535.0, std::round(t * 65535.0))));
        }
        if (!placed) continue;  // probes too close for any float plane between them
        edges.push_back(edge);
        owners.push_back(pair.first);
    }
    if (edges.empty()) return 0;
    // Pairs are sorted by (low, high): the lists come out grouped by owner, partners increasing.
    data.leak_offsets.assign(size_t(probes) + 1, 0);
    for (uint32_t owner : owners) ++data.leak_offsets[size_t(owner) + 1];
    for (uint32_t p = 0; p < probes; ++p) data.leak_offsets[p + 1] += data.leak_offsets[p];
    data.leak_edges = std::move(edges);
    return data.leak_edges.size();
}

}  // namespace tetprobe
