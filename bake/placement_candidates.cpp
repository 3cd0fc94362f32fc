#include "bake/placement_candidates.h"

#include "bake/inside_test.h"
#include "bake/parallel_jobs.h"
#include "bake/sampling.h"
#include "core/error.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <deque>
#include <string>

namespace tetprobe {

namespace {

// Lowest cosine between an upward-facing floor's normal and +y, the up of the frame the rules run in (45 degrees).
constexpr double kFloorCosine = 0.7071;
// Floors a walkable column may have (storeys, tables, stairs); more are ignored.
constexpr size_t kMaxFloorsPerColumn = 64;
// Connection rules of the flood fill from playable seeds, in spacings: the largest height step between
// connected candidates (stairs, ramps), and how far a seed reaches for its first candidate.
constexpr double kReachHeight = 1.5, kSeedReach = 2.0;
// Validation points: one per this many candidates, within [kMinValidation, kMaxValidation] (all
// candidates below the minimum), each tried this many times before it is given up.
constexpr size_t kCandidatesPerValidation = 4, kMinValidation = 1024, kMaxValidation = 16384;
constexpr int kValidationTries = 8;
// Candidates per job of the flood fill's connection pass.
constexpr size_t kConnectionBlock = 256;

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// The lattice: counts[a] points from start[a], a spacing apart. Walkable placement uses its columns only.
struct Lattice {
    double start[3] = {0, 0, 0};
    size_t counts[3] = {1, 1, 1};
    double spacing = 1;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  // the scene's bounds

