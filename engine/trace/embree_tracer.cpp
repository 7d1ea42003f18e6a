#include "trace/embree_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cassert>
#include <cstring>
#include <string>

#include "util/error.h"

namespace edacrt {
namespace {

/// An intersect context that also receives the occluder an occlusion query accepted
/// (rtcOccluded1 itself reports only whether the ray is blocked).
struct OcclusionContext {
    RTCIntersectContext base;  // first member: Embree passes &base back to the filter
    Hit* hit;
};

void record_occluder(const RTCFilterFunctionNArguments* args) {
    assert(args->N == 1);
    auto* context = reinterpret_cast<OcclusionContext*>(args->context);
    // During a filter call the candidate's distance is the ray's tfar.
    *context->hit = {RTCRayN_tfar(args->ray, 1, 0), std::int32_t(RTCHitN_primID(args->hit, 1, 0)),
                     RTCHitN_u(args->hit, 1, 0), RTCHitN_v(args->hit, 1, 0)};
}

RTCRay to_embree(const Ray& ray) {
    RTCRay r;
    r.org_x = ray.org.x;
    r.org_y = ray.org.y;
    r.org_z = ray.org.z;
    r.dir_x = ray.dir.x;
    r.dir_y = ray.dir.y;
    r.dir_z = ray.dir.z;
    r.tnear = ray.tmin;
    r.tfar = ray.tmax;
    r.time = 0.0f;
    r.mask = ~0u;
    r.id = 0;
    r.flags = 0;
    return r;
}

}  // namespace

EmbreeTracer::EmbreeTracer() {
    // No "threads=N" here: that would limit oneTBB for the whole process.
    device_ = rtcNewDevice(nullptr);
    if (!device_)
        throw InputError("Embree: cannot create a device (error " +
                         std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
}

EmbreeTracer::~EmbreeTracer() {
    if (scene_) rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
}

void EmbreeTracer::set_scene(const Scene& scene) {
    if (scene_) rtcReleaseScene(scene_);
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), scene.positions.size()));
    auto* indices = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), scene.triangles.size()));
    if (!vertices || !indices) throw InputError("Embree: cannot allocate the geometry buffers");
    std::memcpy(vertices, scene.positions.data(), scene.positions.size() * sizeof(glm::vec3));
    std::memcpy(indices, scene.triangles.data(),
                scene.triangles.size() * 3 * sizeof(std::uint32_t));
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
}

TraceStats EmbreeTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                     TraceDetail*) {
    assert(rays.size() == hits.size() && scene_);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            Hit& hit = hits[i] = Hit{};
            if (query == Query::closest) {
                RTCIntersectContext context;
                rtcInitIntersectContext(&context);
                RTCRayHit ray_hit;
                ray_hit.ray = to_embree(rays[i]);
                ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene_, &context, &ray_hit);
                if (ray_hit.hit.geomID != RTC_INVALID_GEOMETRY_ID)
                    hit = {ray_hit.ray.tfar, std::int32_t(ray_hit.hit.primID), ray_hit.hit.u,
                           ray_hit.hit.v};
            } else {
                OcclusionContext context;
                rtcInitIntersectContext(&context.base);
                context.base.filter = record_occluder;
                context.hit = &hit;
                RTCRay ray = to_embree(rays[i]);
                rtcOccluded1(scene_, &context.base, &ray);
                if (ray.tfar != -kInfinity) hit = Hit{};  // not occluded after all
            }
        }
    });
    // Embree does not report its internal test counts.
    TraceStats stats;
    stats.rays = rays.size();
    return stats;
}

}  // namespace edacrt
