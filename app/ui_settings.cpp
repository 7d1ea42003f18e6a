// The viewer's settings as the script and tests drive them: `set KEY VALUE`, and whether a
// recording still describes the render in progress.
#include <oneapi/tbb/info.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string_view>

#include "settings_table.h"
#include "util/error.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

/// The keys of `set` that are not settings (viewer_settings()) or EDACRT parameters: they act.
struct SetAction {
    std::string_view key;
    void (*run)(ViewerState&, const std::string& value);
};

int whole_number(const std::string& key, const std::string& value) {
    try {
        std::size_t used = 0;
        const double v = std::stod(value, &used);
        if (used != value.size() || !std::isfinite(v)) throw std::invalid_argument(value);
        return int(std::clamp(v, -2147483648.0, 2147483647.0));
    } catch (const std::exception&) {
        throw InputError("'" + key + "' needs a number, got '" + value + "'");
    }
}

const SetAction kSetActions[] = {
    {"preset", [](ViewerState& s, const std::string& v) { s.ui.params = preset_params(v); }},
    {"scene", [](ViewerState& s, const std::string& v) { s.pending_loads.push_back(v); }},
    {"animate",
     [](ViewerState& s, const std::string& v) {
         load_into(s, s.scene_path, {}, v, true);
         if (!s.scene_error.empty()) throw InputError(s.scene_error);
     }},
    {"level",
     [](ViewerState& s, const std::string& v) { s.explorer_level = whole_number("level", v); }},
    {"node",
     [](ViewerState& s, const std::string& v) { s.explorer_node = whole_number("node", v); }},
    {"crop",
     [](ViewerState& s, const std::string& v) { s.explorer_crop = whole_number("crop", v) != 0; }},
    {"region",
     [](ViewerState& s, const std::string& v) {
         s.explorer_region = parse_region(v);
         s.explorer_crop = true;
         s.analysis_requested = true;  // as a dragged region is recorded
     }},
    {"against",
     [](ViewerState& s, const std::string& v) {
         if (v != "none") preset_params(v);  // throws for an unknown preset
         s.against = v == "none" ? "" : v;
         s.analysis_requested = true;
     }},
    {"heat-of",
     [](ViewerState& s, const std::string& v) { s.heat_of = parse_enum_or_throw(kHeatOf, v); }},
    {"batch",
     [](ViewerState& s, const std::string& v) {
         s.batch = parse_batch(v);
         s.analysis_requested = s.batch != BatchId{};
     }},
    {"step",
     [](ViewerState& s, const std::string& v) {
         s.step = whole_number("step", v);
         s.stepping = true;
     }},
};

}  // namespace

std::string param_inert_reason(const UiSettings& ui, const ParamInfo& info) {
    if (ui.method != Method::edacrt && ui.method != Method::dacrt)
        return "only the edacrt and dacrt methods use it";
    const bool dacrt = ui.method == Method::dacrt;
    if (dacrt && dacrt_sets(info.key))
        return "the dacrt method sets it: surface-area hit ratios, direction-sign order, "
               "filter skipping off";
    const int cores = tbb::info::default_concurrency();
    const int threads = ui.threads > 0 ? std::min(ui.threads, cores) : cores;
    const auto reason =
        param_no_effect_reason(dacrt ? dacrt_params(ui.params) : ui.params, info, threads);
    return reason ? std::string(*reason) : std::string();
}

void apply_setting(ViewerState& s, const std::string& key, const std::string& value) {
    if (const SettingInfo* info = find_setting(key)) return set_setting(s, *info, value);
    if (const ParamInfo* info = find_param(key)) return set_param(s.ui.params, *info, value);
    for (const SetAction& action : kSetActions)
        if (action.key == key) return action.run(s, value);
    throw InputError("unknown setting '" + key + "'");
}

