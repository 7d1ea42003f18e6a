// Taking one batch of a render's first pass (render/batch_capture.h): its names, which batches a
// pass traces, and that the batch taken is exactly the one the renderer traced, wavefront by
// wavefront, with each ray's pixel, without changing the image.
#include "render/batch_capture.h"

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <set>

#include "render/renderer.h"
#include "render/wavefront.h"
#include "scene/builtin_scenes.h"
#include "trace/naive_tracer.h"
#include "util/error.h"

namespace edacrt {
namespace {

using Kind = BatchId::Kind;

/// A naive tracer that keeps every batch it was given, in order.
class RecordingTracer final : public Tracer {
  public:
    struct Batch {
        std::vector<Ray> rays;
        Query query;
    };
    std::vector<Batch> batches;

    Method method() const override { return Method::naive; }
    void set_scene(const Scene& scene) override { inner_.set_scene(scene); }
    std::size_t working_bytes() const override { return 0; }

  protected:
    TraceStats trace_batch(std::span<const Ray> rays, std::span<Hit> hits, Query query,
                           TraceDetail* detail) override {
        batches.push_back({{rays.begin(), rays.end()}, query});
        return inner_.trace(rays, hits, query, detail);
    }

  private:
    NaiveTracer inner_;
};

bool same_rays(std::span<const Ray> a, std::span<const Ray> b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Ray)) == 0;
}

RenderSettings small(Integrator integrator, int max_depth = 3) {
    RenderSettings settings;
    settings.width = 24;
    settings.height = 16;
    settings.integrator = integrator;
    settings.max_depth = max_depth;
    settings.ao_samples = 3;
    settings.seed = 5;
    return settings;
}

TEST(BatchCapture, NamesRoundTripAndBadNamesAreRefused) {
    for (const BatchId b : pass_batches(small(Integrator::path, 4)))
        EXPECT_EQ(parse_batch(batch_name(b)), b) << batch_name(b);
    EXPECT_EQ(parse_batch("ao"), (BatchId{Kind::ao, 0}));
    EXPECT_EQ(parse_batch("bounce:12"), (BatchId{Kind::bounce, 12}));
    for (const char* bad :
         {"", "bounce", "bounce:", "bounce:0", "bounce:-1", "bounce:1x", "bounce: 1", "shadow:-1",
          "Camera", "camera:0", "ao:1", "sky:2", "bounce:99999999999"})
        EXPECT_THROW(parse_batch(bad), InputError) << bad;
}

TEST(BatchCapture, APassListsItsBatchesInTheOrderItTracesThem) {
    const auto names = [](const RenderSettings& s, int max_bounces = 64) {
        std::vector<std::string> out;
        for (const BatchId b : pass_batches(s, max_bounces)) out.push_back(batch_name(b));
        return out;
    };
    EXPECT_EQ(names(small(Integrator::path, 2)),
              (std::vector<std::string>{"camera", "shadow:0", "bounce:1", "shadow:1", "bounce:2"}));
    EXPECT_EQ(names(small(Integrator::path, 0)), (std::vector<std::string>{"camera"}));
    EXPECT_EQ(names(small(Integrator::path, 1000), 1).size(), 3u);
    EXPECT_EQ(names(small(Integrator::ao)), (std::vector<std::string>{"camera", "ao"}));
    EXPECT_EQ(names(small(Integrator::primary)), (std::vector<std::string>{"camera"}));
    for (const Integrator integrator : {Integrator::path, Integrator::ao, Integrator::primary}) {
        const RenderSettings s = small(integrator, 2);
        for (const BatchId b : pass_batches(s)) EXPECT_NO_THROW(check_batch(b, s));
    }
    EXPECT_THROW(check_batch({Kind::bounce, 1}, small(Integrator::primary)), InputError);
    EXPECT_THROW(check_batch({Kind::ao, 0}, small(Integrator::path)), InputError);
    EXPECT_THROW(check_batch({Kind::shadow, 0}, small(Integrator::ao)), InputError);
    EXPECT_THROW(check_batch({Kind::bounce, 3}, small(Integrator::path, 2)), InputError);
    EXPECT_THROW(check_batch({Kind::shadow, 2}, small(Integrator::path, 2)), InputError);
}

