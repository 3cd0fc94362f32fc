#include "bake/placement_candidates.h"

#include "bake/inside_test.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace tetprobe {

namespace {

// Lowest cosine between an upward-facing floor's normal and +y, the up of the frame the rules run in (45 degrees).
constexpr double kFloorCosine = 0.7071;
// Floors a walkable column may have (storeys, tables, stairs); more are ignored.
constexpr size_t kMaxFloorsPerColumn = 64;

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

struct Grid {
    double start[3] = {0, 0, 0};
    size_t counts[3] = {1, 1, 1};
    double spacing = 1;

    size_t points() const { return counts[0] * counts[1] * counts[2]; }
    void point(size_t i, double out[3]) const {
        const size_t x = i % counts[0], y = (i / counts[0]) % counts[1], z = i / (counts[0] * counts[1]);
        out[0] = start[0] + spacing * double(x), out[1] = start[1] + spacing * double(y), out[2] = start[2] + spacing * double(z);
    }
};

[[noreturn]] void too_many(const CandidateRules& rules, double points, const double lo[3], const double hi[3]) {
    throw Error(Status::invalid_argument,
                "spacing " + number(rules.spacing) + " gives " + number(points) + " candidate points over the scene's bounds (" +
                    number(hi[0] - lo[0]) + " x " + number(hi[1] - lo[1]) + " x " + number(hi[2] - lo[2]) +
                    "), more than the " + std::to_string(kMaxPlacementGridPoints / 2) + " placement can test: raise the spacing");
}

// Checks the rules and makes the candidate grid (centred on the scene's bounds, floor(extent /
// spacing) points per axis, at least one) and the held-out grid between its points (one fewer per
// axis, or the same single coordinate). In the walkable mode the grids are columns (one y).
void make_grids(const Scene& scene, const CandidateRules& rules, Grid* candidates, Grid* held_out, double lo[3],
                double hi[3]) {
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
    scene_bounds(scene, lo, hi);
    const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (rules.margin > diagonal)
        throw Error(Status::invalid_argument, "margin " + number(rules.margin) + " is larger than the scene (its bounds' diagonal is " +
                                                  number(diagonal) + ")");
    const bool walkable = rules.mode == PlacementMode::walkable;
    double total = 1;
    for (int a = 0; a < 3; ++a)
        if (!(walkable && a == 1)) total *= std::max(1.0, std::floor((hi[a] - lo[a]) / rules.spacing));
    if (total * 2 > double(kMaxPlacementGridPoints)) too_many(rules, total, lo, hi);
    candidates->spacing = held_out->spacing = rules.spacing;
    for (int a = 0; a < 3; ++a) {
        const size_t n = walkable && a == 1 ? 1 : size_t(std::max(1.0, std::floor((hi[a] - lo[a]) / rules.spacing)));
        const double centre = 0.5 * (lo[a] + hi[a]);
        candidates->counts[a] = n;
        candidates->start[a] = centre - 0.5 * double(n - 1) * rules.spacing;
        held_out->counts[a] = n > 1 ? n - 1 : 1;
        held_out->start[a] = n > 1 ? candidates->start[a] + 0.5 * rules.spacing : centre;
    }
}

// Heights above a floor where walkable candidates stand: every spacing across the band, centred in
// it (one in the middle of a band thinner than the spacing).
std::vector<double> band_heights(const CandidateRules& rules) {
    const double band = rules.walk_max_height - rules.walk_min_height;
    const size_t layers = size_t(std::max(1.0, std::floor(band / rules.spacing)));
    std::vector<double> heights;
    for (size_t k = 0; k < layers; ++k)
        heights.push_back(rules.walk_min_height + 0.5 * band + (double(k) - 0.5 * double(layers - 1)) * rules.spacing);
    return heights;
}

// The scene's geometry as the rules see it: ray casting, the inside test and floors.
class Geometry {
public:
    Geometry(const Scene& scene, const double origin[3]) : scene_(scene), caster_(scene, origin), inside_(scene, caster_) {
        for (int a = 0; a < 3; ++a) origin_[a] = origin[a];
        inside_.require_decidable();
    }

