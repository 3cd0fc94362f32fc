// Shadow caster volumes against a brute-force reference: a box (or sphere) can cast a shadow into the
// region iff one of its points x lies on a segment from the light to a point of the region (for a
// directional light: iff the ray from x along the light's direction enters the region). The
// reference decides that by exact ray and segment clipping at many sampled points; the volume test
// must never say "no" where the reference found "yes". False positives are counted and reported.
#include <catch2/catch.hpp>

#include "core/error.h"
#include "core/shadow_caster_volume.h"

#include <Eigen/Dense>

#include <cstdio>
#include <random>

using namespace tetprobe;
using Eigen::Vector3d;

namespace {

struct Region {
    std::vector<Plane> planes;  // inward, not necessarily normalized
    Vector3d lo, hi;            // a box around the region (for rejection sampling)
    std::vector<double> flat;   // the planes as 4 doubles each: the reference's hot loops avoid Eigen,
                                // which is slow in the Debug + sanitizer build
    std::vector<Vector3d> samples;  // points of the region
};

bool inside(const std::vector<Plane>& planes, const Vector3d& x, double slack = 0.0) {
    for (const Plane& p : planes)
        if (p.head<3>().dot(x) + p[3] < -slack * p.head<3>().norm()) return false;
    return true;
}

// Whether origin + t * u meets the region for some t in [t0, t1] (exact interval clipping).
bool ray_meets_region(const std::vector<double>& planes, const double origin[3], const double u[3], double t0,
                      double t1) {
    for (size_t i = 0; i < planes.size(); i += 4) {
        const double* p = &planes[i];
        double a = p[0] * u[0] + p[1] * u[1] + p[2] * u[2];
        double b = p[0] * origin[0] + p[1] * origin[1] + p[2] * origin[2] + p[3];  // a t + b >= 0
        if (a == 0.0) {
            if (b < 0.0) return false;
        } else if (a > 0.0) {
            t0 = std::max(t0, -b / a);
        } else {
            t1 = std::min(t1, -b / a);
        }
        if (t0 > t1) return false;
    }
    return true;
}

// Whether the segment from a to b meets the box (slab clipping).
bool segment_meets_box(const Vector3d& a, const Vector3d& b, const Vector3d& lo, const Vector3d& hi) {
    double t0 = 0.0, t1 = 1.0;
    Vector3d d = b - a;
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0.0) {
            if (a[k] < lo[k] || a[k] > hi[k]) return false;
            continue;
        }
        double s = (lo[k] - a[k]) / d[k], t = (hi[k] - a[k]) / d[k];
        if (s > t) std::swap(s, t);
        t0 = std::max(t0, s), t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    return true;
}

Region random_box(std::mt19937& rng) {
    std::uniform_real_distribution<double> centre(-5, 5), half(0.2, 3);
    Vector3d c(centre(rng), centre(rng), centre(rng)), h(half(rng), half(rng), half(rng));
    Region r;
    for (int a = 0; a < 3; ++a) {
        Plane low = Plane::Zero(), high = Plane::Zero();
        low[a] = 1, low[3] = -(c[a] - h[a]);
        high[a] = -1, high[3] = c[a] + h[a];
        r.planes.push_back(low * 2.5);  // unnormalized on purpose
        r.planes.push_back(high);
    }
    r.lo = c - h, r.hi = c + h;
    return r;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
    std::normal_distribution<double> g;
    Eigen::Matrix3d m;
    for (int i = 0; i < 9; ++i) m.data()[i] = g(rng);
    Eigen::HouseholderQR<Eigen::Matrix3d> qr(m);
    return qr.householderQ();
}