double relative_rms_change(const Image& a, const Image& b) {
    double diff = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        const glm::dvec3 d = glm::dvec3(a.pixels[i]) - glm::dvec3(b.pixels[i]);
        const glm::dvec3 v(b.pixels[i]);
        if (!std::isfinite(d.x + d.y + d.z + v.x + v.y + v.z)) continue;
        diff += d.x * d.x + d.y * d.y + d.z * d.z;
        norm += v.x * v.x + v.y * v.y + v.z * v.z;
    }
    return norm > 0.0 ? std::sqrt(diff / norm) : 0.0;
}

std::vector<float> explorer_tint(const Analysis& a, std::int32_t node, std::int32_t hits_up_to) {
    std::vector<float> tint(std::size_t(a.width) * std::size_t(a.height), 0.0f);
    if (!a.detail) return tint;
    const TraceDetail& d = *a.detail;
    if (hits_up_to >= 0)
        for (std::size_t r = 0; r < d.hit_node.size(); ++r)
            if (d.hit_node[r] >= 0 && d.hit_node[r] <= hits_up_to) tint[a.pixel_of(r)] = 2.0f;
    if (node >= 0 && std::size_t(node) < d.nodes.size() &&
        d.nodes[std::size_t(node)].ray_ids >= 0) {
        const NodeRecord& n = d.nodes[std::size_t(node)];
        for (std::uint32_t i = 0; i < n.rays; ++i)
            tint[a.pixel_of(d.node_ray_ids[std::size_t(n.ray_ids) + i])] = 1.0f;
    }
    return tint;
}

Integrator default_integrator(const Scene& scene) {
    for (const std::uint32_t m : scene.triangle_materials)
        if (m < scene.materials.size() && scene.materials[m].emissive()) return Integrator::path;
    return Integrator::ao;
}

int advance_step(int step, int last, float rate, double dt, double& carry, bool& playing) {
    if (!playing) return step;
    carry += double(rate) * std::max(dt, 0.0);
    const double whole = std::floor(carry);
    carry -= whole;
    const double next = double(step) + whole;
    if (next >= double(last)) {
        playing = false;
        carry = 0.0;
        return last;
    }
    return int(next);
}

float step_font_scale(float scale, int steps) {
    return std::clamp(scale * std::pow(kFontScaleStep, float(steps)), kMinFontScale, kMaxFontScale);
}

bool analysis_stale(const Analysis& a, const RenderRequest& r, BatchId batch) {
    // The camera rays depend on the view, size and seed alone; later batches on every setting
    // of the pass.
    const bool camera = batch == BatchId{};
    return a.scene != r.scene || !(a.camera == r.camera) || a.width != r.settings.width ||
           a.height != r.settings.height || a.seed != r.settings.seed || a.method != r.method ||
           !(a.params == r.params) || !(a.batch == batch) ||
           (!camera && !(a.settings == r.settings));
}

std::array<int, 4> region_pixels(const ImageRegion& r, int width, int height) {
    if (r.empty()) {
        const int w = std::min(64, width), h = std::min(64, height);
        return {(width - w) / 2, (height - h) / 2, w, h};
    }
    // Pixel x's centre x + 0.5 lies in [u0 W, u1 W): x from ceil(u0 W - 0.5).
    const auto first = [](float f, int n) {
        return std::clamp(int(std::ceil(f * float(n) - 0.5f)), 0, n - 1);
    };
    const int x0 = first(r.u0, width), y0 = first(r.v0, height);
    const int x1 = std::max(x0 + 1, std::min(width, first(r.u1, width) + (r.u1 >= 1.0f)));
    const int y1 = std::max(y0 + 1, std::min(height, first(r.v1, height) + (r.v1 >= 1.0f)));
    return {x0, y0, x1 - x0, y1 - y0};
}

