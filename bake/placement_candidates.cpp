#include "bake/placement_candidates.h"

#include "bake/inside_test.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace tetprobe {

namespace {

// Lowest cosine between an upward-facing floor's normal and +y (45 degrees).
constexpr double kFloorCosine = 0.7071;

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

// The candidate grid (centred on the region, floor(extent / spacing) points per axis, at least one)
// and the held-out grid between its points (one fewer per axis, or the same single coordinate).
void make_grids(const Scene& scene, const CandidateRules& rules, Grid* candidates, Grid* held_out) {
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
    double lo[3], hi[3];
    scene_bounds(scene, lo, hi);
    if (rules.mode == PlacementMode::walkable) hi[1] += rules.walk_max_height;  // probes stand above the top floor too
    const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (rules.margin > diagonal)
        throw Error(Status::invalid_argument, "margin " + number(rules.margin) + " is larger than the scene (its bounds' diagonal is " +
                                                  number(diagonal) + ")");
    double total = 1;
    for (int a = 0; a < 3; ++a) total *= std::max(1.0, std::floor((hi[a] - lo[a]) / rules.spacing));
    if (total * 2 > double(kMaxPlacementGridPoints))
        throw Error(Status::invalid_argument,
                    "spacing " + number(rules.spacing) + " gives " + number(total) + " candidate grid points over the scene's bounds (" +
                        number(hi[0] - lo[0]) + " x " + number(hi[1] - lo[1]) + " x " + number(hi[2] - lo[2]) +
                        "), more than the " + std::to_string(kMaxPlacementGridPoints / 2) + " placement can test: raise the spacing");
    candidates->spacing = held_out->spacing = rules.spacing;
    for (int a = 0; a < 3; ++a) {
        const size_t n = size_t(std::max(1.0, std::floor((hi[a] - lo[a]) / rules.spacing)));
        const double centre = 0.5 * (lo[a] + hi[a]);
        candidates->counts[a] = n;
        candidates->start[a] = centre - 0.5 * double(n - 1) * rules.spacing;
        held_out->counts[a] = n > 1 ? n - 1 : 1;
        held_out->start[a] = n > 1 ? candidates->start[a] + 0.5 * rules.spacing : centre;
    }
}

class Rules {
public:
    Rules(const Scene& scene, const CandidateRules& rules, const double origin[3])
        : scene_(scene), rules_(rules), caster_(scene, origin), inside_(scene, caster_) {
        for (int a = 0; a < 3; ++a) origin_[a] = origin[a];
        inside_.require_decidable();
    }

    // world: the float position a kept candidate is returned as, so the rules judge that very point.
    bool accepts(const float world[3]) const {
        const float local[3] = {float(double(world[0]) - origin_[0]), float(double(world[1]) - origin_[1]),
                                float(double(world[2]) - origin_[2])};
        if (rules_.mode == PlacementMode::walkable && !above_floor(local)) return false;
        if (!clear_of_surfaces(caster_, local, rules_.margin)) return false;
        return !inside_.inside(local);
    }

private:
    bool above_floor(const float local[3]) const {
        const float down[3] = {0.0f, -1.0f, 0.0f};
        RayHit hit;
        if (!caster_.intersect(local, down, 0.0f, float(rules_.walk_max_height), &hit)) return false;
        if (double(hit.distance) < rules_.walk_min_height) return false;
        const Mesh& mesh = scene_.meshes()[hit.mesh];
        const std::vector<float>& v = caster_.local_vertices(hit.mesh);
        const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
        double e1[3], e2[3];
        for (int k = 0; k < 3; ++k) {
            e1[k] = double(v[3 * tri[1] + k]) - v[3 * tri[0] + k];
            e2[k] = double(v[3 * tri[2] + k]) - v[3 * tri[0] + k];
        }
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double up = n[1] / length;
        if (mesh.materials[mesh.triangle_materials[hit.triangle]].two_sided) up = std::abs(up);
        return up >= kFloorCosine;
    }

    const Scene& scene_;
    const CandidateRules& rules_;
    double origin_[3];
    RayCaster caster_;
    InsideTest inside_;
};

}  // namespace

bool clear_of_surfaces(const RayCaster& caster, const float local[3], double margin) {
    if (!(margin > 0)) return true;
    SurfacePoint nearest;
    return !caster.nearest_surface(local, float(margin), &nearest) || double(nearest.distance) >= margin;
}

size_t candidate_bound(const Scene& scene, const CandidateRules& rules) {
    Grid candidates, held_out;
    make_grids(scene, rules, &candidates, &held_out);
    return candidates.points();
}

Candidates find_candidates(const Scene& scene, const CandidateRules& rules, uint32_t threads,
                           const ProgressRange& progress) {
    Grid grids[2];
    make_grids(scene, rules, &grids[0], &grids[1]);
    double lo[3], hi[3], origin[3];
    scene_bounds(scene, lo, hi);
    for (int a = 0; a < 3; ++a) origin[a] = 0.5 * (lo[a] + hi[a]);
    const Rules test(scene, rules, origin);

    const size_t total = grids[0].points() + grids[1].points();
    std::vector<uint8_t> kept(total, 0);
    run_jobs(total, threads, [&](size_t i) {
        const bool held = i >= grids[0].points();
        double p[3];
        grids[held].point(held ? i - grids[0].points() : i, p);
        const float world[3] = {float(p[0]), float(p[1]), float(p[2])};
        kept[i] = test.accepts(world) ? 1 : 0;
    }, progress, "candidates");

    Candidates result;
    result.grid_points = grids[0].points();
    for (size_t i = 0; i < total; ++i) {
        if (!kept[i]) continue;
        const bool held = i >= grids[0].points();
        double p[3];
        grids[held].point(held ? i - grids[0].points() : i, p);
        std::vector<float>& out = held ? result.held_out : result.positions;
        for (double c : p) out.push_back(float(c));
    }
    return result;
}

}  // namespace tetprobe
