#include "bake/ray_caster.h"

#include "bake/closest_point.h"
#include "core/error.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <string>

namespace tetprobe {

namespace {

struct DeviceErrors {
    std::mutex mutex;
    std::string first;
};

void record_error(void* user, RTCError code, const char* message) {
    auto* errors = static_cast<DeviceErrors*>(user);
    std::lock_guard<std::mutex> lock(errors->mutex);
    if (errors->first.empty())
        errors->first = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

// One per process is enough: Embree reports through the device, and devices are per caster.
DeviceErrors& device_errors() {
    static DeviceErrors errors;
    return errors;
}

void check(RTCDevice device, const char* what) {
    RTCError code = rtcGetDeviceError(device);
    if (code == RTC_ERROR_NONE) return;
    DeviceErrors& errors = device_errors();
    std::lock_guard<std::mutex> lock(errors.mutex);
    std::string message = errors.first.empty() ? "Embree error " + std::to_string(int(code)) : errors.first;
    errors.first.clear();
    if (code == RTC_ERROR_OUT_OF_MEMORY) throw Error(Status::out_of_memory, std::string(what) + ": " + message);
    throw Error(Status::internal, std::string(what) + ": " + message);
}

RTCRay make_ray(const float origin[3], const float direction[3], float t_near, float t_far) {
    RTCRay ray;
    ray.org_x = origin[0], ray.org_y = origin[1], ray.org_z = origin[2];
    ray.dir_x = direction[0], ray.dir_y = direction[1], ray.dir_z = direction[2];
    ray.tnear = t_near;
    ray.tfar = t_far;
    ray.time = 0.0f;
    ray.mask = std::numeric_limits<unsigned>::max();
    ray.id = 0;
    ray.flags = 0;
    return ray;
}

// What the point query's callback reads and narrows: the caster's meshes and the best point so far.
struct NearestSearch {
    const RayCaster* caster;
    SurfacePoint best;
    double best_distance = INFINITY;
};

bool closer_triangle(RTCPointQueryFunctionArguments* args) {
    auto* search = static_cast<NearestSearch*>(args->userPtr);
    const std::vector<float>& v = search->caster->local_vertices(args->geomID);
    const uint32_t* tri = &search->caster->local_indices(args->geomID)[3 * size_t(args->primID)];
    double corner[3][3];
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) corner[i][k] = v[3 * size_t(tri[i]) + k];
    const double p[3] = {args->query->x, args->query->y, args->query->z};
    double q[3];
    closest_point_on_triangle(p, corner[0], corner[1], corner[2], q);
    const double distance = std::sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                                      (q[2] - p[2]) * (q[2] - p[2]));
    if (!(distance <= double(args->query->radius)) || distance > search->best_distance) return false;
    // Ties keep the earlier (mesh, triangle), so the answer does not depend on the traversal order.
    if (distance == search->best_distance &&
        (args->geomID > search->best.mesh ||
         (args->geomID == search->best.mesh && args->primID > search->best.triangle)))
        return false;
    search->best_distance = distance;
    search->best.mesh = args->geomID;
    search->best.triangle = args->primID;
    search->best.distance = float(distance);
    for (int k = 0; k < 3; ++k) search->best.point[k] = float(q[k]);
    args->query->radius = std::nextafter(float(distance), INFINITY);
    return true;
}

// Called from a frame of its own: Embree keeps no frame pointers, so the frame that calls into it
// drops out of a ThreadSanitizer report's stack, and tests/tsan.supp knows Embree's own threads'
// reports (their synchronisation is invisible to it) by the RayCaster frame above this one.
[[gnu::noinline]] RTCDevice new_device() { return rtcNewDevice("verbose=0"); }

}  // namespace

RayCaster::RayCaster(const Scene& scene, const double origin[3]) {
    RTCDevice device = new_device();
    if (!device) throw Error(Status::internal, "Embree could not create a device");
    device_ = device;
    rtcSetDeviceErrorFunction(device, record_error, &device_errors());

    meshes_.resize(scene.meshes().size());
    for (size_t m = 0; m < scene.meshes().size(); ++m) {
        const Mesh& mesh = scene.meshes()[m];
        MeshBuffers& buffers = meshes_[m];
        buffers.vertices.resize(mesh.vertices.size() + 1, 0.0f);  // Embree may read 16 bytes of the last vertex
        for (size_t i = 0; i < mesh.vertices.size(); ++i)
            buffers.vertices[i] = float(double(mesh.vertices[i]) - origin[i % 3]);
        buffers.indices = mesh.indices;
    }
    std::vector<uint32_t> every(meshes_.size());
    for (size_t m = 0; m < every.size(); ++m) every[m] = uint32_t(m);
    try {
        all_ = new_scene(every);
    } catch (...) {
        rtcReleaseDevice(device);
        throw;
    }
}

RayCaster::~RayCaster() {
    for (void* s : occlusion_sets_) rtcReleaseScene(static_cast<RTCScene>(s));
    if (all_) rtcReleaseScene(static_cast<RTCScene>(all_));
    if (device_) rtcReleaseDevice(static_cast<RTCDevice>(device_));
}

void* RayCaster::new_scene(const std::vector<uint32_t>& meshes) {
    RTCDevice device = static_cast<RTCDevice>(device_);
    RTCScene scene = rtcNewScene(device);
    check(device, "creating a scene");
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    // Watertight traversal: a ray through a shared edge must not leak out of a closed room.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    for (uint32_t m : meshes) {
        MeshBuffers& buffers = meshes_[m];
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, buffers.vertices.data(), 0,
                                   3 * sizeof(float), (buffers.vertices.size() - 1) / 3);
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, buffers.indices.data(), 0,
                                   3 * sizeof(uint32_t), buffers.indices.size() / 3);
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(scene, geometry, m);  // the geometry ID is the mesh index
        rtcReleaseGeometry(geometry);
        check(device, "adding a mesh");
    }
    rtcCommitScene(scene);
    check(device, "building the ray-casting scene");
    return scene;
}

uint32_t RayCaster::add_occlusion_set(const std::vector<uint32_t>& meshes) {
    occlusion_sets_.push_back(nullptr);
    occlusion_sets_.back() = new_scene(meshes);
    return uint32_t(occlusion_sets_.size() - 1);
}

bool RayCaster::intersect(const float origin[3], const float direction[3], float t_near, float t_far,
                          RayHit* hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayhit;
    rayhit.ray = make_ray(origin, direction, t_near, t_far);
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(static_cast<RTCScene>(all_), &context, &rayhit);
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit->mesh = rayhit.hit.geomID;
    hit->triangle = rayhit.hit.primID;
    hit->distance = rayhit.ray.tfar;
    return true;
}

bool RayCaster::nearest_surface(const float point[3], float radius, SurfacePoint* nearest) const {
    NearestSearch search{this, SurfacePoint{}};
    RTCPointQuery query;
    query.x = point[0], query.y = point[1], query.z = point[2];
    query.time = 0.0f;
    query.radius = radius;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(static_cast<RTCScene>(all_), &query, &context, closer_triangle, &search);
    if (std::isinf(search.best_distance)) return false;
    *nearest = search.best;
    return true;
}

bool RayCaster::occluded(const float origin[3], const float direction[3], float t_near, float t_far,
                         int occlusion_set) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = make_ray(origin, direction, t_near, t_far);
    RTCScene scene = static_cast<RTCScene>(occlusion_set < 0 ? all_ : occlusion_sets_[size_t(occlusion_set)]);
    rtcOccluded1(scene, &context, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace tetprobe
