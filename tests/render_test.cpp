// The renderer against analytic answers: a white furnace, a plane under a uniform sky, ambient
// occlusion of a plane; determinism; progressive convergence.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "render/bsdf.h"
#include "render/renderer.h"
#include "render/shading_scene.h"
#include "scene/builtin_scenes.h"
#include "trace/tracer.h"
#include "util/error.h"

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

TEST(AmbientOcclusion, OfAnOpenPlaneIsItsAlbedo) {
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.integrator = Integrator::ao;
    settings.ao_samples = 16;
    settings.ao_distance = 1e6f;
    const Image image = render(plane(0.5f), looking_down(), settings, 4);
    for (const glm::vec3& p : image.pixels) EXPECT_EQ(p.x, 0.5f);
}

Image render_cornell(Method method, Integrator integrator, std::uint32_t seed, int spp) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    RenderSettings settings;
    settings.width = 48;
    settings.height = 32;
    settings.integrator = integrator;
    settings.seed = seed;
    settings.wavefront_paths = 700;  // several wavefronts, uneven
    return render(scene, *scene.camera, settings, spp, method);
}

TEST(Determinism, SameSeedSameImageForAnyThreadCountAndMethod) {
    for (Integrator integrator : {Integrator::path, Integrator::ao}) {
        const Image reference = render_cornell(Method::naive, integrator, 7, 4);
        for (Method method : {Method::edacrt, Method::dacrt, Method::bvh}) {
            for (int threads : {1, 2, 3}) {
                tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                          std::size_t(threads));
                const Image image = render_cornell(method, integrator, 7, 4);
                // Bit for bit: the same samples, the same hits, the same sums.
                EXPECT_TRUE(image.pixels == reference.pixels)
                    << enum_name(kMethods, method) << ", " << threads << " threads, "
                    << enum_name(kIntegrators, integrator);
            }
        }
    }
    EXPECT_FALSE(render_cornell(Method::edacrt, Integrator::path, 8, 4).pixels ==
                 render_cornell(Method::edacrt, Integrator::path, 7, 4).pixels);
}

TEST(Determinism, PassesOfSeveralSamplesGiveTheImageOfOneSamplePasses) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    for (Integrator integrator : {Integrator::path, Integrator::ao, Integrator::primary}) {
        RenderSettings settings;
        settings.width = 40;
        settings.height = 24;
        settings.integrator = integrator;
        const Image one_by_one = render(scene, *scene.camera, settings, 7);
        settings.samples_per_pass = 3;
        settings.wavefront_paths = 1000;  // wavefronts straddle the samples
        const auto tracer = make_tracer(Method::edacrt);
        tracer->set_scene(scene);
        Renderer renderer(scene, *tracer, *scene.camera, settings);
        EXPECT_TRUE(renderer.render_pass());                     // samples 0-2
        EXPECT_TRUE(renderer.render_pass(nullptr, nullptr, 1));  // 3
        EXPECT_TRUE(renderer.render_pass(nullptr, nullptr, 3));  // 4-6
        EXPECT_EQ(renderer.film().passes(), 7);
        EXPECT_TRUE(renderer.film().mean().pixels == one_by_one.pixels)
            << enum_name(kIntegrators, integrator);
        EXPECT_THROW(renderer.render_pass(nullptr, nullptr, 4), std::invalid_argument);
    }
    RenderSettings bad;
    bad.samples_per_pass = 0;
    EXPECT_THROW(validate(bad), InputError);
    bad.samples_per_pass = 1025;
    EXPECT_THROW(validate(bad), InputError);
}

TEST(Settings, AutoSamplesPerPassGivesPassesOfAboutAMillionPaths) {
    EXPECT_EQ(auto_samples_per_pass(320, 240, 8), 8);     // 14 wanted, --spp 8
    EXPECT_EQ(auto_samples_per_pass(320, 240, 64), 14);   // ceil(2^20 / 76,800)
    EXPECT_EQ(auto_samples_per_pass(1024, 1024, 16), 4);  // at least 4
    EXPECT_EQ(auto_samples_per_pass(4096, 4096, 16), 4);
    EXPECT_EQ(auto_samples_per_pass(512, 512, 2), 2);       // at most --spp
    EXPECT_EQ(auto_samples_per_pass(8, 8, 1 << 20), 1024);  // at most kMaxSamplesPerPass
    EXPECT_EQ(auto_samples_per_pass(1, 1, 1), 1);
    EXPECT_EQ(auto_samples_per_pass(16384, 16384, 1), 1);
    EXPECT_EQ(auto_samples_per_pass(8, 8, 0), 4);  // a time budget: passes of 4
    // An explicit value is kept, capped by --spp only when there is one.
    EXPECT_EQ(resolve_samples_per_pass(16, 320, 240, 0), 16);
    EXPECT_EQ(resolve_samples_per_pass(16, 320, 240, 8), 8);
    EXPECT_EQ(resolve_samples_per_pass(0, 320, 240, 8), 8);
    EXPECT_THROW(resolve_samples_per_pass(-1, 320, 240, 8), InputError);
    EXPECT_THROW(resolve_samples_per_pass(1025, 320, 240, 8), InputError);
}

TEST(Determinism, EmbreeRendersTheSameImageWithinRounding) {
#ifdef EDACRT_HAS_EMBREE
    // Embree's own arithmetic gives t within ~1e-6, so bounces start from points that differ
    // in the last bits: the same image up to a few paths that diverge.
    const Image ours = render_cornell(Method::naive, Integrator::path, 3, 8);
    const Image embree = render_cornell(Method::embree, Integrator::path, 3, 8);
    EXPECT_LT(compare_images(embree, ours).rmse, 1e-3);
#else
    GTEST_SKIP() << "built without Embree";
#endif
}

