#include "level_space.h"

#include "bake/inside_test.h"
#include "bake/parallel_jobs.h"
#include "bake/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <random>
#include <stdexcept>
#include <unordered_map>

namespace bench {

namespace {

using tetprobe::RayHit;

constexpr size_t kMaxHitsPerColumn = 256;

// The surfaces a column's downward ray meets, from the top: height (world y) and whether it is a floor.
struct ColumnHit {
    double y;
    bool floor;
};

class Geometry {
public:
    Geometry(const tetprobe::Scene& scene, const double origin[3])
        : scene_(scene), caster_(scene, origin), inside_(scene, caster_) {
        for (int a = 0; a < 3; ++a) origin_[a] = origin[a];
        inside_.require_decidable();
    }

    void local(const double world[3], float out[3]) const {
        for (int a = 0; a < 3; ++a) out[a] = float(world[a] - origin_[a]);
    }

    std::vector<ColumnHit> column(double x, double z, double top, double step, double floor_cosine) const {
        std::vector<ColumnHit> hits;
        const double from_world[3] = {x, top, z};
        float from[3];
        local(from_world, from);
        const float down[3] = {0.0f, -1.0f, 0.0f};
        float t = 0.0f;
        RayHit hit;
        while (hits.size() < kMaxHitsPerColumn && caster_.intersect(from, down, t, INFINITY, &hit)) {
            hits.push_back({double(from[1]) - double(hit.distance) + origin_[1], up_cosine(hit) >= floor_cosine});
            t = std::max(float(double(hit.distance) + step), std::nextafter(hit.distance, INFINITY));
        }
        return hits;
    }

    bool inside(const double world[3]) const {
        float l[3];
        local(world, l);
        return inside_.inside(l);
    }

    // True when the segment between two world points crosses no surface.
    bool clear(const double a[3], const double b[3]) const {
        float la[3], d[3];
        local(a, la);
        double length = 0;
        for (int k = 0; k < 3; ++k) d[k] = float(b[k] - a[k]), length += double(d[k]) * d[k];
        length = std::sqrt(length);
        if (!(length > 0)) return true;
        for (float& c : d) c = float(c / length);
        return !caster_.occluded(la, d, 0.0f, float(length), -1);
    }

private:
    // The cosine between +y and the front normal of the triangle hit (negative when seen from behind).
    double up_cosine(const RayHit& hit) const {
        const tetprobe::Mesh& mesh = scene_.meshes()[hit.mesh];
        const float* v = mesh.vertices.data();
        const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
        double e1[3], e2[3];
        for (int k = 0; k < 3; ++k) {
            e1[k] = double(v[3 * tri[1] + k]) - v[3 * tri[0] + k];
            e2[k] = double(v[3 * tri[2] + k]) - v[3 * tri[0] + k];
        }
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double up = length > 0 ? n[1] / length : 0.0;
        if (mesh.materials[mesh.triangle_materials[hit.triangle]].two_sided) up = std::abs(up);
        return up;
    }