    // world: the float position a kept candidate is returned as, so the rules judge that very point.
    bool accepts(const float world[3], double margin) const {
        const float local[3] = {float(double(world[0]) - origin_[0]), float(double(world[1]) - origin_[1]),
                                float(double(world[2]) - origin_[2])};
        return clear_of_surfaces(caster_, local, margin) && !inside_.inside(local);
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

// The points the rules are applied to: the grids' points, or in the walkable mode each column's
// floors times the band's heights; candidates first, then held-out points.
std::vector<float> raw_points(const Grid grids[2], const CandidateRules& rules, const Geometry& geometry,
                              const double lo[3], const double hi[3], size_t* candidate_count) {
    std::vector<float> points;
    for (int g = 0; g < 2; ++g) {
        for (size_t i = 0; i < grids[g].points(); ++i) {
            double p[3];
            grids[g].point(i, p);
            if (rules.mode == PlacementMode::whole) {
                for (double c : p) points.push_back(float(c));
                continue;
            }
            const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
            const double step = 1e-5 * extent;
            for (double floor : geometry.floors(p[0], p[2], hi[1] + rules.walk_max_height + rules.spacing, step)) {
                // The band ends below the surface above the floor (a ceiling, a table top) by the
                // margin, and at the scene's bounds: above a roof half the rays escape, so the
                // inside test alone would keep such points.
                const double ceiling = geometry.ceiling(p[0], floor, p[2], step);
                for (double h : band_heights(rules)) {
                    const double y = floor + h;
                    if (y < ceiling && y <= ceiling - rules.margin && y <= hi[1])
                        points.insert(points.end(), {float(p[0]), float(y), float(p[2])});
                }
            }
            if (points.size() / 3 > kMaxPlacementGridPoints) too_many(rules, double(points.size() / 3), lo, hi);
        }
        if (g == 0) *candidate_count = points.size() / 3;
    }
    return points;
}

double centre(const double lo, const double hi) { return 0.5 * (lo + hi); }

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

size_t candidate_bound(const Scene& scene, const CandidateRules& rules) {
    AxisTurn back;
    if (turned_for_walking(scene, rules, &back)) return candidate_bound(scene.meshes_turned(back.inverse()), rules);
    Grid grids[2];
    double lo[3], hi[3];
    make_grids(scene, rules, &grids[0], &grids[1], lo, hi);
    if (rules.mode == PlacementMode::whole) return grids[0].points();
    const double origin[3] = {centre(lo[0], hi[0]), centre(lo[1], hi[1]), centre(lo[2], hi[2])};
    const Geometry geometry(scene, origin);
    size_t candidates = 0;
    raw_points(grids, rules, geometry, lo, hi, &candidates);
    return candidates;
}

Candidates find_candidates(const Scene& scene, const CandidateRules& rules, uint32_t threads,
                           const Progress& progress) {
    AxisTurn back;
    if (turned_for_walking(scene, rules, &back)) {
        Candidates turned = find_candidates(scene.meshes_turned(back.inverse()), rules, threads, progress);
        for (std::vector<float>* points : {&turned.positions, &turned.held_out})
            for (size_t i = 0; i < points->size(); i += 3) back.apply(&(*points)[i], &(*points)[i]);
        return turned;
    }
    Grid grids[2];
    double lo[3], hi[3];
    make_grids(scene, rules, &grids[0], &grids[1], lo, hi);
    const double origin[3] = {centre(lo[0], hi[0]), centre(lo[1], hi[1]), centre(lo[2], hi[2])};
    const Geometry geometry(scene, origin);
    size_t candidate_count = 0;
    const std::vector<float> points = raw_points(grids, rules, geometry, lo, hi, &candidate_count);

    const size_t total = points.size() / 3;
    std::vector<uint8_t> kept(total, 0);
    run_jobs(total, threads, [&](size_t i) { kept[i] = geometry.accepts(&points[3 * i], rules.margin) ? 1 : 0; },
             progress, "candidates");

    Candidates result;
    result.grid_points = candidate_count;
    for (size_t i = 0; i < total; ++i)
        if (kept[i]) {
            std::vector<float>& out = i < candidate_count ? result.positions : result.held_out;
            out.insert(out.end(), &points[3 * i], &points[3 * i] + 3);
        }
    return result;
}

}  // namespace tetprobe
