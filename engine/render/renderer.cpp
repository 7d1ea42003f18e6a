#include "render/renderer.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "render/render_memory.h"

namespace edacrt {
namespace {

const Camera& validated(const Camera& camera) {
    validate(camera);
    return camera;
}

const RenderSettings& validated(const RenderSettings& settings) {
    validate(settings);
    check_render_memory(settings);
    return settings;
}

}  // namespace

Renderer::Renderer(const Scene& scene, Tracer& tracer, const Camera& camera,
                   const RenderSettings& settings)
    : scene_(&scene),
      tracer_(tracer),
      settings_(validated(settings)),
      projection_(validated(camera), settings.width, settings.height),
      shading_(scene),
      film_(settings.width, settings.height),
      samples_(std::size_t(settings.width) * std::size_t(settings.height) *
               std::size_t(settings.samples_per_pass)) {}

bool Renderer::render_pass(const std::atomic<bool>* cancel, TraceDetail* primary_detail,
                           int samples, CapturedBatch* capture) {
    if (samples == 0) samples = settings_.samples_per_pass;
    if (samples < 1 || samples > settings_.samples_per_pass)
        throw std::invalid_argument("Renderer::render_pass: " + std::to_string(samples) +
                                    " samples, at most " +
                                    std::to_string(settings_.samples_per_pass) + " per pass");
    const auto start = std::chrono::steady_clock::now();
    PassStats stats;
    const std::size_t pixels = std::size_t(settings_.width) * std::size_t(settings_.height);
    Wavefront wf{*scene_, shading_, tracer_, settings_, projection_, std::uint32_t(film_.passes()),
                 pixels,  cancel,   stats,   buffers_,  capture};
    const std::size_t paths = pixels * std::size_t(samples);
    const std::size_t wave = wavefront_paths(settings_, paths);
    for (std::size_t begin = 0; begin < paths; begin += wave) {
        const std::size_t end = std::min(paths, begin + wave);
        const std::span<glm::vec3> tile(samples_.data() + begin, end - begin);
        bool done = false;
        switch (settings_.integrator) {
            case Integrator::primary:
                done = render_primary(wf, begin, end, tile);
                break;
            case Integrator::ao:
                done = render_ao(wf, begin, end, tile);
                break;
            case Integrator::path:
                done = render_path(wf, begin, end, tile);
                break;
        }
        if (!done) return false;
    }
    double untimed = 0.0;
    if (primary_detail) {
        // The pass's camera rays again, untimed, as one batch: one recursion to show.
        if (wf.cancelled()) return false;
        const auto detail_start = std::chrono::steady_clock::now();
        std::vector<Ray> rays;
        wf.camera_rays(0, pixels, rays);
        std::vector<Hit> hits(rays.size());
        tracer_.trace(rays, hits, Query::closest, primary_detail);
        untimed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - detail_start).count();
    }
    const std::span<glm::vec3> rendered(samples_.data(), paths);
    for (glm::vec3& sample : rendered)
        if (!std::isfinite(sample.x) || !std::isfinite(sample.y) || !std::isfinite(sample.z)) {
            sample = glm::vec3(0.0f);
            ++stats.dropped_samples;
        }
    // In sample order, as passes of one sample would add them: the same sums.
    for (int k = 0; k < samples; ++k)
        film_.add_pass(rendered.subspan(std::size_t(k) * pixels, pixels));
    stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - untimed;
    last_pass_ = stats;
    total_ += stats;
    return true;
}

void Renderer::reset() {
    film_.reset();
    last_pass_ = total_ = PassStats{};
}

void Renderer::scene_changed(const Scene& scene, bool keep_film) {
    scene_ = &scene;
    shading_ = ShadingScene(scene);
    if (!keep_film) reset();
}

}  // namespace edacrt
