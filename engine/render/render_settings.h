#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <string_view>

#include "util/enum_table.h"

namespace edacrt {

/// primary: one camera ray per sample, shaded for debugging; ao: ambient occlusion; path:
/// unidirectional path tracing with next-event estimation and MIS.
enum class Integrator { primary, ao, path };
inline constexpr auto kIntegrators = enum_table<Integrator>(
    "integrator", {{Integrator::primary, "primary", "camera rays only, debug shading"},
                   {Integrator::ao, "ao", "ambient occlusion"},
                   {Integrator::path, "path", "path tracing with next-event estimation"}});

/// What the primary integrator shows: eye-light (Lambertian lit from the eye), the shading
/// normal (0.5 n + 0.5), the diffuse albedo, or depth (1 near, 0 at the far end of the scene).
enum class PrimaryShading { eye_light, normal, albedo, depth };
inline constexpr auto kPrimaryShadings = enum_table<PrimaryShading>(
    "primary shading", {{PrimaryShading::eye_light, "eye-light", "Lambertian, lit from the eye"},
                        {PrimaryShading::normal, "normal", "the shading normal"},
                        {PrimaryShading::albedo, "albedo", "the diffuse albedo"},
                        {PrimaryShading::depth, "depth", "1 near, 0 at the far end"}});

struct RenderSettings {
    int width = 512;
    int height = 512;
    Integrator integrator = Integrator::path;
    PrimaryShading primary = PrimaryShading::eye_light;
    int max_depth = 8;         // path: bounces after the camera ray (0: emitters seen directly)
    int roulette_depth = 3;    // path: Russian roulette from this bounce on
    int ao_samples = 4;        // ao: rays per hit
    float ao_distance = 0.0f;  // ao: occluders farther than this do not count (0: 1/4 scene size)
    glm::vec3 sky{1.0f};       // radiance of the sky seen by path and ao when nothing is hit,
                               // used by `path` only when the scene has no emitters
    std::uint32_t seed = 0;
    // Samples per pixel a pass renders at most (Renderer::render_pass): a pass traces them all
    // together, so that a divide-and-conquer tracer gets large batches of coherent rays.
    int samples_per_pass = 1;
    // Paths traced as one wavefront; 0: every path of the pass, as far as kWavefrontBudget
    // allows.
    std::size_t wavefront_paths = 0;

    bool operator==(const RenderSettings&) const = default;
};

/// The most samples per pixel one pass may render.
inline constexpr int kMaxSamplesPerPass = 1024;

/// `--samples-per-pass 0`: samples per pixel for passes of about this many paths. A
/// divide-and-conquer tracer pays per batch for binning and partitioning the triangles at every
/// level its rays reach, whatever their number: in Sponza, a late bounce of 21k rays took 29 ms
/// with EDACRT against 7 ms with Embree. So larger passes, fewer and larger batches: at 320x240
/// and 8 spp, passes of 8 samples instead of 4 made a path-traced Sponza render 0.87x the time
/// with EDACRT and 1.05x with Embree (whole renders, 5 interleaved pairs, 2 threads).
inline constexpr std::uint64_t kAutoPassPaths = std::uint64_t(1) << 20;

/// Samples per pass for `--samples-per-pass 0`: kAutoPassPaths paths per pass, but at least 4
/// samples (the interactive default) and at most `spp` and kMaxSamplesPerPass. `spp` 0: no
/// sample count (a time budget ends the render after the pass that reaches it), passes of 4,
/// so that it stops near the budget.
int auto_samples_per_pass(int width, int height, int spp);

/// The samples per pass a render of `spp` samples per pixel (0: as many as a time budget
/// allows) takes for `--samples-per-pass requested`: 0 is auto_samples_per_pass, and no pass
/// takes more than `spp`. Throws InputError when `requested` is outside 0..kMaxSamplesPerPass.
int resolve_samples_per_pass(int requested, int width, int height, int spp);

/// Throws InputError naming the first setting out of range.
void validate(const RenderSettings& settings);

/// Bytes of wavefront state a pass may take when wavefront_paths is 0 (whole passes).
inline constexpr std::uint64_t kWavefrontBudget = std::uint64_t(1) << 30;

/// Paths per wavefront for a pass of `paths` paths: wavefront_paths (for ao divided by
/// ao_samples, so that a wavefront's AO batch holds about wavefront_paths rays) or, when it is
/// 0, the whole pass within kWavefrontBudget. Never more than `paths`, never 0.
std::size_t wavefront_paths(const RenderSettings& settings, std::uint64_t paths);

}  // namespace edacrt
