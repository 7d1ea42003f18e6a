#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/ray.h"
#include "geometry/triangle.h"
#include "scene/scene.h"
#include "trace/bvh_build.h"
#include "trace/edacrt_params.h"
#include "trace/trace_stats.h"
#include "util/enum_table.h"
#include "util/frame_memory.h"

namespace edacrt {

/// The tracing methods behind the Tracer interface.
enum class Method { naive, edacrt, dacrt, bvh, embree };
inline constexpr auto kMethods =
    enum_table<Method>("method", {{Method::edacrt, "edacrt", "Nabata 2013"},
                                  {Method::dacrt, "dacrt", "Afra 2012"},
                                  {Method::bvh, "bvh", "binned SAH, rebuilt per frame"},
                                  {Method::embree, "embree"},
                                  {Method::naive, "naive", "every triangle"}});

/// How the Embree baseline hands rays to Embree: one at a time, in packets of 8, or as streams.
enum class EmbreeMode { single, packet8, stream };
inline constexpr auto kEmbreeModes =
    enum_table<EmbreeMode>("Embree mode", {{EmbreeMode::single, "single", "rtcIntersect1"},
                                           {EmbreeMode::packet8, "packet8", "rtcIntersect8"},
                                           {EmbreeMode::stream, "stream", "rtcIntersect1M"}});
inline constexpr EmbreeMode kDefaultEmbreeMode =
    EmbreeMode::packet8;  // fastest on camera rays (README)

/// Closest hit, or any hit (occlusion: a ray may stop at its first hit).
enum class Query { closest, any };
inline constexpr auto kQueries =
    enum_table<Query>("query", {{Query::closest, "closest"}, {Query::any, "any"}});

/// How update_scene() takes a new frame of the same triangles (an animation, animation.h).
enum class SceneUpdate {
    rebuild,  // everything from scratch, as set_scene()
    dynamic,  // embree: a dynamic scene (RTC_SCENE_FLAG_DYNAMIC) kept with its buffers and
              // committed per frame at low build quality; the others rebuild
    refit,    // bvh, embree: the tree kept, its boxes refitted to the new positions (Embree:
              // RTC_BUILD_QUALITY_REFIT); the others rebuild
};
inline constexpr auto kSceneUpdates = enum_table<SceneUpdate>(
    "scene update",
    {{SceneUpdate::rebuild, "rebuild", "from scratch"},
     {SceneUpdate::dynamic, "dynamic", "embree: a dynamic scene at low build quality"},
     {SceneUpdate::refit, "refit", "bvh, embree: the tree kept, its boxes refitted"}});

/// What update_scene() did to the tracer's structure. `none`: the method keeps no structure
/// (naive, dacrt, edacrt), only per-frame triangle data (EDACRT's pre-split pieces included).
enum class UpdateWork { none, rebuilt, refitted };
inline constexpr auto kUpdateWorks =
    enum_table<UpdateWork>("update work", {{UpdateWork::none, "none"},
                                           {UpdateWork::rebuilt, "rebuilt"},
                                           {UpdateWork::refitted, "refitted"}});

struct UpdateStats {
    UpdateWork work = UpdateWork::none;
    double seconds = 0.0;  // wall clock of the whole update
};

/// Traces batches of rays against one scene. Every method returns the same hits for the same
/// rays (up to ties between triangles hit at the same distance).
class Tracer {
  public:
    virtual ~Tracer() = default;

    virtual Method method() const = 0;

    /// Prepares for batches against `scene`: per-frame triangle data, acceleration structures.
    /// Call again whenever the geometry changes. The tracer keeps no reference to `scene`.
    virtual void set_scene(const Scene& scene) = 0;

    /// Takes the geometry of `scene` for the next batches, as `how` asks, and says what that
    /// did and cost. `dynamic` and `refit` keep what the last update or set_scene() built when
    /// `scene` has the same vertex and triangle counts and the same corner indices (an
    /// Animation's frames do); otherwise, and on the first call, they build from scratch and
    /// report it (`rebuilt`). Every mode gives the same hits as set_scene(); refitted trees are
    /// only slower to trace. The tracer keeps no reference to `scene`.
    UpdateStats update_scene(const Scene& scene, SceneUpdate how);

    /// Bytes of the tracer's own data for the current scene and its last batch (per-frame
    /// structures, per-ray buffers; Embree: the device's peak since set_scene()), for the
    /// benchmark's memory column. Excludes the caller's rays and hits.
    virtual std::size_t working_bytes() const = 0;

    /// hits[i] receives the closest hit of rays[i] in [tmin, tmax] (Query::closest) or, for
    /// Query::any, a hit with prim >= 0 when anything occludes the ray. Rays must be valid
    /// (finite origin, finite non-zero direction, tmin <= tmax); see validate_ray().
    /// With `detail`, also records per-ray (and, for recursive methods, per-level) statistics,
    /// and for those methods the nodes and one ray's path when `detail` asks for them; without
    /// it the fast path counts only the totals. Throws std::invalid_argument unless there is one
    /// hit per ray.
    TraceStats trace(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                     TraceDetail* detail = nullptr) {
        // Checked in every build: a short `hits` would be written out of bounds.
        if (rays.size() != hits.size())
            throw std::invalid_argument("Tracer::trace: " + std::to_string(rays.size()) +
                                        " rays but " + std::to_string(hits.size()) + " hits");
        if (detail) {
            detail->root = RootStats{};
            detail->levels.clear();
            detail->rays.assign(rays.size(), RayStats{});
            detail->nodes.clear();
            detail->follow.clear();
        }
        return trace_batch(rays, hits, query, detail);
    }

  protected:
    /// update_scene() without the clock. By default set_scene(), `rebuilt`.
    virtual UpdateWork update(const Scene& scene, SceneUpdate how);

    /// trace() with `detail` reset (levels empty, one zeroed RayStats per ray) or null.
    virtual TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                                   TraceDetail* detail) = 0;
};

/// A tracer of the given method. The divide-and-conquer methods take `params` (dacrt through
/// dacrt_params()), embree takes `embree_mode`, bvh `bvh_options`; the others ignore them.
/// Throws InputError for bad params.
std::unique_ptr<Tracer> make_tracer(Method method, const EdacrtParams& params = {},
                                    EmbreeMode embree_mode = kDefaultEmbreeMode,
                                    const BvhBuildOptions& bvh_options = {});

/// Gathers each triangle's corners in scene order (the per-frame triangle data of the tracers).
FrameVector<Triangle> gather_triangles(const Scene& scene);

/// The same into `out`, which keeps its storage when the triangle count does not change.
void gather_triangles(const Scene& scene, FrameVector<Triangle>& out);

}  // namespace edacrt