ImageRegion parse_region(const std::string& text) {
    if (text == "centre" || text == "center") return {};
    ImageRegion r;
    float* f[] = {&r.u0, &r.v0, &r.u1, &r.v1};
    std::size_t at = 0;
    for (int i = 0; i < 4; ++i) {
        const std::size_t end = i < 3 ? text.find(',', at) : text.size();
        const std::string part = end == std::string::npos ? "" : text.substr(at, end - at);
        try {
            std::size_t used = 0;
            *f[i] = std::stof(part, &used);
            if (used != part.size() || !std::isfinite(*f[i])) throw std::invalid_argument(part);
        } catch (const std::exception&) {
            throw InputError("region: '" + text +
                             "' is not U0,V0,U1,V1 (fractions of the image) or centre");
        }
        at = end + 1;
    }
    if (!(0.0f <= r.u0 && r.u0 < r.u1 && r.u1 <= 1.0f && 0.0f <= r.v0 && r.v0 < r.v1 &&
          r.v1 <= 1.0f))
        throw InputError("region: '" + text + "' needs 0 <= U0 < U1 <= 1 and 0 <= V0 < V1 <= 1");
    return r;
}

std::string region_text(const ImageRegion& r) {
    if (r.empty()) return "centre";
    char text[64];
    std::snprintf(text, sizeof text, "%.4g,%.4g,%.4g,%.4g", r.u0, r.v0, r.u1, r.v1);
    return text;
}

std::vector<RayStats> per_pixel_stats(std::span<const RayStats> rays,
                                      std::span<const std::uint32_t> pixels, int width,
                                      int height) {
    std::vector<RayStats> out(std::size_t(width) * std::size_t(height));
    for (std::size_t i = 0; i < rays.size() && i < pixels.size(); ++i) {
        if (pixels[i] >= out.size()) continue;
        RayStats& p = out[pixels[i]];
        p.ray_box_tests += rays[i].ray_box_tests;
        p.ray_triangle_tests += rays[i].ray_triangle_tests;
        p.deepest_level = std::max(p.deepest_level, rays[i].deepest_level);
        p.order_misses =
            std::uint16_t(std::min(65535u, unsigned(p.order_misses) + rays[i].order_misses));
    }
    return out;
}

HeatImage heat_image(const ViewerState& s) {
    HeatImage h;
    const Analysis* a = s.analysis.get();
    if (s.view == View::render) return h;
    if (s.heat_of != HeatOf::a && a && a->against_detail && !s.analysis_stale) {
        h.pixels = a->against_pixel_stats;
        if (s.heat_of == HeatOf::difference) h.minus = a->pixel_stats;
        h.width = a->width;
        h.height = a->height;
        h.source = s.analysis;
        return h;
    }
    const ShownBatch batch = shown_batch(s);
    if (!batch.detail) return h;
    h.pixels = batch.pixels;
    h.width = batch.width;
    h.height = batch.height;
    h.source = batch.source;
    return h;
}

std::vector<float> HeatImage::values(View view) const {
    std::vector<float> out = heat_values(pixels, view);
    if (difference()) {
        const std::vector<float> a = heat_values(minus, view);
        for (std::size_t i = 0; i < out.size() && i < a.size(); ++i) out[i] -= a[i];
    }
    return out;
}

ShownBatch shown_batch(const ViewerState& s) {
    ShownBatch b;
    if (s.batch == BatchId{}) {
        if (!s.frame || !s.frame->detail) return b;
        b.detail = s.frame->detail.get();
        b.source = s.frame->detail;
        b.pixels = b.detail->rays;
        b.width = s.frame->image.width;
        b.height = s.frame->image.height;
    } else {
        const Analysis* a = s.analysis.get();
        if (!a || !a->detail || s.analysis_stale || !(a->batch == s.batch)) return b;
        b.detail = a->detail.get();
        b.source = s.analysis;
        b.pixels = a->pixel_stats;
        b.width = a->width;
        b.height = a->height;
    }
    b.rays = b.detail->rays.size();
    return b;
}

}  // namespace edacrt::app
