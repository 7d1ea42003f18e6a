#include "trace/embree_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cstring>
#include <string>
#include <vector>

#include "util/error.h"

namespace edacrt {
namespace {

/// An intersect context that also receives the occluders an occlusion query accepted
/// (rtcOccluded* itself reports only whether a ray is blocked). Rays carry their index in the
/// batch as their id, so the filter finds each lane's hit in every mode (1, 8, stream).
struct OcclusionContext {
    RTCIntersectContext base;  // first member: Embree passes &base back to the filter
    Hit* hits;
};

void record_occluders(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const OcclusionContext*>(args->context);
    for (unsigned lane = 0; lane < args->N; ++lane) {
        if (args->valid[lane] != -1) continue;
        // During a filter call the candidate's distance is the ray's tfar.
        context->hits[RTCRayN_id(args->ray, args->N, lane)] = {
            RTCRayN_tfar(args->ray, args->N, lane),
            std::int32_t(RTCHitN_primID(args->hit, args->N, lane)),
            RTCHitN_u(args->hit, args->N, lane), RTCHitN_v(args->hit, args->N, lane)};
    }
}

RTCRay to_embree(const Ray& ray, std::size_t id) {
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
    r.id = unsigned(id);
    r.flags = 0;
    return r;
}

RTCRayHit to_embree_hit(const Ray& ray, std::size_t id) {
    RTCRayHit r;
    r.ray = to_embree(ray, id);
    r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return r;
}

Hit from_embree(const RTCRayHit& r) {
    if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Hit{};
    return {r.ray.tfar, std::int32_t(r.hit.primID), r.hit.u, r.hit.v};
}

void set_lane(RTCRayHit8& packet, int lane, const Ray& ray, std::size_t id) {
    packet.ray.org_x[lane] = ray.org.x;
    packet.ray.org_y[lane] = ray.org.y;
    packet.ray.org_z[lane] = ray.org.z;
    packet.ray.dir_x[lane] = ray.dir.x;
    packet.ray.dir_y[lane] = ray.dir.y;
    packet.ray.dir_z[lane] = ray.dir.z;
    packet.ray.tnear[lane] = ray.tmin;
    packet.ray.tfar[lane] = ray.tmax;
    packet.ray.time[lane] = 0.0f;
    packet.ray.mask[lane] = ~0u;
    packet.ray.id[lane] = unsigned(id);
    packet.ray.flags[lane] = 0;
    packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
}

/// Rays [begin, end) of the batch (end - begin <= 8) as one packet, `valid` marking the lanes.
void make_packet(std::span<const Ray> rays, std::size_t begin, std::size_t end, RTCRayHit8& packet,
                 int valid[8]) {
    for (int lane = 0; lane < 8; ++lane) {
        const bool active = begin + lane < end;
        valid[lane] = active ? -1 : 0;
        // Inactive lanes get a copy of the first ray so every lane holds finite data.
        set_lane(packet, lane, rays[active ? begin + lane : begin], active ? begin + lane : begin);
    }
}

}  // namespace

EmbreeTracer::EmbreeTracer(EmbreeMode mode) : mode_(mode) {
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

void EmbreeTracer::trace_range(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                               std::size_t begin, std::size_t end) {
    OcclusionContext context;
    rtcInitIntersectContext(&context.base);
    if (query == Query::any) {
        context.base.filter = record_occluders;
        context.hits = hits.data();
    }
    for (std::size_t i = begin; i != end; ++i) hits[i] = Hit{};
    switch (mode_) {
        case EmbreeMode::single:
            for (std::size_t i = begin; i != end; ++i) {
                if (query == Query::closest) {
                    RTCRayHit ray_hit = to_embree_hit(rays[i], i);
                    rtcIntersect1(scene_, &context.base, &ray_hit);
                    hits[i] = from_embree(ray_hit);
                } else {
                    RTCRay ray = to_embree(rays[i], i);
                    rtcOccluded1(scene_, &context.base, &ray);
                    if (ray.tfar != -kInfinity) hits[i] = Hit{};  // not occluded after all
                }
            }
            break;
        case EmbreeMode::packet8:
            for (std::size_t first = begin; first < end; first += 8) {
                const std::size_t last = std::min(first + 8, end);
                alignas(32) int valid[8];
                alignas(32) RTCRayHit8 packet;
                make_packet(rays, first, last, packet, valid);
                if (query == Query::closest) {
                    rtcIntersect8(valid, scene_, &context.base, &packet);
                    for (std::size_t i = first; i < last; ++i) {
                        const int lane = int(i - first);
                        if (packet.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID)
                            hits[i] = {packet.ray.tfar[lane], std::int32_t(packet.hit.primID[lane]),
                                       packet.hit.u[lane], packet.hit.v[lane]};
                    }
                } else {
                    rtcOccluded8(valid, scene_, &context.base, &packet.ray);
                    for (std::size_t i = first; i < last; ++i)
                        if (packet.ray.tfar[i - first] != -kInfinity) hits[i] = Hit{};
                }
            }
            break;
        case EmbreeMode::stream: {
            thread_local std::vector<RTCRayHit> stream;
            stream.clear();
            for (std::size_t i = begin; i != end; ++i) stream.push_back(to_embree_hit(rays[i], i));
            const unsigned count = unsigned(end - begin);
            if (query == Query::closest) {
                rtcIntersect1M(scene_, &context.base, stream.data(), count, sizeof(RTCRayHit));
                for (std::size_t i = begin; i != end; ++i) hits[i] = from_embree(stream[i - begin]);
            } else {
                // RTCRayHit starts with its RTCRay, so the same array serves with its stride.
                rtcOccluded1M(scene_, &context.base, &stream[0].ray, count, sizeof(RTCRayHit));
                for (std::size_t i = begin; i != end; ++i)
                    if (stream[i - begin].ray.tfar != -kInfinity) hits[i] = Hit{};
            }
            break;
        }
    }
}

TraceStats EmbreeTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                     TraceDetail*) {
    assert(rays.size() == hits.size() && scene_);
    // Ranges of whole packets, large enough for streams to pay off.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), [&](const auto& range) {
        trace_range(rays, hits, query, range.begin(), range.end());
    });
    // Embree does not report its internal test counts.
    TraceStats stats;
    stats.rays = rays.size();
    return stats;
}

}  // namespace edacrt