Region random_frustum(std::mt19937& rng) {
    std::uniform_real_distribution<double> centre(-5, 5), near_d(0.1, 1.0), depth(1.0, 9.0), tangent(0.2, 1.5);
    Vector3d c(centre(rng), centre(rng), centre(rng));
    Eigen::Matrix3d frame = random_rotation(rng);
    Vector3d right = frame.col(0), up = frame.col(1), forward = frame.col(2);
    double n = near_d(rng), f = n + depth(rng), tx = tangent(rng), ty = tangent(rng);
    auto plane_through = [&](const Vector3d& normal) {
        Plane p;
        p.head<3>() = normal;
        p[3] = -normal.dot(c);
        return p;
    };
    Region r;
    Plane near_plane = plane_through(forward);
    near_plane[3] -= n;
    Plane far_plane = plane_through(-forward);
    far_plane[3] += f;
    r.planes = {near_plane, far_plane, plane_through(right + tx * forward), plane_through(-right + tx * forward),
                plane_through(up + ty * forward), plane_through(-up + ty * forward)};
    r.lo = r.hi = c;
    for (int corner = 0; corner < 8; ++corner) {
        double depth_at = corner & 4 ? f : n;
        Vector3d p = c + forward * depth_at + right * ((corner & 1 ? 1 : -1) * tx * depth_at) +
                     up * ((corner & 2 ? 1 : -1) * ty * depth_at);
        r.lo = r.lo.cwiseMin(p), r.hi = r.hi.cwiseMax(p);
    }
    return r;
}

// Planes tangent to a sphere at random points: a general convex polyhedron (bounded when the
// normals surround the centre; unbounded draws are rejected by the library and skipped here).
Region random_polytope(std::mt19937& rng) {
    std::uniform_real_distribution<double> centre(-4, 4), radius(0.5, 3);
    std::normal_distribution<double> g;
    Vector3d c(centre(rng), centre(rng), centre(rng));
    double r0 = radius(rng);
    Region r;
    for (int k = 0; k < 12; ++k) {
        Vector3d n(g(rng), g(rng), g(rng));
        n.normalize();
        Plane p;
        p.head<3>() = -n;  // inward
        p[3] = n.dot(c) + r0;
        r.planes.push_back(p);
    }
    // Most of the polytope lies within 2 r0 of the centre; points beyond are just not sampled.
    r.lo = c - Vector3d::Constant(2 * r0), r.hi = c + Vector3d::Constant(2 * r0);
    return r;
}

// Fills region.flat and draws up to 64 points of the region by rejection from its box.
void prepare(Region& region, std::mt19937& rng) {
    for (const Plane& p : region.planes)
        for (int c = 0; c < 4; ++c) region.flat.push_back(p[c]);
    std::uniform_real_distribution<double> u(0, 1);
    for (int attempt = 0; attempt < 20000 && region.samples.size() < 64; ++attempt) {
        Vector3d p;
        for (int k = 0; k < 3; ++k) p[k] = region.lo[k] + u(rng) * (region.hi[k] - region.lo[k]);
        if (inside(region.planes, p)) region.samples.push_back(p);
    }
}

bool random_point_in(const Region& region, std::mt19937& rng, Vector3d* out) {
    if (region.samples.empty()) return false;
    *out = region.samples[std::uniform_int_distribution<size_t>(0, region.samples.size() - 1)(rng)];
    return true;
}

std::vector<float> to_floats(const std::vector<Plane>& planes) {
    std::vector<float> out;
    for (const Plane& p : planes)
        for (int c = 0; c < 4; ++c) out.push_back(float(p[c]));
    return out;
}

// Whether point x can cast a shadow into the region.
bool casts_into(const Region& region, bool directional, const Vector3d& light, const Vector3d& x) {
    const double origin[3] = {x[0], x[1], x[2]};
    if (directional) {
        const double u[3] = {light[0], light[1], light[2]};
        return ray_meets_region(region.flat, origin, u, 0.0, INFINITY);
    }
    const double u[3] = {x[0] - light[0], x[1] - light[1], x[2] - light[2]};  // points L + s (x - L), s >= 1
    return ray_meets_region(region.flat, origin, u, 0.0, INFINITY);
}

struct Tally {
    int positives = 0, negatives = 0, false_positives = 0, false_negatives = 0;
};

