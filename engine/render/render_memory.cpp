#include "render/render_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "geometry/ray.h"
#include "geometry/ray_box.h"
#include "geometry/triangle.h"
#include "trace/ray_stream.h"
#include "trace/trace_stats.h"
#include "util/error.h"
#include "util/input_file.h"

namespace edacrt {
namespace {

// EdacrtTracer's ray stream, the most any method keeps per ray.
constexpr std::uint64_t kTracerBytesPerRay = RayStream::kBytesPerRay;

// The path integrator's per-path state (PathState in integrator_path.cpp: throughput, pixel,
// pdf).
constexpr std::uint64_t kPathStateBytes = sizeof(glm::vec3) + 2 * 4;

std::optional<std::uint64_t> read_number(const char* path) {
    std::string text;
    try {
        // A limit file holds one number; the cap keeps a strange mount from being read whole.
        text = read_text_file(path, "limit file", 4096);
    } catch (const InputError&) {
        return std::nullopt;
    }
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;  // "max"
    return value;
}

std::string format_bytes(std::uint64_t bytes) {
    char text[32];
    if (bytes < 1'000'000'000)
        std::snprintf(text, sizeof text, "%.0f MB", double(bytes) * 1e-6);
    else
        std::snprintf(text, sizeof text, "%.1f GB", double(bytes) * 1e-9);
    return text;
}

}  // namespace

std::uint64_t wavefront_bytes_per_path(const RenderSettings& s) {
    const std::uint64_t traced = trace_bytes_per_ray();
    switch (s.integrator) {
        case Integrator::primary:  // camera rays and hits
            return traced;
        case Integrator::ao:  // camera rays and hits, the hit list, ao_samples rays per hit
            return traced + sizeof(std::uint32_t) + std::uint64_t(s.ao_samples) * traced;
        case Integrator::path:
            // Rays and hits; the next rays, the shadow rays and the compacted shadow batch, with
            // its hits; path states, shadow contributions, two flags and the shadow index.
            return traced + 3 * sizeof(Ray) + sizeof(Hit) + kPathStateBytes + sizeof(glm::vec3) +
                   2 + sizeof(std::uint32_t);
    }
    return traced;
}

std::uint64_t trace_bytes_per_ray(bool detail) {
    return sizeof(Ray) + sizeof(Hit) + kTracerBytesPerRay +
           // RecordingObserver: three path words and a depth per ray
           (detail ? sizeof(RayStats) + 3 * sizeof(std::uint64_t) + sizeof(std::uint16_t) : 0);
}

std::uint64_t render_memory_bytes(const RenderSettings& settings,
                                  std::uint64_t extra_bytes_per_pixel) {
    const std::uint64_t pixels = std::uint64_t(settings.width) * std::uint64_t(settings.height);
    const auto samples = std::uint64_t(settings.samples_per_pass);
    const std::uint64_t wave = wavefront_paths(settings, pixels * samples);
    // Film: a double sum per pixel; Renderer: the pass's float samples.
    const std::uint64_t per_pixel =
        sizeof(glm::dvec3) + samples * sizeof(glm::vec3) + extra_bytes_per_pixel;
    return pixels * per_pixel + wave * wavefront_bytes_per_path(settings);
}

MemoryLimit memory_limit() {
    MemoryLimit limit{
        std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE)),
        "physical memory"};
    const auto lower = [&](std::optional<std::uint64_t> bytes, const char* source) {
        if (bytes && *bytes < limit.bytes) limit = {*bytes, source};
    };
    lower(read_number("/sys/fs/cgroup/memory.max"), "the cgroup memory limit");
    lower(read_number("/sys/fs/cgroup/memory/memory.limit_in_bytes"), "the cgroup memory limit");
    rlimit address_space{};
    if (getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY)
        lower(std::uint64_t(address_space.rlim_cur), "the address-space limit (ulimit -v)");
    if (const char* env = std::getenv("EDACRT_MEMORY_LIMIT"); env && *env) {
        const std::string_view text(env);
        std::uint64_t bytes = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), bytes);
        if (ec != std::errc{} || end != text.data() + text.size())
            throw InputError("EDACRT_MEMORY_LIMIT must be a number of bytes, got '" +
                             std::string(text.substr(0, 40)) + "'");
        lower(bytes, "EDACRT_MEMORY_LIMIT");
    }
    return limit;
}

void check_render_memory(const RenderSettings& settings, std::uint64_t extra_bytes_per_pixel) {
    const std::uint64_t need = render_memory_bytes(settings, extra_bytes_per_pixel);
    const MemoryLimit limit = memory_limit();
    if (need <= limit.bytes) return;
    const std::uint64_t pixels = std::uint64_t(settings.width) * std::uint64_t(settings.height);
    throw InputError("a " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                     " " + std::string(enum_name(kIntegrators, settings.integrator)) +
                     " render needs about " + format_bytes(need) + " of memory (" +
                     std::to_string(need / pixels) + " bytes per pixel), more than the " +
                     format_bytes(limit.bytes) + " of " + limit.source + "; choose a smaller size");
}

}  // namespace edacrt
