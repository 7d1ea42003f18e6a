// The viewer's settings as the script and tests drive them: `set KEY VALUE`, and whether a
// recording still describes the render in progress.
#include <oneapi/tbb/info.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "render/film.h"
#include "util/error.h"
#include "viewer_jobs.h"
#include "viewer_state.h"

namespace edacrt::app {
namespace {

constexpr SettingRange kSettingRanges[] = {
    {"spp", 1, 1 << 20, 65536, true},
    {"threads", 0, 1024, 64, true},  // 0: all cores
    {"resolution", 0.125, 1, 1, false},
    {"seed", 0, std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max(),
     true},
    {"speed", 0.05, 4, 4, false},
};

std::string number_text(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", x);
    return text;
}

}  // namespace

const SettingRange& setting_range(std::string_view key) {
    for (const SettingRange& r : kSettingRanges)
        if (r.key == key) return r;
    throw std::invalid_argument("setting_range: no setting " + std::string(key));
}

double check_setting(std::string_view key, double value) {
    const SettingRange& r = setting_range(key);
    if (!(value >= r.min && value <= r.max) || (r.integer && value != std::floor(value)))
        throw InputError(std::string(key) + " must be " + (r.integer ? "a whole number " : "") +
                         "from " + number_text(r.min) + " to " + number_text(r.max) + ", got " +
                         number_text(value));
    return value;
}

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
    UiSettings& ui = s.ui;
    EdacrtParams& p = ui.params;
    const auto number = [&] {
        try {
            std::size_t used = 0;
            const double v = std::stod(value, &used);
            if (used != value.size() || !std::isfinite(v)) throw std::invalid_argument(value);
            return v;
        } catch (const std::exception&) {
            throw InputError("'" + key + "' needs a number, got '" + value + "'");
        }
    };
    if (key == "method")
        ui.method = parse_enum_or_throw(kMethods, value);
    else if (key == "embree-mode")
        ui.embree_mode = parse_enum_or_throw(kEmbreeModes, value);
    else if (key == "integrator")
        ui.integrator = parse_enum_or_throw(kIntegrators, value);
    else if (key == "primary")
        ui.primary = parse_enum_or_throw(kPrimaryShadings, value);
    else if (key == "spp" || key == "threads" || key == "resolution" || key == "seed") {
        const double v = check_setting(key, number());
        if (key == "spp") ui.spp_target = int(v);
        if (key == "threads") ui.threads = int(v);
        if (key == "resolution") ui.resolution_scale = float(v);
        if (key == "seed") ui.seed = int(v);
    } else if (key == "max-depth" || key == "ao-samples") {
        // Checked as the renderer checks them, now rather than when the render starts.
        const double v = number();
        RenderSettings settings;
        int& field = key == "max-depth" ? settings.max_depth : settings.ao_samples;
        field = v == std::floor(v) && std::abs(v) < 1e9 ? int(v) : -1;
        validate(settings);
        (key == "max-depth" ? ui.max_depth : ui.ao_samples) = field;
    } else if (key == "pause")
        ui.paused = number() != 0;
    else if (key == "preset")
        p = preset_params(value);
    else if (const ParamInfo* info = find_param(key))
        set_param(p, *info, value);
    else if (key == "exposure") {
        const auto exposure = float(number());
        validate_exposure(exposure);
        s.exposure = exposure;
    } else if (key == "scene")
        s.pending_loads.push_back(value);
    else if (key == "compare-spp") {
        const double v = number();
        if (std::find(std::begin(kCompareSpp), std::end(kCompareSpp), v) == std::end(kCompareSpp))
            throw InputError("'compare-spp' is 1, 4 or 16, got '" + value + "'");
        s.compare_spp = int(v);
    } else if (key == "level")
        s.explorer_level = int(number());
    else if (key == "node")
        s.explorer_node = std::int32_t(number());
    else if (key == "crop")
        s.explorer_crop = number() != 0;
    else if (key == "step") {
        s.stepping = true;
        s.step = int(number());
    } else if (key == "animate") {
        load_into(s, s.scene_path, {}, value, true);
        if (!s.scene_error.empty()) throw InputError(s.scene_error);
    } else if (key == "time" || key == "play" || key == "speed" || key == "loop" ||
               key == "update" || key == "shutter" || key == "play-scale") {
        Playback& a = s.playback;
        if (!a.frames) throw InputError("'" + key + "' needs an animated scene");
        if (key == "time") {
            a.playing = false;
            seek(s, number());
            if (!a.error.empty()) throw InputError(a.error);
        } else if (key == "play") {
            a.playing = number() != 0;
            a.waited = 0.0;
        } else if (key == "speed") {
            a.speed = float(check_setting(key, number()));
        } else if (key == "play-scale") {
            const double scale = number();
            if (scale != 1 && scale != 2 && scale != 4) throw InputError("play-scale is 1, 2 or 4");
            a.play_scale = int(scale);
        } else if (key == "loop") {
            a.loop = number() != 0;
        } else if (key == "update") {
            a.update = parse_enum_or_throw(kSceneUpdates, value);
        } else {  // shutter: seconds of motion blur, 0 for none
            const double shutter = number();
            if (!(shutter >= 0.0 && shutter <= 1e3))
                throw InputError("shutter must be from 0 to 1000 seconds");
            a.motion_blur = shutter > 0.0;
            if (shutter > 0.0) a.shutter = float(shutter);
        }
    } else
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

bool analysis_stale(const Analysis& a, const RenderRequest& r) {
    return a.scene != r.scene || !(a.camera == r.camera) || a.width != r.settings.width ||
           a.height != r.settings.height || a.seed != r.settings.seed || a.method != r.method ||
           !(a.params == r.params);
}

}  // namespace edacrt::app