    const tetprobe::Scene& scene_;
    double origin_[3];
    tetprobe::RayCaster caster_;
    tetprobe::InsideTest inside_;
};

}  // namespace

PlayableSpace find_playable_space(const tetprobe::Scene& scene, const std::vector<float>& spawn_points,
                                  const PlayableSpaceSettings& settings, uint32_t threads) {
    PlayableSpace space;
    space.settings = settings;
    double lo[3], hi[3];
    tetprobe::scene_bounds(scene, lo, hi);
    const double origin[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    const Geometry geometry(scene, origin);
    const double step_sizes[3] = {settings.spacing, settings.layer, settings.spacing};
    for (int a = 0; a < 3; ++a) {
        space.dims[a] = int64_t(std::floor((hi[a] - lo[a]) / step_sizes[a])) + 1;
        space.grid_origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * double(space.dims[a] - 1) * step_sizes[a];
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const double ray_step = 1e-5 * extent;

    // 1. Per column, the band points: each grid layer whose nearest surface below is a floor between
    // band_min and band_max under it, and whose nearest surface above is at least clearance away.
    const size_t columns = size_t(space.dims[0] * space.dims[2]);
    std::vector<std::vector<int64_t>> band(columns);
    tetprobe::run_jobs(columns, threads, [&](size_t c) {
        const int64_t ix = int64_t(c) % space.dims[0], iz = int64_t(c) / space.dims[0];
        const double x = space.grid_origin[0] + double(ix) * settings.spacing;
        const double z = space.grid_origin[2] + double(iz) * settings.spacing;
        const std::vector<ColumnHit> hits = geometry.column(x, z, hi[1] + 1.0, ray_step, settings.floor_cosine);
        size_t below = 0;  // hits are from the top: hits[below] is the first at or below y
        for (int64_t iy = space.dims[1] - 1; iy >= 0; --iy) {
            const double y = space.grid_origin[1] + double(iy) * settings.layer;
            while (below < hits.size() && hits[below].y > y) ++below;
            if (below == hits.size() || !hits[below].floor) continue;
            const double height = y - hits[below].y;
            if (height < settings.band_min || height > settings.band_max) continue;
            if (below > 0 && hits[below - 1].y - y < settings.clearance) continue;
            band[c].push_back(ix + space.dims[0] * (iy + space.dims[1] * iz));
        }
    }, {}, "band");
    std::vector<int64_t> cells;
    for (const auto& column : band) cells.insert(cells.end(), column.begin(), column.end());
    std::sort(cells.begin(), cells.end());
    space.band_points = cells.size();
    auto position = [&](int64_t cell, double out[3]) {
        const int64_t ix = cell % space.dims[0], iy = (cell / space.dims[0]) % space.dims[1],
                      iz = cell / (space.dims[0] * space.dims[1]);
        out[0] = space.grid_origin[0] + double(ix) * settings.spacing;
        out[1] = space.grid_origin[1] + double(iy) * settings.layer;
        out[2] = space.grid_origin[2] + double(iz) * settings.spacing;
    };

    // 2. Not inside geometry.
    std::vector<uint8_t> free(cells.size(), 0);
    tetprobe::run_jobs(cells.size(), threads, [&](size_t i) {
        double p[3];
        position(cells[i], p);
        free[i] = !geometry.inside(p);
    }, {}, "inside");
    std::vector<int64_t> free_cells;
    for (size_t i = 0; i < cells.size(); ++i)
        if (free[i]) free_cells.push_back(cells[i]);
    space.free_points = free_cells.size();
    std::unordered_map<int64_t, uint32_t> index_of;
    for (size_t i = 0; i < free_cells.size(); ++i) index_of[free_cells[i]] = uint32_t(i);

    // 3. Connections: each point to its 13 "forward" neighbours (the other 13 see it from theirs).
    std::vector<std::vector<uint32_t>> forward(free_cells.size());
    tetprobe::run_jobs(free_cells.size(), threads, [&](size_t i) {
        const int64_t cell = free_cells[i];
        const int64_t ix = cell % space.dims[0], iy = (cell / space.dims[0]) % space.dims[1],
                      iz = cell / (space.dims[0] * space.dims[1]);
        double a[3];
        position(cell, a);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int order = dx + 3 * dy + 9 * dz;
                    if (order <= 0) continue;
                    const int64_t jx = ix + dx, jy = iy + dy, jz = iz + dz;
                    if (jx < 0 || jy < 0 || jz < 0 || jx >= space.dims[0] || jy >= space.dims[1] || jz >= space.dims[2])
                        continue;
                    const auto it = index_of.find(jx + space.dims[0] * (jy + space.dims[1] * jz));
                    if (it == index_of.end()) continue;
                    double b[3];
                    position(free_cells[it->second], b);
                    if (geometry.clear(a, b)) forward[i].push_back(it->second);
                }
    }, {}, "connections");
    std::vector<std::vector<uint32_t>> adjacent(free_cells.size());
    for (size_t i = 0; i < forward.size(); ++i)
        for (uint32_t j : forward[i]) adjacent[i].push_back(j), adjacent[j].push_back(uint32_t(i));

    // 4. Seeds: the nearest free point within 3 m of each spawn point that it sees; then the flood fill.
    std::vector<uint32_t> seed_of_spawn;
    space.spawns_given = spawn_points.size() / 3;
    for (size_t s = 0; s + 3 <= spawn_points.size(); s += 3) {
        const double p[3] = {spawn_points[s], spawn_points[s + 1], spawn_points[s + 2]};
        double best = 3.0 * 3.0;
        int64_t best_index = -1;
        int64_t c[3];
        for (int a = 0; a < 3; ++a) c[a] = int64_t(std::llround((p[a] - space.grid_origin[a]) / step_sizes[a]));
        const int reach[3] = {int(std::ceil(3.0 / settings.spacing)), int(std::ceil(3.0 / settings.layer)),
                              int(std::ceil(3.0 / settings.spacing))};
        for (int64_t z = c[2] - reach[2]; z <= c[2] + reach[2]; ++z)
            for (int64_t y = c[1] - reach[1]; y <= c[1] + reach[1]; ++y)
                for (int64_t x = c[0] - reach[0]; x <= c[0] + reach[0]; ++x) {
                    if (x < 0 || y < 0 || z < 0 || x >= space.dims[0] || y >= space.dims[1] || z >= space.dims[2]) continue;
                    const auto it = index_of.find(x + space.dims[0] * (y + space.dims[1] * z));
                    if (it == index_of.end()) continue;
                    double q[3], d2 = 0;
                    position(free_cells[it->second], q);
                    for (int a = 0; a < 3; ++a) d2 += (q[a] - p[a]) * (q[a] - p[a]);
                    if (d2 < best && geometry.clear(p, q)) best = d2, best_index = it->second;
                }
        if (best_index >= 0) seed_of_spawn.push_back(uint32_t(best_index));
    }
    if (seed_of_spawn.empty()) throw std::runtime_error("no spawn point is within 3 m of a free point of the walkable band");
    std::vector<int64_t> reached(free_cells.size(), -1);
    std::deque<uint32_t> queue;
    for (uint32_t s : seed_of_spawn)
        if (reached[s] < 0) reached[s] = 0, queue.push_back(s);
    while (!queue.empty()) {
        const uint32_t i = queue.front();
        queue.pop_front();
        for (uint32_t j : adjacent[i])
            if (reached[j] < 0) reached[j] = 0, queue.push_back(j);
    }
    std::vector<uint32_t> new_index(free_cells.size(), UINT32_MAX);
    for (size_t i = 0; i < free_cells.size(); ++i)
        if (reached[i] >= 0) {
            new_index[i] = uint32_t(space.cells.size());
            space.cells.push_back(free_cells[i]);
            double p[3];
            position(free_cells[i], p);
            for (double c : p) space.points.push_back(float(c));
        }
    space.neighbour_start.push_back(0);
    for (size_t i = 0; i < free_cells.size(); ++i) {
        if (reached[i] < 0) continue;
        for (uint32_t j : adjacent[i]) space.neighbours.push_back(new_index[j]);
        space.neighbour_start.push_back(uint32_t(space.neighbours.size()));
    }
    for (uint32_t s : seed_of_spawn) space.seeds.push_back(new_index[s]);
    space.spawns_used = seed_of_spawn.size();
    for (int a = 0; a < 3; ++a) space.lo[a] = INFINITY, space.hi[a] = -INFINITY;
    for (size_t i = 0; i < space.points.size(); ++i)
        space.lo[i % 3] = std::min(space.lo[i % 3], space.points[i]), space.hi[i % 3] = std::max(space.hi[i % 3], space.points[i]);
    return space;
}

std::vector<uint32_t> grid_path(const PlayableSpace& space, uint32_t from, uint32_t to) {
    std::vector<uint32_t> previous(space.count(), UINT32_MAX);
    std::deque<uint32_t> queue{from};
    previous[from] = from;
    while (!queue.empty() && previous[to] == UINT32_MAX) {
        const uint32_t i = queue.front();
        queue.pop_front();
        for (uint32_t k = space.neighbour_start[i]; k < space.neighbour_start[i + 1]; ++k) {
            const uint32_t j = space.neighbours[k];
            if (previous[j] == UINT32_MAX) previous[j] = i, queue.push_back(j);
        }
    }
    if (previous[to] == UINT32_MAX) return {};
    std::vector<uint32_t> path{to};
    while (path.back() != from) path.push_back(previous[path.back()]);
    std::reverse(path.begin(), path.end());
    return path;
}

std::vector<float> draw_free_points(const tetprobe::Scene& scene, const PlayableSpace& space, size_t count,
                                    uint64_t seed, const std::vector<float>& avoid, double clearance) {
    if (space.count() == 0) throw std::runtime_error("draw_free_points: the playable space is empty");
    double lo[3], hi[3];
    tetprobe::scene_bounds(scene, lo, hi);
    const double origin[3] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    const Geometry geometry(scene, origin);
    const double half[3] = {0.5 * space.settings.spacing, 0.5 * space.settings.layer, 0.5 * space.settings.spacing};
    std::mt19937_64 rng(seed);
    std::vector<float> out;
    for (size_t tries = 0; out.size() < 3 * count; ++tries) {
        if (tries > 100 * count + 1000) throw std::runtime_error("draw_free_points: too few points keep clear of the lights");
        const size_t i = size_t(rng() % space.count());
        double a[3], p[3];
        for (int k = 0; k < 3; ++k) {
            a[k] = space.points[3 * i + size_t(k)];
            p[k] = a[k] + half[k] * (2.0 * std::uniform_real_distribution<double>(0.0, 1.0)(rng) - 1.0);
        }
        bool near_light = false;
        for (size_t l = 0; l + 3 <= avoid.size(); l += 3) {
            double d2 = 0;
            for (int k = 0; k < 3; ++k) d2 += (p[k] - avoid[l + size_t(k)]) * (p[k] - avoid[l + size_t(k)]);
            near_light |= d2 < clearance * clearance;
        }
        if (near_light || !geometry.clear(a, p)) continue;
        for (double c : p) out.push_back(float(c));
    }
    return out;
}

std::vector<uint32_t> component_labels(const PlayableSpace& space) {
    std::vector<uint32_t> label(space.count(), UINT32_MAX);
    uint32_t next = 0;
    for (uint32_t start = 0; start < space.count(); ++start) {
        if (label[start] != UINT32_MAX) continue;
        std::deque<uint32_t> queue{start};
        label[start] = next;
        while (!queue.empty()) {
            const uint32_t i = queue.front();
            queue.pop_front();
            for (uint32_t k = space.neighbour_start[i]; k < space.neighbour_start[i + 1]; ++k)
                if (label[space.neighbours[k]] == UINT32_MAX) label[space.neighbours[k]] = next, queue.push_back(space.neighbours[k]);
        }
        ++next;
    }
    return label;
}

std::vector<float> walking_path(const PlayableSpace& space, uint32_t from, uint32_t to, double step) {
    const std::vector<uint32_t> nodes = grid_path(space, from, to);
    std::vector<float> frames;
    if (nodes.empty()) return frames;
    double carried = 0;  // distance walked past the last frame
    for (size_t n = 0; n + 1 < nodes.size(); ++n) {
        const float* a = &space.points[3 * size_t(nodes[n])];
        const float* b = &space.points[3 * size_t(nodes[n + 1])];
        double length = 0;
        for (int k = 0; k < 3; ++k) length += double(b[k] - a[k]) * (b[k] - a[k]);
        length = std::sqrt(length);
        double t = n == 0 ? 0.0 : step - carried;
        for (; t < length; t += step)
            for (int k = 0; k < 3; ++k) frames.push_back(float(a[k] + (b[k] - a[k]) * (t / length)));
        carried = length - (t - step);
    }
    return frames;
}

}  // namespace bench
