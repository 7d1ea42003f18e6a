// The renderer against analytic answers: a white furnace, a plane under a uniform sky, ambient
// occlusion of a plane; determinism; progressive convergence.
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "trace/tracer.h"

namespace edacrt {
namespace {

/// Mean of an image's channels over all pixels.
double mean_value(const Image& image) {
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels) sum += double(p.x + p.y + p.z) / 3.0;
    return sum / double(image.pixels.size());
}

Image render(const Scene& scene, const Camera& camera, const RenderSettings& settings, int spp,
             Method method = Method::edacrt) {
    const auto tracer = make_tracer(method);
    tracer->set_scene(scene);
    Renderer renderer(scene, *tracer, camera, settings);
    for (int pass = 0; pass < spp; ++pass) EXPECT_TRUE(renderer.render_pass());
    return renderer.film().mean();
}

/// A closed sphere that emits Le and reflects a fraction a, seen from its centre.
Scene furnace(float albedo, float emission) {
    Scene scene = make_builtin_scene("builtin:sphere:subdiv=3");
    scene.materials[0].kd = glm::vec3(albedo);
    scene.materials[0].ke = glm::vec3(emission);
    for (auto& tri : scene.triangles) std::swap(tri[1], tri[2]);  // emit inwards
    return scene;
}

Camera looking_from_centre() { return Camera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0f}; }

TEST(Furnace, PathTracingConvergesToTheAnalyticRadiance) {
    // Every bounce sees Le again: L = Le (1 + a + ... + a^D) = Le (1 - a^(D+1)) / (1 - a).
    const float a = 0.5f, le = 1.0f;
    RenderSettings settings;
    settings.width = settings.height = 16;
    for (int depth : {0, 1, 3, 20}) {
        settings.max_depth = depth;
        const double expected = le * (1.0 - std::pow(a, depth + 1)) / (1.0 - a);
        const double measured =
            mean_value(render(furnace(a, le), looking_from_centre(), settings, 64));
        EXPECT_NEAR(measured, expected, 0.01 * expected) << "max depth " << depth;
    }
}

/// A 100 x 100 square at y = 0 seen from above.
Scene plane(float albedo) {
    Scene scene;
    scene.source = "plane";
    scene.positions = {{-50, 0, -50}, {50, 0, -50}, {50, 0, 50}, {-50, 0, 50}};
    scene.triangles = {{0, 1, 2}, {0, 2, 3}};
    scene.triangle_materials = {0, 0};
    scene.materials.resize(1);
    scene.materials[0].kd = glm::vec3(albedo);
    return scene;
}

Camera looking_down() { return Camera{{0, 1, 0}, {0, 0, 0}, {0, 0, -1}, 60.0f}; }

TEST(Sky, LambertianPlaneReflectsAlbedoTimesSky) {
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.sky = glm::vec3(2.0f);
    const Image image = render(plane(0.6f), looking_down(), settings, 8);
    for (const glm::vec3& p : image.pixels) EXPECT_NEAR(p.x, 1.2f, 1e-4f);
}

TEST(AmbientOcclusion, OfAPlaneIsOne) {
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.integrator = Integrator::ao;
    settings.ao_samples = 16;
    settings.ao_distance = 1e6f;
    const Image image = render(plane(0.5f), looking_down(), settings, 4);
    for (const glm::vec3& p : image.pixels) EXPECT_EQ(p.x, 1.0f);
}

}  // namespace
}  // namespace edacrt
