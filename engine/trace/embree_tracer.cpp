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

/// The context of every query: a filter (called for each candidate hit Embree finds) accepts
/// only hits our own watertight test accepts too. Embree has no conservative t test, so from
/// an exact point on a coordinate plane it reports the ray's own triangle at t = 0; with this
/// filter, rays spawned from surfaces (geometry/offset.h, tmin > 0) do not self-intersect. For
/// occlusion queries the filter also records the occluder (rtcOccluded* reports only whether a ray
/// is blocked). Rays carry their index in the batch as their id, so the filter finds each lane's
/// hit in every mode (1, 8, stream).
struct FilterContext {
    RTCIntersectContext base;  // first member: Embree passes &base back to the filter
    const Triangle* triangles;
    Hit* occluders;  // null for closest-hit queries
};

void filter_candidates(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const FilterContext*>(args->context);
    const unsigned n = args->N;
    for (unsigned lane = 0; lane < n; ++lane) {
        if (args->valid[lane] != -1) continue;
        const auto prim = RTCHitN_primID(args->hit, n, lane);
        // During a filter call the candidate's distance is the ray's tfar.
        const float t = RTCRayN_tfar(args->ray, n, lane);
        const Ray ray{{RTCRayN_org_x(args->ray, n, lane), RTCRayN_org_y(args->ray, n, lane),
                       RTCRayN_org_z(args->ray, n, lane)},
                      {RTCRayN_dir_x(args->ray, n, lane), RTCRayN_dir_y(args->ray, n, lane),
                       RTCRayN_dir_z(args->ray, n, lane)},
                      RTCRayN_tnear(args->ray, n, lane),
                      kInfinity};
        TriangleHit ours;
        if (!intersect_triangle(make_watertight_ray(ray), context->triangles[prim], ray.tmin,
                                kInfinity, ours)) {
            args->valid[lane] = 0;  // reject: Embree goes on looking
            continue;
        }
        if (context->occluders)
            context->occluders[RTCRayN_id(args->ray, n, lane)] = {t, std::int32_t(prim),
                                                                  RTCHitN_u(args->hit, n, lane),
                                                                  RTCHitN_v(args->hit, n, lane)};
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
    triangles_ = gather_triangles(scene);
}

void EmbreeTracer::trace_range(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                               std::size_t begin, std::size_t end) {
    FilterContext context;
    rtcInitIntersectContext(&context.base);
    // Camera rays (tmin = 0) never start on a surface: spare them the filter's cost (+40% for
    // packets). Spawned rays carry tmin > 0 (kSpawnTmin); occlusion needs the filter anyway.
    const bool spawned =
        std::any_of(rays.begin() + std::ptrdiff_t(begin), rays.begin() + std::ptrdiff_t(end),
                    [](const Ray& ray) { return ray.tmin > 0.0f; });
    context.base.filter = query == Query::any || spawned ? filter_candidates : nullptr;
    context.triangles = triangles_.data();
    context.occluders = query == Query::any ? hits.data() : nullptr;
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
