// One small reference image: the built-in Cornell box, eye-light shaded, pixel centres.
// Regenerate after an intended change with:
//   build/edacrt render --scene builtin:cornell --width 64 --height 48 --out
//   tests/data/cornell_eye_light.png
#include <gtest/gtest.h>

#include <cmath>

#include "render/eye_light.h"
#include "scene/builtin_scenes.h"
#include "test_paths.h"
#include "trace/naive_tracer.h"

namespace edacrt {
namespace {

TEST(ReferenceImage, CornellEyeLightMatches) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    NaiveTracer tracer;
    tracer.set_scene(scene);
    const EyeLightResult result = render_eye_light(scene, *scene.camera, tracer, {64, 48, 1, 0});
    const Image reference = read_png(test::source_dir() / "tests/data/cornell_eye_light.png");
    ASSERT_EQ(reference.width, 64);
    ASSERT_EQ(reference.height, 48);

    // 8-bit quantisation allows ~1/255 per channel; a handful of edge pixels may flip to a
    // neighbouring triangle under a different compiler, hence an RMSE bound plus a count bound.
    double squared = 0.0;
    int different = 0;
    for (std::size_t i = 0; i < reference.pixels.size(); ++i) {
        const glm::vec3 d = result.image.pixels[i] - reference.pixels[i];
        squared += double(glm::dot(d, d)) / 3.0;
        different += glm::length(d) > 0.02f;
    }
    EXPECT_LT(std::sqrt(squared / double(reference.pixels.size())), 0.01);
    EXPECT_LE(different, 10);
    EXPECT_EQ(result.stats.rays, 64u * 48u);
}

}  // namespace
}  // namespace edacrt
