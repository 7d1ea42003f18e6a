#include "render/render_settings.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "render/render_limits.h"
#include "render/render_memory.h"
#include "util/error.h"

namespace edacrt {

void validate(const RenderSettings& s) {
    const auto fail = [](const std::string& what) { throw InputError(what); };
    if (s.width < 1 || s.width > 16384 || s.height < 1 || s.height > 16384)
        fail("image size must be 1..16384 pixels per side, got " + std::to_string(s.width) + "x" +
             std::to_string(s.height));
    if (s.max_depth < 0 || s.max_depth > kMaxMaxDepth)
        fail("max depth must be 0.." + std::to_string(kMaxMaxDepth) + ", got " +
             std::to_string(s.max_depth));
    if (s.roulette_depth < 0) fail("roulette depth must be >= 0");
    if (s.ao_samples < 1 || s.ao_samples > kMaxAoSamples)
        fail("ao samples must be 1.." + std::to_string(kMaxAoSamples) + ", got " +
             std::to_string(s.ao_samples));
    if (!std::isfinite(s.ao_distance) || s.ao_distance < 0.0f)
        fail("ao distance must be finite and >= 0 (0: a quarter of the scene size)");
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(s.sky[c]) || s.sky[c] < 0.0f)
            fail("sky radiance must be finite and >= 0");
    if (s.samples_per_pass < 1 || s.samples_per_pass > kMaxSamplesPerPass)
        fail("samples per pass must be 1.." + std::to_string(kMaxSamplesPerPass) + ", got " +
             std::to_string(s.samples_per_pass));
}

int auto_samples_per_pass(int width, int height, int spp) {
    const std::uint64_t pixels =
        std::uint64_t(std::max(width, 1)) * std::uint64_t(std::max(height, 1));
    const std::uint64_t samples =
        std::max<std::uint64_t>(4, (kAutoPassPaths + pixels - 1) / pixels);
    if (spp <= 0) return 4;  // no sample count: a time budget ends the render
    return int(std::min<std::uint64_t>({samples, std::uint64_t(spp), kMaxSamplesPerPass}));
}

std::size_t wavefront_paths(const RenderSettings& settings, std::uint64_t paths) {
    std::uint64_t wave = settings.wavefront_paths;
    if (wave == 0)
        wave = kWavefrontBudget / wavefront_bytes_per_path(settings);
    else if (settings.integrator == Integrator::ao)
        wave /= std::uint64_t(settings.ao_samples);
    return std::size_t(std::clamp<std::uint64_t>(std::min(wave, paths), 1, paths > 0 ? paths : 1));
}

int resolve_samples_per_pass(int requested, int width, int height, int spp) {
    if (requested < 0 || requested > kMaxSamplesPerPass)
        throw InputError("--samples-per-pass must be 0.." + std::to_string(kMaxSamplesPerPass) +
                         " (0: about 1M paths per pass), got " + std::to_string(requested));
    if (requested == 0) return auto_samples_per_pass(width, height, spp);
    return spp > 0 ? std::min(requested, spp) : requested;
}

}  // namespace edacrt