TEST(Progressive, MeanOfTwoHalfRendersEqualsAFullRender) {
    // Unbiased estimates of the same image: the per-pixel differences of (A + B) / 2 and C
    // have zero mean, up to their standard error.
    const Image a = render_cornell(Method::edacrt, Integrator::path, 1, 8);
    const Image b = render_cornell(Method::edacrt, Integrator::path, 2, 8);
    const Image c = render_cornell(Method::edacrt, Integrator::path, 3, 16);
    double sum = 0.0, squares = 0.0, level = 0.0;
    for (std::size_t i = 0; i < c.pixels.size(); ++i) {
        const glm::vec3 half_mean = 0.5f * (a.pixels[i] + b.pixels[i]);
        const double d = double(half_mean.x + half_mean.y + half_mean.z - c.pixels[i].x -
                                c.pixels[i].y - c.pixels[i].z);
        sum += d;
        squares += d * d;
        level += double(c.pixels[i].x + c.pixels[i].y + c.pixels[i].z);
    }
    const double n = double(c.pixels.size());
    const double mean = sum / n;
    const double standard_error = std::sqrt((squares / n - mean * mean) / n);
    EXPECT_LT(std::abs(mean), 4.0 * standard_error);
    EXPECT_LT(std::abs(mean), 0.02 * level / n);
    // And the film's mean over passes is what one longer render gives.
    EXPECT_GT(level / n, 0.05);
}

TEST(Progressive, CancelLeavesTheFilmUnchanged) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    const auto tracer = make_tracer(Method::edacrt);
    tracer->set_scene(scene);
    RenderSettings settings;
    settings.width = settings.height = 16;
    Renderer renderer(scene, *tracer, *scene.camera, settings);
    ASSERT_TRUE(renderer.render_pass());
    const Image before = renderer.film().mean();
    const std::atomic<bool> cancel{true};
    EXPECT_FALSE(renderer.render_pass(&cancel));
    EXPECT_EQ(renderer.film().passes(), 1);
    EXPECT_TRUE(renderer.film().mean().pixels == before.pixels);
    renderer.reset();
    EXPECT_EQ(renderer.film().passes(), 0);
}

class SelfIntersection : public ::testing::TestWithParam<const char*> {};

TEST_P(SelfIntersection, GrazingRaysNeverHitTheirOwnTriangle) {
    // Convex tessellated shapes: a ray leaving a face outwards hits nothing at all, and one
    // leaving it inwards hits another face. Grazing angles down to 1e-6 rad. The cube's faces
    // lie in coordinate planes, three of them through 0 after the shift, so their hit points
    // are exact (zero error bound) and only the triangle test's t bound keeps rays off them.
    Scene scene = make_builtin_scene(GetParam());
    if (std::string(GetParam()).find("cube") != std::string::npos)
        for (glm::vec3& p : scene.positions) p += glm::vec3(1.0f);
    std::vector<std::unique_ptr<Tracer>> tracers;
    for (Method method : {Method::naive, Method::edacrt, Method::dacrt, Method::bvh})
        tracers.push_back(make_tracer(method));
#ifdef EDACRT_HAS_EMBREE
    tracers.push_back(make_tracer(Method::embree));  // through its candidate filter
#endif
    for (const auto& tracer : tracers) tracer->set_scene(scene);
    std::vector<Ray> outward, inward;
    std::vector<std::int32_t> own;
    for (std::uint32_t prim = 0; prim < scene.triangle_count(); prim += 7) {
        const Triangle tri = scene.corners(prim);
        for (float u : {0.2f, 0.45f, 1e-4f})
            for (float grazing : {1e-1f, 1e-3f, 1e-6f}) {
                const float v = 0.3f;
                Hit hit{0.0f, std::int32_t(prim), u, v};
                // A ray that arrives at the point from outside, so the surface faces it.
                const glm::vec3 n = unit_normal(tri);
                const glm::vec3 p = (1 - u - v) * tri.p0 + u * tri.p1 + v * tri.p2;
                const Ray arriving{p + n, -n};
                const Surface s = make_surface(scene, arriving, hit);
                glm::vec3 t, b;
                orthonormal_basis(s.ng, t, b);
                for (glm::vec3 tangent : {t, b, -t}) {
                    outward.push_back(spawn_ray(s, glm::normalize(tangent + grazing * s.ng)));
                    inward.push_back(spawn_ray(s, glm::normalize(tangent - grazing * s.ng)));
                    own.push_back(std::int32_t(prim));
                }
            }
    }
    for (const auto& tracer : tracers) {
        std::vector<Hit> hits(outward.size());
        tracer->trace(outward, hits, Query::closest);
        for (std::size_t i = 0; i < hits.size(); ++i)
            ASSERT_FALSE(hits[i].hit())
                << enum_name(kMethods, tracer->method()) << " outward ray " << i << " hit triangle "
                << hits[i].prim << " at t " << hits[i].t << " (own " << own[i] << ")";
        tracer->trace(inward, hits, Query::closest);
        for (std::size_t i = 0; i < hits.size(); ++i) {
            ASSERT_TRUE(hits[i].hit())
                << enum_name(kMethods, tracer->method()) << " inward ray " << i;
            ASSERT_NE(hits[i].prim, own[i])
                << enum_name(kMethods, tracer->method()) << " inward ray " << i;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(ConvexShapes, SelfIntersection,
                         ::testing::Values("builtin:sphere:subdiv=4", "builtin:cube:n=4"),
                         [](const auto& info) {
                             return std::string(info.index == 0 ? "sphere" : "cube");
                         });

}  // namespace
}  // namespace edacrt
