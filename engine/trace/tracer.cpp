#include "trace/tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

#include "trace/bvh_tracer.h"
#include "trace/edacrt_tracer.h"
#ifdef EDACRT_HAS_EMBREE
#include "trace/embree_tracer.h"
#endif
#include "trace/naive_tracer.h"
#include "util/error.h"

namespace edacrt {

std::unique_ptr<Tracer> make_tracer(Method method, const EdacrtParams& params,
                                    EmbreeMode embree_mode, const BvhBuildOptions& bvh_options) {
    switch (method) {
        case Method::naive:
            return std::make_unique<NaiveTracer>();
        case Method::bvh:
            return std::make_unique<BvhTracer>(bvh_options);
        case Method::embree:
#ifdef EDACRT_HAS_EMBREE
            return std::make_unique<EmbreeTracer>(embree_mode);
#else
            (void)embree_mode;
            throw InputError("this build has no Embree: configure with -DEDACRT_EMBREE=ON");
#endif
        case Method::edacrt:
            return std::make_unique<EdacrtTracer>(params, Method::edacrt);
        case Method::dacrt:
            return std::make_unique<EdacrtTracer>(dacrt_params(params), Method::dacrt);
    }
    throw InputError("unknown tracing method");
}

FrameVector<Triangle> gather_triangles(const Scene& scene) {
    FrameVector<Triangle> triangles;
    gather_triangles(scene, triangles);
    return triangles;
}

void gather_triangles(const Scene& scene, FrameVector<Triangle>& out) {
    out.resize(scene.triangle_count());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) out[i] = scene.corners(i);
    });
}

UpdateStats Tracer::update_scene(const Scene& scene, SceneUpdate how) {
    const auto start = std::chrono::steady_clock::now();
    UpdateStats stats;
    stats.work = update(scene, how);
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

UpdateWork Tracer::update(const Scene& scene, SceneUpdate) {
    set_scene(scene);
    return UpdateWork::rebuilt;
}

}  // namespace edacrt
