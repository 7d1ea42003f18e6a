#pragma once
// The progressive wavefront renderer: each pass adds samples to every pixel of the film, all of
// them traced together as one wavefront (or a few, within a memory budget), every bounce of a
// wavefront one batch of the chosen Tracer.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "render/film.h"
#include "render/render_settings.h"
#include "render/shading_scene.h"
#include "render/wavefront.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/tracer.h"

namespace edacrt {

class Renderer {
  public:
    /// `tracer` must have been given `scene` (set_scene); both must outlive the renderer.
    /// Throws InputError for bad settings or camera.
    Renderer(const Scene& scene, Tracer& tracer, const Camera& camera,
             const RenderSettings& settings);

    /// Renders the next pass, `samples` samples per pixel (0: settings().samples_per_pass, the
    /// most a pass may take), into the film. Returns false, leaving the film as it was, when
    /// `cancel` became true (it is checked before every batch). With `primary_detail`, also
    /// records the per-level and per-pixel statistics of the first sample's camera rays
    /// (untimed). With `capture`, also takes the batch it names (capture_batch()). The image
    /// depends on the samples rendered so far, not on how passes group them.
    bool render_pass(const std::atomic<bool>* cancel = nullptr,
                     TraceDetail* primary_detail = nullptr, int samples = 0,
                     CapturedBatch* capture = nullptr);

    /// Starts over (the next pass is sample 0 again).
    void reset();

    /// Takes another frame of the scene's animation for the next passes: `scene` holds the same
    /// triangles and materials with new positions (Animation::frame() wrote it, into the
    /// constructor's scene or another buffer that must outlive its use), and the tracer took it
    /// with update_scene(). The lights' areas and the scene's bounds are recomputed. The film
    /// starts over, unless `keep_film`: then the next passes add to it, so passes rendered at
    /// several times of a shutter interval average into motion blur.
    void scene_changed(const Scene& scene, bool keep_film = false);

    const Film& film() const { return film_; }
    const RenderSettings& settings() const { return settings_; }
    const PassStats& last_pass() const { return last_pass_; }
    const PassStats& total() const { return total_; }
    /// MTL settings the renderer approximates (to be reported once).
    const std::vector<std::string>& notes() const { return shading_.notes; }

  private:
    const Scene* scene_;  // never null
    Tracer& tracer_;
    RenderSettings settings_;
    PinholeProjection projection_;
    ShadingScene shading_;
    Film film_;
    PassStats last_pass_, total_;
    std::vector<glm::vec3> samples_;  // the pass being rendered, sample-major
    WavefrontBuffers buffers_;        // the integrators' arrays, kept between passes
};

}  // namespace edacrt
