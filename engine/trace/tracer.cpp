#include "trace/tracer.h"

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

std::vector<Triangle> gather_triangles(const Scene& scene) {
    std::vector<Triangle> triangles;
    triangles.reserve(scene.triangles.size());
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) triangles.push_back(scene.corners(i));
    return triangles;
}

}  // namespace edacrt