void check_shapes(const Region& region, bool directional, const Vector3d& light, const std::vector<float>& volume,
                  std::mt19937& rng, Tally& boxes, Tally& spheres) {
    std::uniform_real_distribution<double> centre(-15, 15), half(0.05, 2.0), u(0, 1), jitter(-0.3, 0.3);
    for (int query = 0; query < 24; ++query) {
        Vector3d c(centre(rng), centre(rng), centre(rng));
        // Half of the queries sit near the volume's boundary: on a segment toward the region, jittered.
        Vector3d p;
        if (query % 2 == 0 && random_point_in(region, rng, &p)) {
            double s = u(rng) * 1.5;
            c = directional ? Vector3d(p - light * (s * 8.0)) : Vector3d(light + (p - light) * s);
            c += Vector3d(jitter(rng), jitter(rng), jitter(rng)) * 3.0;
        }
        const double h = half(rng);
        const Vector3d lo = c - Vector3d::Constant(h), hi = c + Vector3d::Constant(h);

        // Reference for the box: sampled points of the box, then segments from the light to sampled
        // points of the region clipped against the box.
        bool box_reference = false;
        const int grid = 4;
        for (int i = 0; i <= grid && !box_reference; ++i)
            for (int j = 0; j <= grid && !box_reference; ++j)
                for (int k = 0; k <= grid && !box_reference; ++k) {
                    Vector3d x = lo + (hi - lo).cwiseProduct(Vector3d(i, j, k) / grid);
                    box_reference = casts_into(region, directional, light, x);
                }
        for (int s = 0; s < 48 && !box_reference; ++s) {
            if (!random_point_in(region, rng, &p)) break;
            Vector3d far_end = directional ? Vector3d(p - light * 100.0) : light;
            box_reference = segment_meets_box(p, far_end, lo, hi);
        }
        const float flo[3] = {float(lo[0]), float(lo[1]), float(lo[2])}, fhi[3] = {float(hi[0]), float(hi[1]), float(hi[2])};
        const bool box_test = volume_may_intersect_aabb(volume.data(), volume.size() / 4, flo, fhi);
        (box_reference ? boxes.positives : boxes.negatives)++;
        if (box_reference && !box_test) {
            ++boxes.false_negatives;
            FAIL_CHECK("false negative: box [" << lo.transpose() << "] - [" << hi.transpose() << "]");
        }
        if (!box_reference && box_test) ++boxes.false_positives;

        // Sphere of radius h about c: points on concentric shells, then the same segments.
        bool sphere_reference = casts_into(region, directional, light, c);
        for (int s = 0; s < 60 && !sphere_reference; ++s) {
            std::normal_distribution<double> g;
            Vector3d d(g(rng), g(rng), g(rng));
            Vector3d x = c + d.normalized() * h * (s % 3 == 0 ? 1.0 : std::cbrt(u(rng)));
            sphere_reference = casts_into(region, directional, light, x);
        }
        const float fc[3] = {float(c[0]), float(c[1]), float(c[2])};
        const bool sphere_test = volume_may_intersect_sphere(volume.data(), volume.size() / 4, fc, float(h));
        (sphere_reference ? spheres.positives : spheres.negatives)++;
        if (sphere_reference && !sphere_test) {
            ++spheres.false_negatives;
            FAIL_CHECK("false negative: sphere at " << c.transpose() << " radius " << h);
        }
        if (!sphere_reference && sphere_test) ++spheres.false_positives;
    }
}

// Fewer trials in the unoptimized sanitizer build, where Eigen's expression templates are slow.
#ifdef NDEBUG
constexpr int kTrials = 240;
#else
constexpr int kTrials = 36;
#endif

}  // namespace

