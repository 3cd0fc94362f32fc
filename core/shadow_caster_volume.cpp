#include "core/shadow_caster_volume.h"

#include "core/error.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

namespace tetprobe {

namespace {

using Eigen::Vector3d;

// The region as a polyhedron: its vertices and, per face plane, the vertices on it.
struct Polyhedron {
    std::vector<Plane> faces;                // normalized, one per 2D face, no duplicates
    std::vector<Vector3d> vertices;
    std::vector<std::vector<int>> face_vertices;
    struct Edge {
        int face_a, face_b;
        Vector3d a, b;
    };
    std::vector<Edge> edges;
    Vector3d interior = Vector3d::Zero();
};

double plane_distance(const Plane& p, const Vector3d& x) { return p.head<3>().dot(x) + p[3]; }

// Tolerance for "on the plane" at a point of magnitude `magnitude`: loose enough for the error of a
// pivoted LU solve in double, tight enough to be far below any float the tests can see.
double on_plane_tolerance(double magnitude) { return 1e-9 * (1.0 + magnitude); }

std::vector<Plane> normalized_planes(const std::vector<Plane>& planes) {
    std::vector<Plane> out;
    out.reserve(planes.size());
    for (size_t i = 0; i < planes.size(); ++i) {
        const Plane& p = planes[i];
        if (!p.allFinite())
            throw Error(Status::invalid_argument, "plane " + std::to_string(i) + " is not finite");
        double length = p.head<3>().norm();
        if (!(length > 0.0))
            throw Error(Status::invalid_argument, "plane " + std::to_string(i) + " has a zero normal");
        out.push_back(p / length);
    }
    return out;
}

// Vertices from plane triples (pivoted LU), faces (planes holding a 2D polygon of vertices) and
// edges (pairs of faces sharing two vertices). Throws if the planes do not bound a polyhedron.
Polyhedron build_polyhedron(const std::vector<Plane>& planes) {
    const size_t n = planes.size();
    double max_d = 0.0;
    for (const Plane& p : planes) max_d = std::max(max_d, std::abs(p[3]));

    std::vector<Vector3d> vertices;
    for (size_t i = 0; i < n; ++i) {
        for (size_t j = i + 1; j < n; ++j) {
            for (size_t k = j + 1; k < n; ++k) {
                Eigen::Matrix3d a;
                a.row(0) = planes[i].head<3>().transpose();
                a.row(1) = planes[j].head<3>().transpose();
                a.row(2) = planes[k].head<3>().transpose();
                Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
                lu.setThreshold(1e-10);
                if (!lu.isInvertible()) continue;
                Vector3d v = lu.solve(Vector3d(-planes[i][3], -planes[j][3], -planes[k][3]));
                if (!v.allFinite()) continue;
                double tol = on_plane_tolerance(v.cwiseAbs().maxCoeff() + max_d);
                bool feasible = true;
                for (const Plane& p : planes) {
                    if (plane_distance(p, v) < -tol) {
                        feasible = false;
                        break;
                    }
                }
                if (!feasible) continue;
                bool duplicate = false;
                for (const Vector3d& w : vertices) {
                    if ((w - v).cwiseAbs().maxCoeff() <= tol) {
                        duplicate = true;
                        break;
                    }
                }
                if (!duplicate) vertices.push_back(v);
            }
        }
    }
    if (vertices.size() < 4)
        throw Error(Status::degenerate, "the planes do not bound a convex polyhedron with volume");

    double magnitude = max_d;
    for (const Vector3d& v : vertices) magnitude = std::max(magnitude, v.cwiseAbs().maxCoeff());
    const double tol = on_plane_tolerance(magnitude);

    Polyhedron poly;
    poly.vertices = vertices;
    for (const Vector3d& v : vertices) poly.interior += v;
    poly.interior /= double(vertices.size());

    for (size_t i = 0; i < n; ++i) {
        std::vector<int> on;
        for (size_t v = 0; v < vertices.size(); ++v)
            if (std::abs(plane_distance(planes[i], vertices[v])) <= tol) on.push_back(int(v));
        if (on.size() < 3) continue;  // touches the polyhedron in a vertex or an edge at most
        bool duplicate = false;
        for (const std::vector<int>& other : poly.face_vertices) duplicate = duplicate || other == on;
        if (duplicate) continue;
        poly.faces.push_back(planes[i]);
        poly.face_vertices.push_back(on);
    }

    const int faces = int(poly.faces.size());
    for (int a = 0; a < faces; ++a) {
        for (int b = a + 1; b < faces; ++b) {
            std::vector<int> shared;
            std::set_intersection(poly.face_vertices[a].begin(), poly.face_vertices[a].end(),
                                  poly.face_vertices[b].begin(), poly.face_vertices[b].end(),
                                  std::back_inserter(shared));
            if (shared.size() < 2) continue;
            // More than two shared vertices cannot happen on a true edge; take the farthest pair.
            int best_a = shared[0], best_b = shared[1];
            double best = -1.0;
            for (size_t s = 0; s < shared.size(); ++s)
                for (size_t t = s + 1; t < shared.size(); ++t) {
                    double d = (vertices[shared[s]] - vertices[shared[t]]).squaredNorm();
                    if (d > best) best = d, best_a = shared[s], best_b = shared[t];
                }
            poly.edges.push_back({a, b, vertices[best_a], vertices[best_b]});
        }
    }

    // Bounded and closed: every face is a closed polygon (each of its vertices ends exactly two of
    // its edges) and Euler's formula holds. An unbounded region fails here.
    bool closed = faces >= 4 &&
                  int(vertices.size()) - int(poly.edges.size()) + faces == 2;
    for (int f = 0; closed && f < faces; ++f) {
        for (int v : poly.face_vertices[f]) {
            int ends = 0;
            for (const Polyhedron::Edge& e : poly.edges) {
                if (e.face_a != f && e.face_b != f) continue;
                if ((e.a - vertices[v]).cwiseAbs().maxCoeff() <= tol ||
                    (e.b - vertices[v]).cwiseAbs().maxCoeff() <= tol)
                    ++ends;
            }
            if (ends != 2) closed = false;
        }
    }
    if (!closed) throw Error(Status::degenerate, "the planes do not bound a closed convex polyhedron");
    return poly;
}

// The plane through three points (or two points and a direction) oriented so that `interior` is inside.
Plane oriented_plane(const Vector3d& normal_unnormalized, const Vector3d& point, const Vector3d& interior) {
    Vector3d normal = normal_unnormalized.normalized();
    Plane p;
    p.head<3>() = normal;
    p[3] = -normal.dot(point);
    if (plane_distance(p, interior) < 0.0) p = -p;
    return p;
}

}  // namespace

size_t shadow_caster_volume_bound(size_t plane_count) { return 4 * plane_count + 1; }

std::vector<Plane> shadow_caster_volume(const std::vector<Plane>& region, CasterLight light,
                                        const Eigen::Vector3d& light_vector) {
    if (!light_vector.allFinite()) throw Error(Status::invalid_argument, "the light vector is not finite");
    const Polyhedron poly = build_polyhedron(normalized_planes(region));
    const size_t faces = poly.faces.size();

    Vector3d direction = Vector3d::Zero();
    if (light == CasterLight::directional) {
        if (!(light_vector.norm() > 0.0))
            throw Error(Status::invalid_argument, "the light direction is zero");
        direction = light_vector.normalized();
    }

    // A face is kept when the light is on its inner side: for a directional light, when its normal
    // points back toward where the light comes from.
    std::vector<char> kept(faces);
    bool all_kept = true;
    for (size_t f = 0; f < faces; ++f) {
        if (light == CasterLight::directional)
            kept[f] = poly.faces[f].head<3>().dot(direction) <= 1e-12;
        else
            kept[f] = plane_distance(poly.faces[f], light_vector) >=
                      -1e-12 * (1.0 + light_vector.cwiseAbs().maxCoeff());
        all_kept = all_kept && kept[f];
    }

    std::vector<Plane> volume;
    for (size_t f = 0; f < faces; ++f)
        if (kept[f]) volume.push_back(poly.faces[f]);
    // A point light inside the region: every segment from it to the region stays in the region.
    if (all_kept) return volume;

    for (const Polyhedron::Edge& e : poly.edges) {
        if (kept[e.face_a] == kept[e.face_b]) continue;  // not on the silhouette
        Vector3d normal = light == CasterLight::directional ? Vector3d((e.b - e.a).cross(direction))
                                                            : Vector3d((e.b - e.a).cross(light_vector - e.a));
        if (!(normal.norm() > 1e-300)) continue;
        Plane plane = oriented_plane(normal, e.a, poly.interior);
        // An edge whose kept face contains the light's direction gives that face again.
        bool repeated = false;
        for (const Plane& q : volume)
            repeated = repeated || (q - plane).cwiseAbs().maxCoeff() <= on_plane_tolerance(std::abs(plane[3]));
        if (!repeated) volume.push_back(plane);
    }

    if (light == CasterLight::point) {
        // The silhouette planes meet at the light in a cone whose acute apex lets boxes behind the
        // light pass every plane test; a plane through the light with the region on its inner side
        // removes them. Prefer the axis toward the region's centre; any face the light is outside
        // of also separates them.
        Vector3d axis = (poly.interior - light_vector).normalized();
        auto separates = [&](const Vector3d& u) {
            for (const Vector3d& v : poly.vertices)
                if (u.dot(v - light_vector) < 0.0) return false;
            return true;
        };
        if (!separates(axis)) {
            double most_outside = 0.0;
            for (size_t f = 0; f < faces; ++f) {
                double s = plane_distance(poly.faces[f], light_vector);
                if (s < most_outside) most_outside = s, axis = poly.faces[f].head<3>();
            }
        }
        if (axis.allFinite() && separates(axis)) {
            Plane apex;
            apex.head<3>() = axis;
            apex[3] = -axis.dot(light_vector);
            volume.push_back(apex);
        }
    }
    return volume;
}

namespace {

// A plane rejects a shape when even the shape's point farthest inside is outside by more than the
// rounding of float planes and coordinates (magnitude: the sum of the terms' absolute values).
bool outside(double distance, double magnitude) { return distance < -1e-5 * magnitude; }

}  // namespace

bool volume_may_intersect_aabb(const float* planes, size_t plane_count, const float box_min[3],
                               const float box_max[3]) {
    for (size_t i = 0; i < plane_count; ++i) {
        const float* p = planes + 4 * i;
        double distance = p[3], magnitude = std::abs(double(p[3]));
        for (int a = 0; a < 3; ++a) {
            double corner = p[a] >= 0.0f ? box_max[a] : box_min[a];
            distance += double(p[a]) * corner;
            magnitude += std::abs(double(p[a]) * corner);
        }
        if (outside(distance, magnitude)) return false;
    }
    return true;
}

bool volume_may_intersect_sphere(const float* planes, size_t plane_count, const float center[3],
                                 float radius) {
    for (size_t i = 0; i < plane_count; ++i) {
        const float* p = planes + 4 * i;
        double length = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
        double distance = p[3], magnitude = std::abs(double(p[3]));
        for (int a = 0; a < 3; ++a) {
            distance += double(p[a]) * center[a];
            magnitude += std::abs(double(p[a]) * center[a]);
        }
        distance += length * radius;
        magnitude += length * radius;
        if (outside(distance, magnitude)) return false;
    }
    return true;
}

}  // namespace tetprobe
