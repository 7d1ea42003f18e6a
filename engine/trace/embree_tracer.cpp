#include "trace/embree_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "util/error.h"

namespace edacrt {
namespace {

/// Our distance and barycentrics for a triangle Embree found the ray to pass through: those of
/// our whole test (triangle.h, intersect_triangle) where it agrees. Otherwise the inside
/// decision stays Embree's (rejecting it would leak: Embree would not offer the neighbour
/// across the edge that our test would take) with our distance test, and the barycentrics
/// are clamped into the triangle: Embree's float test differs from ours near edges and, from
/// 1e6 away, by its rounding of the origin (there our float barycentrics of its hit came out
/// at u = 8.8). The wrapper so never reports a point outside the hit triangle.
bool checked_hit(const WatertightRay& r, const Triangle& tri, float tmin, float tmax,
                 TriangleHit& out) {
    if (intersect_triangle(r, tri, tmin, tmax, out)) return true;
    const ShearedTriangle<float> s = shear_triangle(r, tri);
    const float det = s.u + s.v + s.w;
    if (!(safe_determinant(det) ? decide_distance(r, tri, s, det, tmin, tmax, out)
                                : refine_hit_in_double(r, tri, tmin, tmax, out)))
        return false;
    if (!(out.u >= 0.0f)) out.u = 0.0f;  // NaN too: a triangle seen edge-on
    if (!(out.v >= 0.0f)) out.v = 0.0f;
    if (const float sum = out.u + out.v; sum > 1.0f) {
        out.u /= sum;
        out.v /= sum;
    }
    return true;
}

/// The context of every query: a filter (called for each candidate hit Embree finds) accepts
/// a candidate only where our distance test does (checked_hit: t conservatively positive,
/// within [tmin, tmax]). Embree has no conservative t test, so from an exact point on a
/// coordinate plane it reports the ray's own triangle at t = 0; with this filter, rays spawned
/// from surfaces (geometry/offset.h, tmin > 0) do not self-intersect. For occlusion queries the
/// filter also records the occluder (rtcOccluded* reports only whether a ray is blocked). Rays
/// carry their index in the batch as their id, so the filter finds each lane's hit in every mode
/// (1, 8, stream).
struct FilterContext {
    RTCIntersectContext base;  // first member: Embree passes &base back to the filter
    const Triangle* triangles;
    const Ray* rays;  // the batch, as given (Embree's copy has tmin clamped, tfar moved)
    Hit* occluders;   // null for closest-hit queries
};

void filter_candidates(const RTCFilterFunctionNArguments* args);

/// A query context; with `filtered`, candidates go through filter_candidates.
FilterContext make_context(const Triangle* triangles, const Ray* rays, Hit* occluders,
                           bool filtered) {
    FilterContext context;
    rtcInitIntersectContext(&context.base);
    context.base.filter = filtered ? filter_candidates : nullptr;
    context.triangles = triangles;
    context.rays = rays;
    context.occluders = occluders;
    return context;
}

void filter_candidates(const RTCFilterFunctionNArguments* args) {
    const auto* context = reinterpret_cast<const FilterContext*>(args->context);
    const unsigned n = args->N;
    for (unsigned lane = 0; lane < n; ++lane) {
        if (args->valid[lane] != -1) continue;
        const auto prim = RTCHitN_primID(args->hit, n, lane);
        const unsigned id = RTCRayN_id(args->ray, n, lane);
        const Ray& ray = context->rays[id];
        TriangleHit ours;
        if (!checked_hit(make_watertight_ray(ray), context->triangles[prim], ray.tmin, ray.tmax,
                         ours)) {
            args->valid[lane] = 0;  // reject: Embree goes on looking
            continue;
        }
        if (context->occluders)
            context->occluders[id] = {ours.t, std::int32_t(prim), ours.u, ours.v};
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
    r.tnear = std::max(ray.tmin, 0.0f);  // the same query: no method accepts t <= 0
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
    packet.ray.tnear[lane] = std::max(ray.tmin, 0.0f);
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

/// Embree computes in float with denormals flushed to zero: products of coordinates overflow
/// beyond ~1e12 (measured: wrong triangles from 1e13 on, an assertion abort from 1.8e18, hits at
/// t = inf) and the edge products of triangles below ~1e-18 flush to zero (nothing is hit).
/// Measured on spheres from 1e-34 to 1e18, near and far from the origin (hard_cases_test.cpp).
constexpr double kLargestCoordinate = 1e12;
constexpr double kSmallestDoubledArea = 1e-36;

std::string format_number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return text;
}

/// Throws InputError for a scene Embree cannot trace correctly.
void check_scene_for_embree(const Scene& scene) {
    double largest = 0.0;
    for (const glm::vec3& p : scene.positions)
        largest = std::max(
            {largest, std::abs(double(p.x)), std::abs(double(p.y)), std::abs(double(p.z))});
    if (largest > kLargestCoordinate)
        throw InputError("Embree cannot trace " + scene.source + ": coordinates reach " +
                         format_number(largest) +
                         ", beyond the 1e12 where its float arithmetic "
                         "overflows; use another method");
    std::size_t tiny = 0;
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
        const double doubled_area = 2.0 * triangle_area(scene.corners(i));
        tiny += doubled_area > 0.0 && doubled_area < kSmallestDoubledArea;
    }
    if (tiny > 0)
        throw InputError("Embree cannot trace " + scene.source + ": " + std::to_string(tiny) +
                         " triangles are smaller than ~1e-18 across, where Embree's products "
                         "flush to zero and nothing is hit; use another method");
}

/// Throws InputError for a ray Embree cannot trace (see check_scene_for_embree).
void check_ray_for_embree(const Ray& ray, std::size_t index) {
    const glm::vec3 o = glm::abs(ray.org), d = glm::abs(ray.dir);
    const double org = std::max({o.x, o.y, o.z}), dir = std::max({d.x, d.y, d.z});
    if (org > kLargestCoordinate || dir > kLargestCoordinate || dir < 1.0 / kLargestCoordinate)
        throw InputError("Embree cannot trace ray " + std::to_string(index) + ": its origin (" +
                         format_number(org) + ") or direction (" + format_number(dir) +
                         ") is outside what its float arithmetic covers (origin up to 1e12, "
                         "direction 1e-12 to 1e12); use another method");
}

/// Embree's memory monitor: `bytes` > 0 for an allocation, < 0 for a release.
template <class DeviceMemory>
bool track_device_bytes(void* user, ssize_t bytes, bool /*post*/) {
    auto& memory = *static_cast<DeviceMemory*>(user);
    const std::int64_t now = memory.current += bytes;
    std::int64_t peak = memory.peak.load();
    while (now > peak && !memory.peak.compare_exchange_weak(peak, now)) {
    }
    return true;  // never refuse an allocation
}

}  // namespace

EmbreeTracer::EmbreeTracer(EmbreeMode mode) : mode_(mode) {
    // No "threads=N" here: that would limit oneTBB for the whole process.
    device_ = rtcNewDevice(nullptr);
    if (!device_)
        throw InputError("Embree: cannot create a device (error " +
                         std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceMemoryMonitorFunction(device_, track_device_bytes<DeviceMemory>, &device_memory_);
}

EmbreeTracer::~EmbreeTracer() {
    release();
    rtcReleaseDevice(device_);
}

void EmbreeTracer::release() {
    if (geometry_) rtcReleaseGeometry(geometry_);
    if (scene_) rtcReleaseScene(scene_);
    geometry_ = nullptr;
    scene_ = nullptr;  // no stale scene to trace if the next one is refused
}

void EmbreeTracer::set_scene(const Scene& scene) { build(scene, SceneUpdate::rebuild); }

void EmbreeTracer::build(const Scene& scene, SceneUpdate how) {
    release();
    device_memory_.peak = device_memory_.current.load();
    check_scene_for_embree(scene);
    scene_ = rtcNewScene(device_);
    const bool dynamic = how != SceneUpdate::rebuild;
    rtcSetSceneFlags(scene_,
                     RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION |
                                   (dynamic ? RTC_SCENE_FLAG_DYNAMIC : 0)));
    geometry_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (dynamic) {
        // Low scene quality makes Embree build two levels, where the geometry's own quality
        // (low, or refit) applies.
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_LOW);
        rtcSetGeometryBuildQuality(
            geometry_, how == SceneUpdate::refit ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_LOW);
    }
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), scene.positions.size()));
    auto* indices = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geometry_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(std::uint32_t), scene.triangles.size()));
    if (!vertices || !indices) throw InputError("Embree: cannot allocate the geometry buffers");
    std::memcpy(vertices, scene.positions.data(), scene.positions.size() * sizeof(glm::vec3));
    std::memcpy(indices, scene.triangles.data(),
                scene.triangles.size() * 3 * sizeof(std::uint32_t));
    rtcCommitGeometry(geometry_);
    rtcAttachGeometry(scene_, geometry_);
    rtcCommitScene(scene_);
    built_for_ = how;
    vertices_ = scene.positions.size();
    gather_triangles(scene, triangles_);
}

