// What every Tracer checks about its arguments in every build (not only with assertions on).
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "scene/builtin_scenes.h"
#include "trace/tracer.h"

namespace edacrt {
namespace {

TEST(TracerContract, OneHitPerRayOrInvalidArgument) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    for (const auto& [method, name, help] : kMethods) {
        std::unique_ptr<Tracer> tracer;
        try {
            tracer = make_tracer(method);
        } catch (const std::exception&) {
            continue;  // embree in a build without it
        }
        tracer->set_scene(scene);
        const std::vector<Ray> rays(10);
        std::vector<Hit> short_hits(9), long_hits(11);
        for (Query query : {Query::closest, Query::any}) {
            EXPECT_THROW(tracer->trace(rays, short_hits, query), std::invalid_argument) << name;
            EXPECT_THROW(tracer->trace(rays, long_hits, query), std::invalid_argument) << name;
        }
        std::vector<Hit> hits(10);
        EXPECT_NO_THROW(tracer->trace(rays, hits, Query::closest)) << name;
    }
}

}  // namespace
}  // namespace edacrt