TEST_CASE("shadow caster volume: no false negatives against brute force on random regions and lights", "[scv]") {
    std::mt19937 rng(20240611);
    std::uniform_real_distribution<double> far(-15, 15), u(0, 1);
    std::normal_distribution<double> g;
    Tally boxes, spheres;
    int volumes = 0, skipped = 0, inside_lights = 0;
    for (int trial = 0; trial < kTrials; ++trial) {
        Region region = trial % 3 == 0 ? random_box(rng) : trial % 3 == 1 ? random_frustum(rng) : random_polytope(rng);
        prepare(region, rng);
        const bool directional = trial % 4 == 3;
        Vector3d light;
        if (directional) {
            light = Vector3d(g(rng), g(rng), g(rng)).normalized();
        } else {
            light = Vector3d(far(rng), far(rng), far(rng));
            Vector3d p;
            if (trial % 10 == 1 && random_point_in(region, rng, &p)) light = p, ++inside_lights;
        }
        std::vector<Plane> planes;
        try {
            planes = shadow_caster_volume(region.planes, directional ? CasterLight::directional : CasterLight::point, light);
        } catch (const Error& e) {
            REQUIRE(trial % 3 == 2);  // only random tangent planes may fail to bound a polyhedron
            REQUIRE(e.status() == tetprobe::Status::degenerate);
            ++skipped;
            continue;
        }
        ++volumes;
        REQUIRE(planes.size() <= shadow_caster_volume_bound(region.planes.size()));
        // The volume contains the region and, for a point light, the light itself.
        Vector3d p;
        for (const Vector3d& q : region.samples) CHECK(inside(planes, q, 1e-9));
        if (!directional) CHECK(inside(planes, light, 1e-9));
        check_shapes(region, directional, light, to_floats(planes), rng, boxes, spheres);
    }
    CHECK(boxes.false_negatives == 0);
    CHECK(spheres.false_negatives == 0);
    CHECK(volumes > kTrials * 4 / 5);
    CHECK(boxes.positives > kTrials * 4);
    CHECK(boxes.negatives > kTrials * 4);
    char report[512];
    std::snprintf(report, sizeof report,
                  "shadow caster volumes: %d volumes (%d regions unbounded, %d lights inside); boxes: %d positive, "
                  "%d negative, %d false positives (%.1f%% of negatives); spheres: %d positive, %d negative, "
                  "%d false positives (%.1f%% of negatives)",
                  volumes, skipped, inside_lights, boxes.positives, boxes.negatives, boxes.false_positives,
                  100.0 * boxes.false_positives / std::max(1, boxes.negatives), spheres.positives, spheres.negatives,
                  spheres.false_positives, 100.0 * spheres.false_positives / std::max(1, spheres.negatives));
    WARN(report);
}

TEST_CASE("shadow caster volume: a point light inside the region gives the region", "[scv]") {
    std::vector<Plane> cube;
    for (int a = 0; a < 3; ++a) {
        Plane low = Plane::Zero(), high = Plane::Zero();
        low[a] = 1, low[3] = 1, high[a] = -1, high[3] = 1;
        cube.push_back(low), cube.push_back(high);
    }
    std::vector<Plane> volume = shadow_caster_volume(cube, CasterLight::point, Vector3d(0.2, -0.3, 0.5));
    REQUIRE(volume.size() == 6);
    for (size_t i = 0; i < 6; ++i) CHECK((volume[i] - cube[i]).norm() < 1e-12);
}

