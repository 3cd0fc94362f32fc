// Shadow caster volumes (L. Hutchinson, "Shadow Caster Volumes For The Culling Of Potential Shadow
// Casters", 2006): the convex volume of everything that can cast a shadow from a light into a convex
// region. Planes are (nx, ny, nz, d), inward: x is inside when n.x + d >= 0.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace tetprobe {

using Plane = Eigen::Vector4d;

enum class CasterLight { directional, point };

// Most planes a volume built from plane_count planes can have: the kept planes, one plane per
// silhouette edge (a convex polyhedron of F faces has at most 3F - 6 edges) and the apex plane.
size_t shadow_caster_volume_bound(size_t plane_count);

// Builds the shadow caster volume of the bounded convex polyhedron `region` for a light.
// light_vector is the light's position (point) or the direction its light travels (directional).
// Planes facing the light are kept, a plane through each silhouette edge and the light (or
// containing the light's direction) is added, and for a point light a plane through the light
// bounds the cone's apex, which removes the false positives of box tests near the acute apex.
// A point light inside the region gives the region itself (no caster outside it can shadow it);
// a directional light gives an unbounded volume. Output planes are normalized. Throws
// Error(Status::degenerate) if the region is empty or unbounded and Error(Status::invalid_argument)
// for a non-finite input or a zero direction.
std::vector<Plane> shadow_caster_volume(const std::vector<Plane>& region, CasterLight light,
                                        const Eigen::Vector3d& light_vector);

// True unless the box lies entirely outside one plane (conservative: a box that intersects the
// volume always returns true; a small relative tolerance absorbs float rounding).
bool volume_may_intersect_aabb(const float* planes, size_t plane_count, const float box_min[3],
                               const float box_max[3]);

// True unless the sphere lies entirely outside one plane (conservative, as the box test).
bool volume_may_intersect_sphere(const float* planes, size_t plane_count, const float center[3],
                                 float radius);

}  // namespace tetprobe
