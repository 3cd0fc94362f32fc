// Ray casting for the bake with Embree 3: one scene of every mesh for path segments, and per
// shadowing light an occlusion scene holding only the meshes that can shadow the probes from it.
// Coordinates are local (world minus an origin) floats; the caster is read-only once built, so
// any number of threads may cast rays through it at once.
#pragma once

#include "bake/scene.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace tetprobe {

// Largest coordinate (and reach) of a ray Embree accepts (its FLT_LARGE is 1.844e18).
constexpr double kLargestRayCoordinate = 1e18;

// The closest point of the scene's surfaces to a query point.
struct SurfacePoint {
    uint32_t mesh = 0;
    uint32_t triangle = 0;
    float point[3] = {0, 0, 0};  // local
    float distance = 0;
};

struct RayHit {
    uint32_t mesh = 0;
    uint32_t triangle = 0;  // index among the mesh's kept triangles
    float distance = 0;
};

class RayCaster {
public:
    // Builds the scene of all meshes, translated by -origin. Throws Error(Status::internal) if Embree
    // fails (the message is Embree's).
    RayCaster(const Scene& scene, const double origin[3]);
    ~RayCaster();
    RayCaster(const RayCaster&) = delete;
    RayCaster& operator=(const RayCaster&) = delete;

    // Adds an occlusion scene of only `meshes` and returns its index for occluded().
    uint32_t add_occlusion_set(const std::vector<uint32_t>& meshes);

    // Closest hit along origin + t * direction for t in (t_near, t_far); false if none.
    bool intersect(const float origin[3], const float direction[3], float t_near, float t_far, RayHit* hit) const;

    // True if something blocks the open segment (t_near, t_far). occlusion_set < 0: every mesh.
    bool occluded(const float origin[3], const float direction[3], float t_near, float t_far,
                  int occlusion_set) const;

    // The closest surface point to `point` (local) within `radius`, found with Embree's point query
    // and an exact-as-float closest point on each candidate triangle; false if no surface is that near.
    bool nearest_surface(const float point[3], float radius, SurfacePoint* nearest) const;

    // The local vertices of a mesh, 3 floats per vertex (followed by one float of padding).
    const std::vector<float>& local_vertices(uint32_t mesh) const { return meshes_[mesh].vertices; }
    // A mesh's kept triangles, 3 vertex indices each.
    const std::vector<uint32_t>& local_indices(uint32_t mesh) const { return meshes_[mesh].indices; }

private:
    struct MeshBuffers {
        std::vector<float> vertices;   // local, padded for Embree's 16-byte loads
        std::vector<uint32_t> indices;
    };
    void* new_scene(const std::vector<uint32_t>& meshes);  // RTCScene

    void* device_ = nullptr;             // RTCDevice
    void* all_ = nullptr;                // RTCScene of every mesh
    std::vector<void*> occlusion_sets_;  // RTCScene each
    std::vector<MeshBuffers> meshes_;
};

}  // namespace tetprobe
