// The memory estimate of a render and the refusal of one that cannot fit, with the figure.
#include "render/render_memory.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "util/error.h"

namespace edacrt {
namespace {

/// Sets $EDACRT_MEMORY_LIMIT for the lifetime of the object.
class MemoryLimitOverride {
  public:
    explicit MemoryLimitOverride(const std::string& bytes) {
        if (const char* old = std::getenv("EDACRT_MEMORY_LIMIT")) old_ = old;
        setenv("EDACRT_MEMORY_LIMIT", bytes.c_str(), 1);
    }
    ~MemoryLimitOverride() {
        if (old_)
            setenv("EDACRT_MEMORY_LIMIT", old_->c_str(), 1);
        else
            unsetenv("EDACRT_MEMORY_LIMIT");
    }

  private:
    std::optional<std::string> old_;
};

std::string refusal(const RenderSettings& settings, std::uint64_t extra = 0) {
    try {
        check_render_memory(settings, extra);
    } catch (const InputError& e) {
        return e.what();
    }
    return "accepted";
}

TEST(RenderMemory, FilmSamplesAndOneWavefront) {
    RenderSettings settings;
    settings.width = 16384;
    settings.height = 16384;
    const std::uint64_t pixels = 16384ull * 16384ull;
    // The film's double sums and the pass's float samples; the path tracer's wavefront, here
    // as many paths as fit the budget.
    const std::uint64_t per_path = wavefront_bytes_per_path(settings);
    EXPECT_GT(per_path, 4 * sizeof(Ray));  // rays, next, shadow and batch
    const std::uint64_t wave = kWavefrontBudget / per_path;
    EXPECT_EQ(wavefront_paths(settings, pixels), wave);
    EXPECT_EQ(render_memory_bytes(settings), 36 * pixels + wave * per_path);
    EXPECT_LE(wave * per_path, kWavefrontBudget);
    EXPECT_EQ(render_memory_bytes(settings, 24) - render_memory_bytes(settings), 24 * pixels);
    // Several samples per pass: a float sample each, the same wavefront.
    settings.samples_per_pass = 4;
    EXPECT_EQ(render_memory_bytes(settings), (24 + 4 * 12) * pixels + wave * per_path);
    // A small image is one wavefront of all its paths; an explicit size is taken as given.
    settings.width = settings.height = 16;
    EXPECT_EQ(wavefront_paths(settings, 4 * 256), 4u * 256u);
    EXPECT_EQ(render_memory_bytes(settings), 256 * (24 + 4 * 12) + 4 * 256 * per_path);
    settings.wavefront_paths = 100;
    EXPECT_EQ(wavefront_paths(settings, 4 * 256), 100u);
    EXPECT_EQ(wavefront_paths(settings, 50), 50u);
}

TEST(RenderMemory, AmbientOcclusionWavefrontsShrinkWithTheirRays) {
    RenderSettings settings;
    settings.integrator = Integrator::ao;
    settings.width = settings.height = 512;
    settings.ao_samples = 1024;
    settings.wavefront_paths = 1 << 18;
    EXPECT_EQ(wavefront_paths(settings, 512 * 512), settings.wavefront_paths / 1024);
    // About wavefront_paths AO rays per batch, whatever ao_samples: well under a gigabyte
    // here (the whole 512x512 image as one wavefront needed 35 GB).
    EXPECT_LT(render_memory_bytes(settings), 100'000'000u);
    // Whole passes stay within the budget too.
    settings.wavefront_paths = 0;
    EXPECT_LE(render_memory_bytes(settings), 512 * 512 * 36 + kWavefrontBudget);
}

TEST(RenderMemory, WhatCannotFitIsRefusedWithTheFigure) {
    const MemoryLimitOverride limit("100000000");
    EXPECT_EQ(memory_limit().bytes, 100'000'000u);
    EXPECT_EQ(memory_limit().source, "EDACRT_MEMORY_LIMIT");
    RenderSettings settings;
    settings.width = 2048;
    settings.height = 1024;
    const std::uint64_t need = render_memory_bytes(settings);
    EXPECT_EQ(refusal(settings), "a 2048x1024 path render needs about " +
                                     std::to_string((need + 500'000) / 1'000'000) +
                                     " MB of memory (" + std::to_string(need / (2048 * 1024)) +
                                     " bytes per pixel), more than the 100 MB of "
                                     "EDACRT_MEMORY_LIMIT; choose a smaller size");
    settings.width = settings.height = 512;
    EXPECT_EQ(refusal(settings), "accepted");
    const std::uint64_t with_extra = render_memory_bytes(settings, 400) / (512 * 512);
    EXPECT_NE(refusal(settings, 400).find("(" + std::to_string(with_extra) + " bytes per pixel)"),
              std::string::npos);
    // The renderer checks too, before allocating anything.
    const Scene scene = make_builtin_scene("builtin:cornell");
    const auto tracer = make_tracer(Method::naive);
    settings.width = settings.height = 8192;
    EXPECT_THROW(Renderer(scene, *tracer, *scene.camera, settings), InputError);
}

TEST(RenderMemory, AnOverrideThatIsNotANumberIsAnError) {
    const MemoryLimit limit = memory_limit();
    EXPECT_GT(limit.bytes, 0u);
    const MemoryLimitOverride garbage("lots");
    EXPECT_THROW(memory_limit(), InputError);
}

}  // namespace
}  // namespace edacrt
