// Whether a point is inside geometry. Each triangle may have a solid side: the back of a one-sided
// triangle (its front, counter-clockwise side, is what a viewer sees, so behind it is the inside of
// a wall), and for a two-sided triangle the enclosed side when its mesh is closed (every edge, by
// exact vertex positions, shared by exactly two triangles wound consistently; the mesh is then a
// solid such as a crate or a pillar, whatever its winding). A two-sided triangle of an open mesh (a
// sheet, a leaf card) has no inside. A point is inside when more than half of a fixed set of rays
// from it first hit a triangle from that triangle's solid side: inside a wall or a crate every ray
// leaves through a solid side, outside at most the rays toward one side do.
#pragma once

#include "bake/ray_caster.h"
#include "bake/scene.h"

#include <cstdint>
#include <vector>

namespace tetprobe {

constexpr uint32_t kInsideTestRays = 64;

class InsideTest {
public:
    // The caster must be built over the same scene; both must outlive this object.
    InsideTest(const Scene& scene, const RayCaster& caster);

    // True when some triangle has a solid side, so that a point can be inside at all.
    bool decidable() const { return solid_triangles_ > 0; }
    // Throws Error(Status::scene) with a message saying why when the test cannot decide anything.
    void require_decidable() const;

    // Whether the local point is inside (see above).
    bool inside(const float local[3]) const;

    // The unit normal of a triangle pointing out of its solid side (toward free space), or zeros
    // when the triangle has no solid side.
    const float* free_normal(uint32_t mesh, uint32_t triangle) const { return &free_normals_[mesh][3 * size_t(triangle)]; }
    // Ray direction `ray` of the fixed set.
    const float* direction(uint32_t ray) const { return &directions_[3 * size_t(ray)]; }

private:
    const RayCaster& caster_;
    std::vector<std::vector<float>> free_normals_;  // per mesh, 3 per triangle
    std::vector<float> directions_;                 // 3 per ray
    size_t solid_triangles_ = 0;
    size_t meshes_ = 0;
};

// The indices of the probes at `positions` (3 floats each, world units) that are inside geometry,
// ascending. When no triangle of the scene has a solid side it throws Error(Status::scene), or, when
// `decided` is given, sets *decided = false and returns none.
std::vector<uint32_t> find_inside_probes(const Scene& scene, const std::vector<float>& positions, uint32_t threads,
                                         bool* decided = nullptr);

// The centre of the scene's meshes' bounds (the local origin of the ray casting), and the bounds.
void scene_bounds(const Scene& scene, double lo[3], double hi[3]);

}  // namespace tetprobe
