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

namespace {
constexpr Method kMethods[] = {Method::edacrt, Method::dacrt, Method::bvh, Method::embree,
                               Method::naive};
}

std::unique_ptr<Tracer> make_tracer(Method method, const EdacrtParams& params,
                                    EmbreeMode embree_mode) {
    switch (method) {
        case Method::naive:
            return std::make_unique<NaiveTracer>();
        case Method::bvh:
            return std::make_unique<BvhTracer>();
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

std::string_view method_name(Method method) {
    switch (method) {
        case Method::naive:
            return "naive";
        case Method::bvh:
            return "bvh";
        case Method::embree:
            return "embree";
        case Method::edacrt:
            return "edacrt";
        case Method::dacrt:
            return "dacrt";
    }
    return "?";
}

Method parse_method(std::string_view name) {
    for (Method m : kMethods)
        if (method_name(m) == name) return m;
    std::string known;
    for (const std::string& n : method_names()) known += (known.empty() ? "" : ", ") + n;
    throw InputError("unknown method '" + std::string(name) + "' (known: " + known + ")");
}

std::vector<std::string> method_names() {
    std::vector<std::string> names;
    for (Method m : kMethods) names.emplace_back(method_name(m));
    return names;
}

std::string_view embree_mode_name(EmbreeMode mode) {
    switch (mode) {
        case EmbreeMode::single:
            return "single";
        case EmbreeMode::packet8:
            return "packet8";
        case EmbreeMode::stream:
            return "stream";
    }
    return "?";
}

EmbreeMode parse_embree_mode(std::string_view name) {
    for (EmbreeMode mode : {EmbreeMode::single, EmbreeMode::packet8, EmbreeMode::stream})
        if (embree_mode_name(mode) == name) return mode;
    throw InputError("unknown Embree mode '" + std::string(name) +
                     "' (known: single, packet8, stream)");
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

std::string_view scene_update_name(SceneUpdate how) {
    switch (how) {
        case SceneUpdate::rebuild:
            return "rebuild";
        case SceneUpdate::dynamic:
            return "dynamic";
        case SceneUpdate::refit:
            return "refit";
    }
    return "?";
}

SceneUpdate parse_scene_update(std::string_view name) {
    for (SceneUpdate how : {SceneUpdate::rebuild, SceneUpdate::dynamic, SceneUpdate::refit})
        if (scene_update_name(how) == name) return how;
    throw InputError("unknown scene update '" + std::string(name) +
                     "' (known: rebuild, dynamic, refit)");
}

std::string_view update_work_name(UpdateWork work) {
    switch (work) {
        case UpdateWork::none:
            return "none";
        case UpdateWork::rebuilt:
            return "rebuilt";
        case UpdateWork::refitted:
            return "refitted";
    }
    return "?";
}

}  // namespace edacrt
