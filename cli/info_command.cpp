// edacrt info: what a scene is before rendering it: size, materials, emitters, bounds, the
// camera a render would use, the memory it would need, and what will not be rendered.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "camera_flags.h"
#include "commands.h"
#include "common_options.h"
#include "enum_flags.h"
#include "render/default_camera.h"
#include "render/image_format.h"
#include "render/render_memory.h"
#include "render/scene_summary.h"
#include "scene/text_scan.h"
#include "trace/stats_json.h"
#include "trace/tracer.h"
#include "util/error.h"
#include "util/printable.h"

namespace edacrt::cli {
namespace {

struct InfoOptions {
    std::string scene;
    bool json = false;
    RenderSettings settings;
    int spp = 16;
    CameraOptions camera;
    InfoOptions() { settings.samples_per_pass = 0; }
};

nlohmann::json vec(glm::vec3 v) { return {v.x, v.y, v.z}; }

std::string format_bytes(std::uint64_t bytes) {
    char text[32];
    if (bytes < 1'000'000)
        std::snprintf(text, sizeof text, "%.0f kB", double(bytes) * 1e-3);
    else if (bytes < 1'000'000'000)
        std::snprintf(text, sizeof text, "%.1f MB", double(bytes) * 1e-6);
    else
        std::snprintf(text, sizeof text, "%.2f GB", double(bytes) * 1e-9);
    return text;
}

/// Everything reported, as JSON; the text form is printed from it.
nlohmann::json describe(const InfoOptions& o, const RenderSettings& settings, const Scene& scene) {
    const SceneSummary s = summarize_scene(scene);
    nlohmann::json materials = nlohmann::json::array();
    for (const MaterialSummary& m : s.materials) {
        nlohmann::json textures = nlohmann::json::array();
        for (std::size_t k = 0; k < m.textures.size(); ++k)
            textures.push_back({{"keyword", m.textures[k].keyword},
                                {"file", m.textures[k].file},
                                {"rendered", k == m.rendered_texture}});
        materials.push_back({{"name", m.name},
                             {"triangles", m.triangles},
                             {"model", m.model},
                             {"emissive", m.emissive},
                             {"textures", textures}});
    }
    const Camera camera = choose_camera(scene, o.camera);
    const std::string from = o.camera.given()     ? "the camera options"
                             : scene.camera       ? "the scene"
                             : is_interior(scene) ? "inside the interior, above the floor"
                                                  : std::string("framing the bounds from ") +
                                                        framing_side(scene.bounds());

    // The renderer's state with a PNG written at the end, as `edacrt render` estimates it.
    const std::uint64_t renderer = render_memory_bytes(
        settings, sizeof(glm::vec3) + save_image_bytes_per_pixel(ImageFormat::png));
    nlohmann::json scene_bytes = nlohmann::json::object();
    nlohmann::json cannot_trace = nlohmann::json::object();
    for (const EnumEntry<Method>& method : kMethods) {
        const auto tracer = make_tracer(method.value);
        // info traces nothing: a method that refuses the scene (Embree past its range) is
        // something to report, not a reason to report nothing.
        try {
            tracer->set_scene(scene);
            scene_bytes[std::string(method.name)] = tracer->working_bytes();
        } catch (const InputError& e) {
            scene_bytes[std::string(method.name)] = nullptr;
            cannot_trace[std::string(method.name)] = e.what();
        }
    }
    return {{"scene", scene.source},
            {"triangles", s.triangles},
            {"degenerate_triangles", s.degenerate_triangles},
            {"vertices", s.vertices},
            {"shading_normals", s.shading_normals},
            {"materials", materials},
            {"emitters", {{"triangles", s.emissive_triangles}, {"area", s.emissive_area}}},
            {"bounds",
             {{"min", vec(s.bounds.lo)},
              {"max", vec(s.bounds.hi)},
              {"diagonal", glm::length(s.bounds.hi - s.bounds.lo)}}},
            {"camera",
             {{"from", from},
              {"eye", vec(camera.eye)},
              {"look_at", vec(camera.look_at)},
              {"up", vec(camera.up)},
              {"vfov_degrees", camera.vfov_degrees}}},
            {"memory",
             {{"width", settings.width},
              {"height", settings.height},
              {"integrator", enum_name(kIntegrators, settings.integrator)},
              {"spp", o.spp},
              {"samples_per_pass", settings.samples_per_pass},
              {"renderer_bytes", renderer},
              {"tracer_scene_bytes", scene_bytes},
              {"methods_that_cannot_trace", cannot_trace},
              {"limit_bytes", memory_limit().bytes},
              {"limit_source", memory_limit().source}}},
            {"warnings", s.warnings}};
}

void print_text(const nlohmann::json& j) {
    const auto v3 = [](const nlohmann::json& v) {
        char text[96];
        std::snprintf(text, sizeof text, "(%g, %g, %g)", v[0].get<double>(), v[1].get<double>(),
                      v[2].get<double>());
        return std::string(text);
    };
    // Names come from files: printed escaped (json_text replaces what is not UTF-8).
    const auto text = [](const nlohmann::json& name) { return printable(name.get<std::string>()); };
    std::cout << text(j["scene"]) << "\n"
              << "  triangles    " << j["triangles"] << " (" << j["degenerate_triangles"]
              << " degenerate: zero area, never hit)\n"
              << "  vertices     " << j["vertices"] << ", " << j["shading_normals"]
              << " shading normals\n"
              << "  bounds       " << v3(j["bounds"]["min"]) << " to " << v3(j["bounds"]["max"])
              << ", diagonal " << j["bounds"]["diagonal"].get<double>() << "\n"
              << "  emitters     " << j["emitters"]["triangles"] << " triangles, area "
              << j["emitters"]["area"].get<double>()
              << (j["emitters"]["triangles"] == 0 ? " (a render lights it with the sky)" : "")
              << "\n  materials    " << j["materials"].size() << "\n";
    for (const auto& m : j["materials"]) {
        std::cout << "    " << text(m["name"]) << ": " << m["triangles"] << " triangles, "
                  << m["model"].get<std::string>() << "\n";
        // The first few of a material's textures, as warnings are capped (scene/text_scan.h).
        const std::size_t shown = text_scan::WarningLimit::kWarningsPerKind;
        for (std::size_t i = 0; i < std::min(shown, m["textures"].size()); ++i)
            std::cout << "      " << text(m["textures"][i]["keyword"]) << " "
                      << text(m["textures"][i]["file"])
                      << (m["textures"][i]["rendered"].get<bool>() ? " (rendered)\n"
                                                                   : " (not rendered)\n");
        if (m["textures"].size() > shown)
            std::cout << "      ... and " << m["textures"].size() - shown << " more textures\n";
    }
    const auto& c = j["camera"];
    std::cout << "  camera       from " << c["from"].get<std::string>() << ": eye " << v3(c["eye"])
              << ", look at " << v3(c["look_at"]) << ", up " << v3(c["up"]) << ", vertical fov "
              << c["vfov_degrees"].get<double>() << " degrees\n";
    const auto& m = j["memory"];
    std::cout << "  memory       " << m["width"] << "x" << m["height"] << " "
              << m["integrator"].get<std::string>() << " render at " << m["spp"]
              << " spp in passes of " << m["samples_per_pass"] << ": "
              << format_bytes(m["renderer_bytes"]) << " for the renderer (film, samples, "
              << "wavefront, PNG output), of " << format_bytes(m["limit_bytes"]) << " ("
              << m["limit_source"].get<std::string>() << ")\n"
              << "               and the tracer's scene data:";
    for (const auto& [name, bytes] : m["tracer_scene_bytes"].items())
        std::cout << " " << name << " " << (bytes.is_null() ? "-" : format_bytes(bytes));
    std::cout << "\n";
    for (const auto& [name, why] : m["methods_that_cannot_trace"].items())
        std::cout << "  note         " << name << " cannot trace it: " << text(why) << "\n";
    std::cout << "  warnings     " << j["warnings"].size() << "\n";
    for (const auto& w : j["warnings"]) std::cout << "    " << text(w) << "\n";
}

void run(const InfoOptions& o) {
    RenderSettings settings = o.settings;
    check_flags([&] {
        settings.samples_per_pass = resolve_samples_per_pass(
            settings.samples_per_pass, settings.width, settings.height, o.spp);
        validate(settings);
    });
    const nlohmann::json info = describe(o, settings, load_scene(o.scene));
    if (o.json)
        std::cout << json_text(info);
    else
        print_text(info);
}

}  // namespace

std::function<void()> add_info_command(CLI::App& app) {
    auto options = std::make_shared<InfoOptions>();
    InfoOptions& o = *options;
    CLI::App* command = app.add_subcommand(
        "info",
        "Describe a scene without rendering it: triangles (degenerate ones counted), vertices, "
        "materials and what each models, emitters, bounds, the camera a render would use, the "
        "memory a render of the given size would need, and warnings (unmodelled MTL "
        "statements, missing textures).\nExample: edacrt info "
        "assets/cornell-box/CornellBox-Original.obj --width 1920 --height 1080 --json");
    command->add_option("scene", o.scene, "OBJ file or builtin:NAME")->required();
    command->add_flag("--json", o.json, "print JSON instead of text (for scripts)");
    flags::add_image_size_options(*command, o.settings.width, o.settings.height);
    flags::add_enum_option(*command, "--integrator", o.settings.integrator, kIntegrators,
                           "integrator");
    command->add_option("--spp", o.spp, "samples per pixel")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    command
        ->add_option("--samples-per-pass", o.settings.samples_per_pass,
                     "samples per pixel traced together in one pass (at most --spp); 0: about "
                     "1M paths per pass, at least 4 samples")
        ->capture_default_str();
    flags::add_camera_options(*command, o.camera);
    return [options] { run(*options); };
}

}  // namespace edacrt::cli
