#include "render/batch_capture.h"

#include <algorithm>
#include <charconv>

#include "render/renderer.h"
#include "util/error.h"

namespace edacrt {

std::string batch_name(BatchId batch) {
    switch (batch.kind) {
        case BatchId::Kind::camera:
            return "camera";
        case BatchId::Kind::bounce:
            return "bounce:" + std::to_string(batch.bounce);
        case BatchId::Kind::shadow:
            return "shadow:" + std::to_string(batch.bounce);
        case BatchId::Kind::ao:
            return "ao";
    }
    return "?";
}

BatchId parse_batch(std::string_view text) {
    const auto bad = [&] {
        return InputError("unknown batch '" + std::string(text) +
                          "' (known: camera, bounce:N for N >= 1, shadow:N for N >= 0, ao)");
    };
    if (text == "camera") return {};
    if (text == "ao") return {BatchId::Kind::ao, 0};
    const std::size_t colon = text.find(':');
    if (colon == std::string_view::npos) throw bad();
    const std::string_view kind = text.substr(0, colon), number = text.substr(colon + 1);
    int n = -1;
    const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), n);
    if (error != std::errc() || end != number.data() + number.size() || number.empty()) throw bad();
    if (kind == "bounce" && n >= 1) return {BatchId::Kind::bounce, n};
    if (kind == "shadow" && n >= 0) return {BatchId::Kind::shadow, n};
    throw bad();
}

Query batch_query(BatchId batch) {
    const bool closest = batch.kind == BatchId::Kind::camera || batch.kind == BatchId::Kind::bounce;
    return closest ? Query::closest : Query::any;
}

std::vector<BatchId> pass_batches(const RenderSettings& settings, int max_bounces) {
    std::vector<BatchId> out{BatchId{}};
    if (settings.integrator == Integrator::ao) out.push_back({BatchId::Kind::ao, 0});
    if (settings.integrator != Integrator::path) return out;
    const int bounces = std::min(settings.max_depth, max_bounces);
    for (int n = 0; n < bounces; ++n) {
        out.push_back({BatchId::Kind::shadow, n});
        out.push_back({BatchId::Kind::bounce, n + 1});
    }
    return out;
}

void check_batch(BatchId batch, const RenderSettings& settings) {
    const std::string name = batch_name(batch);
    const auto refuse = [&](const std::string& why) {
        throw InputError("no batch " + name + ": " + why);
    };
    const bool path = settings.integrator == Integrator::path;
    switch (batch.kind) {
        case BatchId::Kind::camera:
            return;
        case BatchId::Kind::ao:
            if (settings.integrator != Integrator::ao)
                refuse("only the ao integrator traces AO rays");
            return;
        case BatchId::Kind::bounce:
        case BatchId::Kind::shadow:
            if (!path) refuse("only the path integrator traces bounces and shadow rays");
            // Paths end at max_depth bounces; the hits of the last make no shadow rays.
            if (batch.kind == BatchId::Kind::bounce && batch.bounce > settings.max_depth)
                refuse("paths end after max-depth " + std::to_string(settings.max_depth) +
                       " bounces");
            if (batch.kind == BatchId::Kind::shadow && batch.bounce >= settings.max_depth)
                refuse("the hits of bounce " + std::to_string(settings.max_depth) +
                       " (max-depth) make no shadow rays");
            return;
    }
}

CapturedBatch capture_batch(const Scene& scene, Tracer& tracer, const Camera& camera,
                            RenderSettings settings, BatchId id) {
    check_batch(id, settings);
    settings.samples_per_pass = 1;
    Renderer renderer(scene, tracer, camera, settings);
    CapturedBatch batch;
    batch.id = id;
    renderer.render_pass(nullptr, nullptr, 1, &batch);
    return batch;
}

}  // namespace edacrt
