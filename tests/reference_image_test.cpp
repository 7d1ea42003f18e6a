// One small reference image: the built-in Cornell box, eye-light shaded, one sample per pixel.
// Regenerate after an intended change with:
//   build/edacrt render --scene builtin:cornell --integrator primary --spp 1 --width 64
//   --height 48 --out tests/data/cornell_eye_light.png
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "test_paths.h"
#include "trace/naive_tracer.h"

namespace edacrt {
namespace {

TEST(ReferenceImage, CornellEyeLightMatches) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    NaiveTracer tracer;
    tracer.set_scene(scene);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.integrator = Integrator::primary;
    Renderer renderer(scene, tracer, *scene.camera, settings);
    ASSERT_TRUE(renderer.render_pass());
    const Image image = renderer.film().mean();
    const Image reference = read_png(test::source_dir() / "tests/data/cornell_eye_light.png");
    ASSERT_EQ(reference.width, 64);
    ASSERT_EQ(reference.height, 48);

    // 8-bit quantisation allows ~1/255 per channel; a handful of edge pixels may flip to a
    // neighbouring triangle under a different compiler, hence an RMSE bound plus a count bound.
    double squared = 0.0;
    int different = 0;
    for (std::size_t i = 0; i < reference.pixels.size(); ++i) {
        // The PNG holds clamped values (the emitter's eye-light value exceeds 1).
        const glm::vec3 d = glm::min(image.pixels[i], 1.0f) - reference.pixels[i];
        squared += double(glm::dot(d, d)) / 3.0;
        different += glm::length(d) > 0.02f;
    }
    EXPECT_LT(std::sqrt(squared / double(reference.pixels.size())), 0.01);
    EXPECT_LE(different, 10);
    EXPECT_EQ(renderer.total().trace.rays, 64u * 48u);
}

}  // namespace
}  // namespace edacrt