bool EmbreeTracer::same_topology(const Scene& scene) const {
    if (scene.positions.size() != vertices_ || scene.triangles.size() != triangles_.size())
        return false;
    const void* indices = rtcGetGeometryBufferData(geometry_, RTC_BUFFER_TYPE_INDEX, 0);
    return std::memcmp(indices, scene.triangles.data(),
                       scene.triangles.size() * 3 * sizeof(std::uint32_t)) == 0;
}

UpdateWork EmbreeTracer::update(const Scene& scene, SceneUpdate how) {
    if (how == SceneUpdate::rebuild || !scene_ || built_for_ != how || !same_topology(scene)) {
        build(scene, how);
        return UpdateWork::rebuilt;
    }
    try {
        check_scene_for_embree(scene);
    } catch (const InputError&) {
        release();
        throw;
    }
    std::memcpy(rtcGetGeometryBufferData(geometry_, RTC_BUFFER_TYPE_VERTEX, 0),
                scene.positions.data(), scene.positions.size() * sizeof(glm::vec3));
    rtcUpdateGeometryBuffer(geometry_, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geometry_);
    rtcCommitScene(scene_);
    gather_triangles(scene, triangles_);
    return how == SceneUpdate::refit ? UpdateWork::refitted : UpdateWork::rebuilt;
}

