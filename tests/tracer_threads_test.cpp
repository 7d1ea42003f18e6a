// Every method traces a batch with 4 engine threads exactly as with 1. A binary of its own, so
// that the ThreadSanitizer build of scripts/test compiles and runs just this (and the viewer's
// worker) to look for races inside the tracers.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <random>
#include <string>
#include <vector>

#include "scene/builtin_scenes.h"
#include "trace/tracer.h"

namespace edacrt {
namespace {

/// Rays from random points of the soup's box in random directions, some of them short.
std::vector<Ray> random_rays(std::size_t count) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-1.2f, 1.2f);
    std::vector<Ray> rays(count);
    for (Ray& ray : rays) {
        ray.org = {coord(rng), coord(rng), coord(rng)};
        do ray.dir = {coord(rng), coord(rng), coord(rng)};
        while (ray.dir == glm::vec3(0.0f));
        if (rng() % 4 == 0) ray.tmax = 0.3f;
    }
    return rays;
}

/// Traces in an arena of `threads` slots (more than this machine's cores is fine: the point is
/// concurrent access, which ThreadSanitizer checks).
std::vector<Hit> trace(Tracer& tracer, const std::vector<Ray>& rays, Query query, int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    std::size_t(threads));
    tbb::task_arena arena(threads);
    std::vector<Hit> hits(rays.size());
    arena.execute([&] {
        EXPECT_EQ(tbb::this_task_arena::max_concurrency(), threads);
        tracer.trace(rays, hits, query);
    });
    return hits;
}

class TracerThreads : public ::testing::TestWithParam<Method> {};

TEST_P(TracerThreads, FourThreadsTraceAsOne) {
    // A soup: no shared edges, so no ties whose winner could depend on the order.
    const Scene scene = make_builtin_scene("builtin:soup:count=200,seed=3,size=0.4");
    const std::vector<Ray> rays = random_rays(50'000);
    const auto tracer = make_tracer(GetParam());
    tracer->set_scene(scene);
    for (Query query : {Query::closest, Query::any}) {
        const std::vector<Hit> one = trace(*tracer, rays, query, 1);
        const std::vector<Hit> four = trace(*tracer, rays, query, 4);
        std::size_t hits = 0, differences = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            hits += one[i].hit();
            // Any-hit may stop at a different occluder; whether there is one is fixed.
            const bool same = query == Query::any
                                  ? one[i].hit() == four[i].hit()
                                  : one[i].prim == four[i].prim && one[i].t == four[i].t &&
                                        one[i].u == four[i].u && one[i].v == four[i].v;
            if (!same && ++differences <= 5)
                ADD_FAILURE() << "ray " << i << ": prim " << one[i].prim << " t " << one[i].t
                              << " with 1 thread, prim " << four[i].prim << " t " << four[i].t
                              << " with 4";
        }
        EXPECT_EQ(differences, 0u) << (query == Query::any ? "any hit" : "closest hit");
        EXPECT_GT(hits, rays.size() / 10) << "the batch exercises hits";
        EXPECT_LT(hits, rays.size()) << "and misses";
    }
}

std::vector<Method> methods() {
    std::vector<Method> out = {Method::naive, Method::edacrt, Method::dacrt, Method::bvh};
#ifdef EDACRT_HAS_EMBREE
    out.push_back(Method::embree);
#endif
    return out;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, TracerThreads, ::testing::ValuesIn(methods()),
                         [](const auto& info) { return std::string(method_name(info.param)); });

}  // namespace
}  // namespace edacrt