/// Path tracing in one wavefront: the recorded batches are camera, then per bounce the shadow
/// batch (any hit, when there is one) and the next bounce (closest hit). Each captured batch is
/// the recorded one, byte for byte, and its pixels are those of its paths.
TEST(BatchCapture, TheBatchIsTheOneTheRendererTraced) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    const RenderSettings settings = small(Integrator::path, 4);
    RecordingTracer recorder;
    recorder.set_scene(scene);
    {
        RenderSettings one = settings;
        Renderer renderer(scene, recorder, *scene.camera, one);
        ASSERT_TRUE(renderer.render_pass());
    }
    std::map<std::string, const RecordingTracer::Batch*> expected;
    int bounce = -1;
    for (const auto& b : recorder.batches) {
        if (b.query == Query::closest) ++bounce;
        const BatchId id = b.query == Query::any ? BatchId{Kind::shadow, bounce}
                           : bounce == 0         ? BatchId{}
                                                 : BatchId{Kind::bounce, bounce};
        expected[batch_name(id)] = &b;
    }
    ASSERT_GE(expected.size(), 5u) << "camera, shadow:0, bounce:1, shadow:1, bounce:2 at least";
    const std::vector<Ray> camera = first_pass_camera_rays(*scene.camera, settings);
    NaiveTracer naive;
    naive.set_scene(scene);
    std::vector<Hit> camera_hits(camera.size());
    naive.trace(camera, camera_hits, Query::closest);
    for (const BatchId id : pass_batches(settings)) {
        SCOPED_TRACE(batch_name(id));
        const CapturedBatch batch = capture_batch(scene, naive, *scene.camera, settings, id);
        EXPECT_EQ(batch.id, id);
        ASSERT_EQ(batch.pixels.size(), batch.rays.size());
        const auto found = expected.find(batch_name(id));
        if (found == expected.end()) {
            EXPECT_TRUE(batch.rays.empty());
            continue;
        }
        EXPECT_TRUE(same_rays(batch.rays, found->second->rays));
        EXPECT_EQ(batch_query(id), found->second->query);
        // One sample per pixel: a pixel has at most one ray per batch.
        EXPECT_EQ(std::set<std::uint32_t>(batch.pixels.begin(), batch.pixels.end()).size(),
                  batch.pixels.size());
        for (std::size_t i = 0; i < batch.rays.size(); ++i) {
            const std::uint32_t p = batch.pixels[i];
            ASSERT_LT(p, camera.size());
            if (id == BatchId{}) {
                EXPECT_EQ(p, i);
            } else if (id.bounce == 0 || (id.kind == Kind::bounce && id.bounce == 1)) {
                // Rays from the camera ray's hit in the same pixel.
                const Ray& c = camera[p];
                const glm::vec3 hit = c.org + camera_hits[p].t * c.dir;
                EXPECT_LT(glm::length(batch.rays[i].org - hit), 1e-2f) << "pixel " << p;
            }
        }
    }
    EXPECT_TRUE(same_rays(capture_batch(scene, naive, *scene.camera, settings, {}).rays, camera));
}

TEST(BatchCapture, WavefrontsAddUpAndTheImageIsTheSame) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    for (const Integrator integrator : {Integrator::path, Integrator::ao, Integrator::primary}) {
        SCOPED_TRACE(std::string(enum_name(kIntegrators, integrator)));
        RenderSettings whole = small(integrator, 3);
        RenderSettings pieces = whole;
        pieces.wavefront_paths = 50;  // eight wavefronts, the last one short
        NaiveTracer naive;
        naive.set_scene(scene);
        for (const BatchId id : pass_batches(whole)) {
            SCOPED_TRACE(batch_name(id));
            const CapturedBatch a = capture_batch(scene, naive, *scene.camera, whole, id);
            const CapturedBatch b = capture_batch(scene, naive, *scene.camera, pieces, id);
            EXPECT_TRUE(same_rays(a.rays, b.rays));
            EXPECT_EQ(a.pixels, b.pixels);
            if (id.kind == Kind::ao) {
                // ao-samples rays per camera hit, each hit's together.
                ASSERT_EQ(a.rays.size() % 3, 0u);
                for (std::size_t i = 0; i < a.pixels.size(); ++i)
                    EXPECT_EQ(a.pixels[i], a.pixels[i - i % 3]);
            }
        }
        // Capturing changes nothing the renderer computes.
        Renderer plain(scene, naive, *scene.camera, whole),
            capturing(scene, naive, *scene.camera, whole);
        CapturedBatch batch;
        batch.id = pass_batches(whole).back();
        ASSERT_TRUE(plain.render_pass());
        ASSERT_TRUE(capturing.render_pass(nullptr, nullptr, 0, &batch));
        EXPECT_FALSE(batch.rays.empty());
        EXPECT_TRUE(plain.film().mean().pixels == capturing.film().mean().pixels);
    }
}

TEST(BatchCapture, ABounceNoPathReachesIsEmptyAndABatchThePassNeverTracesIsAnError) {
    // A square under the sky: bounce 1 leaves it upwards and escapes, so no path has a bounce 2.
    Scene plane;
    plane.source = "plane";
    plane.positions = {{-50, 0, -50}, {50, 0, -50}, {50, 0, 50}, {-50, 0, 50}};
    plane.triangles = {{0, 1, 2}, {0, 2, 3}};
    plane.triangle_materials = {0, 0};
    plane.materials.resize(1);
    plane.materials[0].kd = glm::vec3(0.5f);
    const Camera down{{0, 1, 0}, {0, 0, 0}, {0, 0, -1}, 60.0f};
    NaiveTracer naive;
    naive.set_scene(plane);
    const RenderSettings settings = small(Integrator::path, 3);
    EXPECT_EQ(capture_batch(plane, naive, down, settings, {Kind::bounce, 1}).rays.size(),
              std::size_t(settings.width * settings.height));
    EXPECT_TRUE(capture_batch(plane, naive, down, settings, {Kind::bounce, 2}).rays.empty());
    EXPECT_TRUE(capture_batch(plane, naive, down, settings, {Kind::shadow, 0}).rays.empty())
        << "no emitters: no shadow rays";
    EXPECT_THROW(capture_batch(plane, naive, down, settings, {Kind::bounce, 4}), InputError);
    EXPECT_THROW(capture_batch(plane, naive, down, settings, {Kind::ao, 0}), InputError);
}

}  // namespace
}  // namespace edacrt