std::size_t EmbreeTracer::working_bytes() const {
    return std::size_t(device_memory_.peak.load()) + triangles_.capacity() * sizeof(Triangle);
}

void EmbreeTracer::trace_range(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                               std::size_t begin, std::size_t end) {
    // Camera rays (tmin = 0) never start on a surface: spare them the filter's cost (+40% for
    // packets). Spawned rays carry tmin > 0 (kSpawnTmin); occlusion needs the filter anyway.
    bool spawned = false;
    for (std::size_t i = begin; i != end; ++i) {
        check_ray_for_embree(rays[i], i);
        spawned |= rays[i].tmin > 0.0f;
        hits[i] = Hit{};
    }
    FilterContext context =
        make_context(triangles_.data(), rays.data(), query == Query::any ? hits.data() : nullptr,
                     query == Query::any || spawned);
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
    if (query == Query::closest) refine_closest_hits(rays, hits, begin, end);
}

void EmbreeTracer::refine_closest_hits(std::span<const Ray> rays, std::span<Hit> hits,
                                       std::size_t begin, std::size_t end) const {
    for (std::size_t i = begin; i != end; ++i) {
        if (!hits[i].hit()) continue;
        const WatertightRay wray = make_watertight_ray(rays[i]);
        const Triangle& tri = triangles_[std::size_t(hits[i].prim)];
        TriangleHit ours;
        if (!checked_hit(wray, tri, rays[i].tmin, rays[i].tmax, ours)) {
            // Traced without the filter (tmin = 0), yet not conservatively in front: again,
            // filtered, so Embree looks beyond it.
            FilterContext context = make_context(triangles_.data(), rays.data(), nullptr, true);
            RTCRayHit ray_hit = to_embree_hit(rays[i], i);
            rtcIntersect1(scene_, &context.base, &ray_hit);
            hits[i] = from_embree(ray_hit);
            if (!hits[i].hit()) continue;
            if (!checked_hit(wray, triangles_[std::size_t(hits[i].prim)], rays[i].tmin,
                             rays[i].tmax, ours)) {
                hits[i] = Hit{};
                continue;
            }
        }
        hits[i].t = ours.t;
        hits[i].u = ours.u;
        hits[i].v = ours.v;
    }
}

TraceStats EmbreeTracer::trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                     TraceDetail*) {
    if (!scene_) throw InputError("Embree: no scene to trace (set_scene failed or never ran)");
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