TEST_CASE("shadow caster volume: point light above a cube is the hull of the cube and the light", "[scv]") {
    std::vector<Plane> cube;
    for (int a = 0; a < 3; ++a) {
        Plane low = Plane::Zero(), high = Plane::Zero();
        low[a] = 1, low[3] = 1, high[a] = -1, high[3] = 1;
        cube.push_back(low), cube.push_back(high);
    }
    const Vector3d light(0, 5, 0);
    std::vector<Plane> volume = shadow_caster_volume(cube, CasterLight::point, light);
    // Kept: the 5 faces the light does not see; added: 4 silhouette planes and the apex plane.
    REQUIRE(volume.size() == 10);
    for (int corner = 0; corner < 8; ++corner) {
        Vector3d p(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
        CHECK(inside(volume, p, 1e-12));
    }
    CHECK(inside(volume, light, 1e-12));
    CHECK(inside(volume, Vector3d(0.5, 2.9, 0.0), 0));  // the cone's half width at y is (5 - y) / 4
    CHECK(!inside(volume, Vector3d(0.55, 2.9, 0.0), 0));
    // The apex plane: a box just behind the light straddles every silhouette plane but not it.
    std::vector<float> f = to_floats(volume);
    const float lo[3] = {-0.5f, 5.2f, -0.5f}, hi[3] = {0.5f, 6.0f, 0.5f};
    CHECK(!volume_may_intersect_aabb(f.data(), volume.size(), lo, hi));
    std::vector<float> without_apex(f.begin(), f.end() - 4);
    CHECK(volume_may_intersect_aabb(without_apex.data(), without_apex.size() / 4, lo, hi));
}

TEST_CASE("shadow caster volume: directional light sweeps the region to infinity", "[scv]") {
    std::vector<Plane> cube;
    for (int a = 0; a < 3; ++a) {
        Plane low = Plane::Zero(), high = Plane::Zero();
        low[a] = 1, low[3] = 1, high[a] = -1, high[3] = 1;
        cube.push_back(low), cube.push_back(high);
    }
    std::vector<Plane> volume = shadow_caster_volume(cube, CasterLight::directional, Vector3d(0, -2, 0));
    // The top face sees the light and goes; the four sides and the bottom stay (sides contain the direction).
    REQUIRE(volume.size() == 5);
    CHECK(inside(volume, Vector3d(0.9, 1e6, -0.9), 0));
    CHECK(!inside(volume, Vector3d(1.1, 10, 0), 0));
    CHECK(!inside(volume, Vector3d(0, -1.1, 0), 0));

    // A slanted light: silhouette planes appear and contain the direction.
    const Vector3d d = Vector3d(1, -2, 0.5).normalized();
    volume = shadow_caster_volume(cube, CasterLight::directional, d);
    for (const Plane& p : volume) CHECK(p.head<3>().dot(d) <= 1e-12);
    CHECK(inside(volume, Vector3d(0.5, 0.5, 0.5) - 100.0 * d, 1e-9));
}

TEST_CASE("shadow caster volume: bad regions and lights are reported", "[scv]") {
    std::vector<Plane> open_box;
    for (int a = 0; a < 3; ++a) {
        Plane low = Plane::Zero(), high = Plane::Zero();
        low[a] = 1, low[3] = 1, high[a] = -1, high[3] = 1;
        open_box.push_back(low);
        if (a != 1) open_box.push_back(high);
    }
    try {
        shadow_caster_volume(open_box, CasterLight::point, Vector3d(0, 5, 0));
        FAIL("an unbounded region was accepted");
    } catch (const Error& e) {
        CHECK(e.status() == tetprobe::Status::degenerate);
    }
    std::vector<Plane> empty = {Plane(1, 0, 0, -1), Plane(-1, 0, 0, -1), Plane(0, 1, 0, 1), Plane(0, -1, 0, 1),
                                Plane(0, 0, 1, 1), Plane(0, 0, -1, 1)};
    CHECK_THROWS_AS(shadow_caster_volume(empty, CasterLight::point, Vector3d(0, 5, 0)), Error);
    std::vector<Plane> cube = {Plane(1, 0, 0, 1), Plane(-1, 0, 0, 1), Plane(0, 1, 0, 1), Plane(0, -1, 0, 1),
                               Plane(0, 0, 1, 1), Plane(0, 0, -1, 1)};
    CHECK_THROWS_AS(shadow_caster_volume(cube, CasterLight::directional, Vector3d(0, 0, 0)), Error);
    CHECK_THROWS_AS(shadow_caster_volume(cube, CasterLight::point, Vector3d(NAN, 0, 0)), Error);
    cube.push_back(Plane(0, 0, 0, 1));
    CHECK_THROWS_AS(shadow_caster_volume(cube, CasterLight::point, Vector3d(0, 5, 0)), Error);
    // Redundant and duplicated planes change nothing.
    cube.pop_back();
    std::vector<Plane> padded = cube;
    padded.push_back(Plane(1, 1, 1, 10));  // far outside: redundant
    padded.push_back(cube[0] * 3.0);       // the same plane again
    std::vector<Plane> a = shadow_caster_volume(cube, CasterLight::point, Vector3d(3, 4, 5));
    std::vector<Plane> b = shadow_caster_volume(padded, CasterLight::point, Vector3d(3, 4, 5));
    REQUIRE(a.size() == b.size());
    for (size_t i = 0; i < a.size(); ++i) CHECK((a[i] - b[i]).norm() < 1e-12);
}