    double coordinate(int axis, size_t i) const { return start[axis] + spacing * double(i); }
};

// Checks the rules and makes the lattice (centred on the scene's bounds, floor(extent / spacing) points
// per axis, at least one).
Lattice make_lattice(const Scene& scene, const CandidateRules& rules) {
    if (!(std::isfinite(rules.spacing) && rules.spacing > 0))
        throw Error(Status::invalid_argument, "spacing must be positive and finite (got " + number(rules.spacing) + ")");
    if (!(std::isfinite(rules.margin) && rules.margin >= 0))
        throw Error(Status::invalid_argument, "margin must be zero or positive and finite (got " + number(rules.margin) + ")");
    if (rules.mode != PlacementMode::whole && rules.mode != PlacementMode::walkable)
        throw Error(Status::invalid_argument, "unknown placement mode " + std::to_string(uint32_t(rules.mode)));
    if (rules.mode == PlacementMode::walkable &&
        !(std::isfinite(rules.walk_max_height) && rules.walk_min_height >= 0 && rules.walk_max_height > rules.walk_min_height))
        throw Error(Status::invalid_argument, "the walkable height band needs 0 <= walk_min_height < walk_max_height (got " +
                                                  number(rules.walk_min_height) + ", " + number(rules.walk_max_height) + ")");
    if (scene.meshes().empty()) throw Error(Status::scene, "the scene has no mesh to place probes around");
    Lattice l;
    scene_bounds(scene, l.lo, l.hi);
    const double* lo = l.lo;
    const double* hi = l.hi;
    const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (rules.margin > diagonal)
        throw Error(Status::invalid_argument, "margin " + number(rules.margin) + " is larger than the scene (its bounds' diagonal is " +
                                                  number(diagonal) + ")");
    const bool walkable = rules.mode == PlacementMode::walkable;
    double tested = 1;
    for (int a = 0; a < 3; ++a)
        if (!(walkable && a == 1)) tested *= std::max(1.0, std::floor((hi[a] - lo[a]) / rules.spacing));
    if (tested > double(kMaxPlacementTested))
        throw Error(Status::invalid_argument,
                    "spacing " + number(rules.spacing) + " gives " + number(tested) + (walkable ? " columns" : " lattice points") +
                        " over the scene's bounds (" + number(hi[0] - lo[0]) + " x " + number(hi[1] - lo[1]) + " x " +
                        number(hi[2] - lo[2]) + "), more than the " + std::to_string(kMaxPlacementTested) +
                        " placement tests: raise the spacing");
    l.spacing = rules.spacing;
    for (int a = 0; a < 3; ++a) {
        const size_t n = size_t(std::max(1.0, std::floor((hi[a] - lo[a]) / rules.spacing)));
        l.counts[a] = n;
        l.start[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * double(n - 1) * rules.spacing;
    }
    return l;
}

// Heights (world y) where walkable candidates stand above a floor at `floor` whose band ends at `end`
// (the band's top, the surface above less the margin, or the cut-off): from the band's bottom (at least
// the margin above the floor) to its end, evenly, at most a spacing apart, so that the whole band lies
// between candidates and is interpolated, not extrapolated.
void band_heights(const CandidateRules& rules, double floor, double end, std::vector<double>* out) {
    out->clear();
    // The ends sit a ten-thousandth of a spacing inside the band, so that a candidate the band puts exactly
    // the margin from a surface is not decided by the rounding of its float position.
    const double inset = 1e-4 * rules.spacing;
    const double low = floor + std::max(rules.walk_min_height, rules.margin) + inset;
    const double high = std::min(end, floor + rules.walk_max_height) - inset;
    if (!(high >= low)) return;
    const size_t layers = size_t(std::ceil((high - low) / rules.spacing)) + 1;
    for (size_t k = 0; k < layers; ++k) out->push_back(layers == 1 ? low : low + (high - low) * double(k) / double(layers - 1));
}

// The heights (world y) a candidate of a column stands for, half way to its neighbours in the band (a
// band of one layer: a quarter spacing either side): where its validation points are drawn.
void layer_extent(const std::vector<double>& heights, size_t k, double spacing, float out[2]) {
    const size_t n = heights.size();
    out[0] = float(n == 1 ? heights[k] - 0.25 * spacing : k == 0 ? heights[0] : 0.5 * (heights[k - 1] + heights[k]));
    out[1] = float(n == 1 ? heights[k] + 0.25 * spacing : k + 1 == n ? heights[k] : 0.5 * (heights[k] + heights[k + 1]));
}

// The scene's geometry as the rules see it: ray casting, the inside test and floors.
class Geometry {
public:
    Geometry(const Scene& scene, const double origin[3]) : scene_(scene), caster_(scene, origin), inside_(scene, caster_) {
        for (int a = 0; a < 3; ++a) origin_[a] = origin[a];
        inside_.require_decidable();
    }

    void local(const float world[3], float out[3]) const {
        for (int a = 0; a < 3; ++a) out[a] = float(double(world[a]) - origin_[a]);
    }

    // world: the float position a kept candidate is returned as, so the rules judge that very point.
    bool accepts(const float world[3], double margin) const {
        float l[3];
        local(world, l);
        return clear_of_surfaces(caster_, l, margin) && !inside_.inside(l);
    }

    bool inside(const float world[3]) const {
        float l[3];
        local(world, l);
        return inside_.inside(l);
    }

    // True when the segment between two world points crosses no surface.
    bool clear(const float a[3], const float b[3]) const {
        float la[3], lb[3], d[3];
        local(a, la);
        local(b, lb);
        double length = 0;
        for (int k = 0; k < 3; ++k) d[k] = lb[k] - la[k], length += double(d[k]) * d[k];
        length = std::sqrt(length);
        if (!(length > 0)) return true;
        for (float& c : d) c = float(c / length);
        return !caster_.occluded(la, d, 0.0f, float(length), -1);
    }

    // The heights (world y) of the upward-facing surfaces along the vertical line at (x, z), from the
    // top down: a ray cast down from above the scene, continued past every surface it meets.
    std::vector<double> floors(double x, double z, double top, double step) const {
        std::vector<double> heights;
        const float from[3] = {float(x - origin_[0]), float(top - origin_[1]), float(z - origin_[2])};
        const float down[3] = {0.0f, -1.0f, 0.0f};
        float t = 0.0f;
        RayHit hit;
        while (heights.size() < kMaxFloorsPerColumn && caster_.intersect(from, down, t, INFINITY, &hit)) {
            if (faces_up(hit)) heights.push_back(double(from[1]) - double(hit.distance) + origin_[1]);
            // Past the surface just hit, by at least one float step: far above a small scene the
            // step alone can round away, and the same triangle would be hit again forever.
            t = std::max(float(double(hit.distance) + step), std::nextafter(hit.distance, INFINITY));
        }
        return heights;
    }

    // Whether the first surface straight below the world point is a floor between low and high under
    // it: the point stands in that floor's walkable band (the band ends at the first surface above a
    // floor, so the floor a band point belongs to is the first surface below it).
    bool in_band(const float world[3], double low, double high) const {
        float from[3];
        local(world, from);
        const float down[3] = {0.0f, -1.0f, 0.0f};
        RayHit hit;
        if (!caster_.intersect(from, down, 0.0f, INFINITY, &hit)) return false;
        return faces_up(hit) && double(hit.distance) >= low && double(hit.distance) <= high;
    }

    // The height (world y) of the first surface of any kind above the point at (x, y, z), or
    // infinity: where a walkable band above a floor at y ends.
    double ceiling(double x, double y, double z, double step) const {
        const float from[3] = {float(x - origin_[0]), float(y - origin_[1]), float(z - origin_[2])};
        const float up[3] = {0.0f, 1.0f, 0.0f};
        RayHit hit;
        if (!caster_.intersect(from, up, float(step), INFINITY, &hit)) return INFINITY;
        return double(from[1]) + double(hit.distance) + origin_[1];
    }

private:
    bool faces_up(const RayHit& hit) const {
        const Mesh& mesh = scene_.meshes()[hit.mesh];
        const std::vector<float>& v = caster_.local_vertices(hit.mesh);
        const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
        double e1[3], e2[3];
        for (int k = 0; k < 3; ++k) {
            e1[k] = double(v[3 * tri[1] + k]) - v[3 * tri[0] + k];
            e2[k] = double(v[3 * tri[2] + k]) - v[3 * tri[0] + k];
        }
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double up = n[1] / std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (mesh.materials[mesh.triangle_materials[hit.triangle]].two_sided) up = std::abs(up);
        return up >= kFloorCosine;  // a one-sided surface seen from behind is not a floor
    }

    const Scene& scene_;
    double origin_[3];
    RayCaster caster_;
    InsideTest inside_;
};

// The points of column (ix, iz) the inside and margin tests are applied to, bottom up within a floor:
// the lattice's y values (whole), or each floor's band (walkable; the band ends below the surface
// above the floor, a ceiling or a table top, by the margin, and at `top`: without playable seeds the
// scene's bounds, since above a roof half the rays escape and the inside test alone would keep such
// points; with seeds the flood fill leaves roofs out, and open floors near the top keep their band).
void column_points(const Lattice& l, const CandidateRules& rules, const Geometry& geometry, double top, size_t ix,
                   size_t iz, std::vector<float>* out, std::vector<float>* extents) {
    out->clear();
    extents->clear();
    const double x = l.coordinate(0, ix), z = l.coordinate(2, iz);
    if (rules.mode == PlacementMode::whole) {
        for (size_t iy = 0; iy < l.counts[1]; ++iy) {
            const double y = l.coordinate(1, iy);
            out->insert(out->end(), {float(x), float(y), float(z)});
            extents->insert(extents->end(), {float(y - 0.5 * l.spacing), float(y + 0.5 * l.spacing)});
        }
        return;
    }
    const double extent = std::max({l.hi[0] - l.lo[0], l.hi[1] - l.lo[1], l.hi[2] - l.lo[2]});
    const double step = 1e-5 * extent;
    std::vector<double> heights;
    for (double floor : geometry.floors(x, z, l.hi[1] + rules.walk_max_height + rules.spacing, step)) {
        const double ceiling = geometry.ceiling(x, floor, z, step);
        band_heights(rules, floor, std::min(ceiling - rules.margin, top), &heights);
        for (size_t k = 0; k < heights.size(); ++k) {
            out->insert(out->end(), {float(x), float(heights[k]), float(z)});
            float extent[2];
            layer_extent(heights, k, rules.spacing, extent);
            extents->insert(extents->end(), extent, extent + 2);
        }
    }
}

double centre(double lo, double hi) { return 0.5 * (lo + hi); }

double band_top(const Scene& scene, const Lattice& l, const CandidateRules& rules) {
    return scene.playable_seeds().empty() ? l.hi[1] : l.hi[1] + rules.walk_max_height;
}

[[noreturn]] void too_many_candidates(const CandidateRules& rules, size_t found, size_t rows_done, size_t rows) {
    throw Error(Status::invalid_argument, "spacing " + number(rules.spacing) + " gives more than " +
                                              std::to_string(kMaxPlacementCandidates) + " candidates (" + std::to_string(found) +
                                              " after " + std::to_string(rows_done) + " of " + std::to_string(rows) +
                                              " rows of columns), more than placement holds in memory: raise the spacing");
}

// Keeps the candidates the scene's playable seeds reach (see placement_candidates.h). columns: each
// candidate's column (ix + nx * iz), non-decreasing. Returns the kept indices, ascending.
std::vector<uint32_t> reached_from_seeds(const Scene& scene, const Lattice& l, const Geometry& geometry,
                                         const std::vector<float>& positions, const std::vector<uint64_t>& columns,
                                         uint32_t threads, const Progress& progress) {
    const size_t count = positions.size() / 3;
    const size_t nx = l.counts[0], nz = l.counts[2];
    auto column_range = [&](int64_t ix, int64_t iz, size_t* first, size_t* last) {
        *first = *last = 0;
        if (ix < 0 || iz < 0 || ix >= int64_t(nx) || iz >= int64_t(nz)) return;
        const uint64_t id = uint64_t(ix) + uint64_t(nx) * uint64_t(iz);
        *first = size_t(std::lower_bound(columns.begin(), columns.end(), id) - columns.begin());
        *last = size_t(std::upper_bound(columns.begin(), columns.end(), id) - columns.begin());
    };
    const double reach_height = kReachHeight * l.spacing;
    // Connections, each found once from its lower-indexed candidate (the forward half of the 3 x 3 columns).
    const size_t blocks = (count + kConnectionBlock - 1) / kConnectionBlock;
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> found(blocks);
    run_jobs(blocks, threads, [&](size_t b) {
        for (size_t i = b * kConnectionBlock; i < std::min(count, (b + 1) * kConnectionBlock); ++i) {
            const int64_t ix = int64_t(columns[i] % nx), iz = int64_t(columns[i] / nx);
            for (int dz = 0; dz <= 1; ++dz)
                for (int dx = -1; dx <= 1; ++dx) {
                    if (dz == 0 && dx < 0) continue;
                    size_t first, last;
                    column_range(ix + dx, iz + dz, &first, &last);
                    for (size_t j = std::max(first, i + 1); j < last; ++j)
                        if (std::fabs(double(positions[3 * j + 1]) - positions[3 * i + 1]) <= reach_height &&
                            geometry.clear(&positions[3 * i], &positions[3 * j]))
                            found[b].push_back({uint32_t(i), uint32_t(j)});
                }
        }
    }, progress.part(0, 0.9), "candidates");
    std::vector<uint32_t> start(count + 1, 0);
    for (const auto& block : found)
        for (const auto& e : block) ++start[e.first + 1], ++start[e.second + 1];
    for (size_t i = 0; i < count; ++i) start[i + 1] += start[i];
    std::vector<uint32_t> adjacent(start.back()), fill(start.begin(), start.end() - 1);
    for (const auto& block : found)
        for (const auto& e : block) adjacent[fill[e.first]++] = e.second, adjacent[fill[e.second]++] = e.first;
    found.clear();

    std::vector<uint8_t> reached(count, 0);
    std::deque<uint32_t> queue;
    const std::vector<float>& seeds = scene.playable_seeds();
    const int reach = int(std::ceil(kSeedReach));
    for (size_t s = 0; s + 3 <= seeds.size(); s += 3) {
        const float* seed = &seeds[s];
        const int64_t ix = int64_t(std::llround((seed[0] - l.start[0]) / l.spacing));
        const int64_t iz = int64_t(std::llround((seed[2] - l.start[2]) / l.spacing));
        double best = kSeedReach * l.spacing * kSeedReach * l.spacing;
        int64_t nearest = -1;
        for (int64_t z = iz - reach; z <= iz + reach; ++z)
            for (int64_t x = ix - reach; x <= ix + reach; ++x) {
                size_t first, last;
                column_range(x, z, &first, &last);
                for (size_t j = first; j < last; ++j) {
                    double d2 = 0;
                    for (int a = 0; a < 3; ++a) d2 += (double(positions[3 * j + size_t(a)]) - seed[a]) * (double(positions[3 * j + size_t(a)]) - seed[a]);
                    if (d2 < best && geometry.clear(seed, &positions[3 * j])) best = d2, nearest = int64_t(j);
                }
            }
        if (nearest >= 0 && !reached[size_t(nearest)]) reached[size_t(nearest)] = 1, queue.push_back(uint32_t(nearest));
    }
    if (queue.empty())
        throw Error(Status::scene, "none of the scene's " + std::to_string(seeds.size() / 3) +
                                       " playable seeds sees a candidate within " + number(kSeedReach * l.spacing) +
                                       " (two spacings): move the seeds or lower the spacing");
    while (!queue.empty()) {
        const uint32_t i = queue.front();
        queue.pop_front();
        for (uint32_t k = start[i]; k < start[i + 1]; ++k)
            if (!reached[adjacent[k]]) reached[adjacent[k]] = 1, queue.push_back(adjacent[k]);
    }
    progress.report(1.0, "candidates");
    std::vector<uint32_t> kept;
    for (size_t i = 0; i < count; ++i)
        if (reached[i]) kept.push_back(uint32_t(i));
    return kept;
}

// Validation points (see placement_candidates.h). Each candidate stands for a box: half a spacing to
// each side where a neighbouring column has a candidate within half a spacing in height, a whole
// spacing where none has (toward a wall that kept the neighbour out, so the strip along walls is
// measured too), and its share of the band in height. The k-th point is drawn from the candidate at
// quantile (k + 1/2) / wanted of the boxes' volumes, uniformly in its box, and kept when the move crosses
// no surface, the point is not inside geometry and (walkable) stands in a floor's band: points fall
// uniformly over the free volume where candidates could stand.
std::vector<float> validation_points(const Lattice& l, const CandidateRules& rules, const Geometry& geometry,
                                     const std::vector<float>& candidates,
                                     const std::vector<float>& extents, const std::vector<uint64_t>& columns, uint64_t seed,
                                     uint32_t threads, const Progress& progress) {
    const size_t count = candidates.size() / 3;
    const size_t wanted = count < kMinValidation ? count
                                                 : std::min(kMaxValidation, std::max(kMinValidation, count / kCandidatesPerValidation));
    const size_t nx = l.counts[0], nz = l.counts[2];
    // Walkable: the band the candidates fill (band_heights), checked at the point itself, since a box
    // reaching past its column may hang over a drop, a slope too steep to stand on or a lower floor.
    const bool walkable = rules.mode == PlacementMode::walkable;
    const double band_low = std::max(rules.walk_min_height, rules.margin), band_high = rules.walk_max_height;
    // Half-widths toward -x, +x, -z, +z.
    std::vector<float> reach(4 * count);
    run_jobs(count, threads, [&](size_t i) {
        const int64_t ix = int64_t(columns[i] % nx), iz = int64_t(columns[i] / nx);
        const int64_t steps[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
        for (int side = 0; side < 4; ++side) {
            const int64_t x = ix + steps[side][0], z = iz + steps[side][1];
            bool neighbour = false;
            if (x >= 0 && z >= 0 && x < int64_t(nx) && z < int64_t(nz)) {
                const uint64_t id = uint64_t(x) + uint64_t(nx) * uint64_t(z);
                for (auto it = std::lower_bound(columns.begin(), columns.end(), id); it != columns.end() && *it == id && !neighbour; ++it)
                    neighbour = std::fabs(double(candidates[3 * size_t(it - columns.begin()) + 1]) - candidates[3 * i + 1]) <= 0.5 * l.spacing;
            }
            reach[4 * i + size_t(side)] = float(neighbour ? 0.5 * l.spacing : l.spacing);
        }
    }, {}, "candidates");
    std::vector<double> cumulative(count + 1, 0.0);
    for (size_t i = 0; i < count; ++i)
        cumulative[i + 1] = cumulative[i] + double(reach[4 * i] + reach[4 * i + 1]) * double(reach[4 * i + 2] + reach[4 * i + 3]) *
                                                std::max(0.0, double(extents[2 * i + 1]) - extents[2 * i]);
    const bool by_volume = cumulative[count] > 0;
    std::vector<float> points(3 * wanted);
    std::vector<uint8_t> kept(wanted, 0);
    run_jobs(wanted, threads, [&](size_t k) {
        const double quantile = (double(k) + 0.5) / double(wanted);
        size_t i = (2 * k + 1) * count / (2 * wanted);
        if (by_volume)
            i = std::min(count - 1, size_t(std::upper_bound(cumulative.begin(), cumulative.end(), quantile * cumulative[count]) -
                                           cumulative.begin()) - 1);
        const float* from = &candidates[3 * i];
        const float* r = &reach[4 * i];
        for (int attempt = 0; attempt < kValidationTries; ++attempt) {
            double u[3];
            for (int a = 0; a < 3; ++a) u[a] = sample_uniform(seed, k, uint64_t(attempt), uint64_t(a));
            const float p[3] = {float(double(from[0]) - r[0] + u[0] * (double(r[0]) + r[1])),
                                float(double(extents[2 * i]) + u[1] * (double(extents[2 * i + 1]) - extents[2 * i])),
                                float(double(from[2]) - r[2] + u[2] * (double(r[2]) + r[3]))};
            if (geometry.clear(from, p) && !geometry.inside(p) && (!walkable || geometry.in_band(p, band_low, band_high))) {
                std::copy(p, p + 3, &points[3 * k]);
                kept[k] = 1;
                return;
            }
        }
    }, progress, "candidates");
    std::vector<float> out;
    for (size_t k = 0; k < wanted; ++k)
        if (kept[k]) out.insert(out.end(), &points[3 * k], &points[3 * k] + 3);
    return out;
}

}  // namespace

bool clear_of_surfaces(const RayCaster& caster, const float local[3], double margin) {
    if (!(margin > 0)) return true;
    SurfacePoint nearest;
    return !caster.nearest_surface(local, float(margin), &nearest) || double(nearest.distance) >= margin;
}

// Walkable columns stand along the scene's up: the rules below run where up is +y, so a scene with
// another up is turned there exactly (a signed permutation of its coordinates) and points turned back.
static bool turned_for_walking(const Scene& scene, const CandidateRules& rules, AxisTurn* back) {
    if (rules.mode != PlacementMode::walkable || scene.up() == UpAxis::pos_y) return false;
    *back = turn_between(UpAxis::pos_y, scene.up());
    return true;
}

size_t candidate_bound(const Scene& scene, const CandidateRules& rules, uint32_t threads) {
    AxisTurn back;
    if (turned_for_walking(scene, rules, &back)) return candidate_bound(scene.meshes_turned(back.inverse()), rules, threads);
    const Lattice l = make_lattice(scene, rules);
    if (rules.mode == PlacementMode::whole) return l.counts[0] * l.counts[1] * l.counts[2];
    const double origin[3] = {centre(l.lo[0], l.hi[0]), centre(l.lo[1], l.hi[1]), centre(l.lo[2], l.hi[2])};
    const Geometry geometry(scene, origin);
    std::vector<size_t> per_row(l.counts[2], 0);
    run_jobs(l.counts[2], threads, [&](size_t iz) {
        std::vector<float> points, extents;
        for (size_t ix = 0; ix < l.counts[0]; ++ix) {
            column_points(l, rules, geometry, band_top(scene, l, rules), ix, iz, &points, &extents);
            per_row[iz] += points.size() / 3;
        }
    }, {}, "candidates");
    size_t total = 0;
    for (size_t n : per_row) total += n;
    return total;
}

Candidates find_candidates(const Scene& scene, const CandidateRules& rules, uint64_t seed, uint32_t threads,
                           const Progress& progress) {
    AxisTurn back;
    if (turned_for_walking(scene, rules, &back)) {  // extents stay heights of the turned frame
        Candidates turned = find_candidates(scene.meshes_turned(back.inverse()), rules, seed, threads, progress);
        for (std::vector<float>* points : {&turned.positions, &turned.validation})
            for (size_t i = 0; i < points->size(); i += 3) back.apply(&(*points)[i], &(*points)[i]);
        return turned;
    }
    const Lattice l = make_lattice(scene, rules);
    const double origin[3] = {centre(l.lo[0], l.hi[0]), centre(l.lo[1], l.hi[1]), centre(l.lo[2], l.hi[2])};
    const Geometry geometry(scene, origin);
    const bool seeded = !scene.playable_seeds().empty();
    const Progress testing = progress.part(0, seeded ? 0.6 : 0.9);

    // Row by row of columns (z), each row's candidates in column order.
    const size_t rows = l.counts[2];
    std::vector<std::vector<float>> row_positions(rows);
    std::vector<std::vector<uint32_t>> row_columns(rows);
    std::vector<std::vector<float>> row_extents(rows);
    std::vector<size_t> row_tested(rows, 0);
    std::atomic<size_t> total{0}, rows_done{0};
    run_jobs(rows, threads, [&](size_t iz) {
        std::vector<float> points, extents;
        for (size_t ix = 0; ix < l.counts[0]; ++ix) {
            column_points(l, rules, geometry, band_top(scene, l, rules), ix, iz, &points, &extents);
            row_tested[iz] += points.size() / 3;
            for (size_t k = 0; k < points.size() / 3; ++k)
                if (geometry.accepts(&points[3 * k], rules.margin)) {
                    row_positions[iz].insert(row_positions[iz].end(), &points[3 * k], &points[3 * k] + 3);
                    row_extents[iz].insert(row_extents[iz].end(), &extents[2 * k], &extents[2 * k] + 2);
                    row_columns[iz].push_back(uint32_t(ix));
                }
        }
        const size_t now = total += row_columns[iz].size();
        const size_t done = ++rows_done;
        if (now > kMaxPlacementCandidates) too_many_candidates(rules, now, done, rows);
    }, testing, "candidates");

    Candidates result;
    std::vector<uint64_t> columns;
    for (size_t iz = 0; iz < rows; ++iz) {
        result.tested += row_tested[iz];
        result.positions.insert(result.positions.end(), row_positions[iz].begin(), row_positions[iz].end());
        result.extents.insert(result.extents.end(), row_extents[iz].begin(), row_extents[iz].end());
        std::vector<float>().swap(row_extents[iz]);
        for (uint32_t ix : row_columns[iz]) columns.push_back(uint64_t(ix) + uint64_t(l.counts[0]) * iz);
        std::vector<float>().swap(row_positions[iz]);
        std::vector<uint32_t>().swap(row_columns[iz]);
    }
    if (seeded && !columns.empty()) {
        const std::vector<uint32_t> kept =
            reached_from_seeds(scene, l, geometry, result.positions, columns, threads, progress.part(0.6, 0.9));
        result.unreached = columns.size() - kept.size();
        std::vector<float> reached(3 * kept.size()), extents(2 * kept.size());
        std::vector<uint64_t> reached_columns(kept.size());
        for (size_t k = 0; k < kept.size(); ++k) {
            std::copy_n(&result.positions[3 * size_t(kept[k])], 3, &reached[3 * k]);
            std::copy_n(&result.extents[2 * size_t(kept[k])], 2, &extents[2 * k]);
            reached_columns[k] = columns[kept[k]];
        }
        result.positions = std::move(reached);
        result.extents = std::move(extents);
        columns = std::move(reached_columns);
    }
    result.validation =
        validation_points(l, rules, geometry, result.positions, result.extents, columns, seed, threads, progress.part(0.9, 1.0));
    return result;
}

}  // namespace tetprobe
