#include "bench_scenes.h"

#include <cmath>
#include <iostream>

#include "scene/scene_manifest.h"
#include "trace/tracer.h"
#include "util/error.h"

namespace edacrt::cli {
namespace {

const SceneManifest& manifest() {
    static const SceneManifest manifest =
        read_scene_manifest(scene_manifest_path(EDACRT_SOURCE_DIR));
    return manifest;
}

/// The manifest's scene called `name`, or null; builtin:... specs need no manifest.
const ManifestScene* known_scene(const std::string& name) {
    return name.starts_with("builtin:") ? nullptr : manifest().find(name);
}

/// Fractions of `count` rays from `eye` in all directions (a Fibonacci sphere) that hit
/// anything, and of those that see a triangle's front (counter-clockwise) side.
std::pair<double, double> enclosure(const Scene& scene, Tracer& tracer, glm::vec3 eye) {
    constexpr int kCount = 256;
    std::vector<Ray> rays;
    for (int i = 0; i < kCount; ++i) {
        const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(kCount);
        const float r = std::sqrt(1.0f - z * z), phi = 2.3999632f * float(i);  // golden angle
        rays.push_back({eye, {r * std::cos(phi), z, r * std::sin(phi)}});
    }
    std::vector<Hit> hits(rays.size());
    tracer.trace(rays, hits, Query::closest);
    int hit = 0, front = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!hits[i].hit()) continue;
        ++hit;
        front += glm::dot(unit_normal(scene.corners(std::size_t(hits[i].prim))), rays[i].dir) < 0;
    }
    return {double(hit) / kCount, hit ? double(front) / hit : 0.0};
}

std::string percent(double fraction) { return std::to_string(int(std::lround(100 * fraction))); }

}  // namespace

std::vector<std::string> bench_scene_list(const std::string& list) { return manifest().list(list); }

std::string bench_scene_list_text(const std::string& list) {
    try {
        std::string text;
        for (const std::string& name : manifest().list(list))
            text += (text.empty() ? "" : ", ") + name;
        return text;
    } catch (const InputError&) {  // reported when a scene is looked up
        return "the list " + list + " of assets/scenes.json";
    }
}

std::string bench_scene_help() {
    std::string names = "a name";
    try {
        names = manifest().names();
    } catch (const InputError&) {
    }
    return "a scene to measure (repeatable): " + names + " (assets/scenes.json), an OBJ path " +
           "or builtin:... (default: " + bench_scene_list_text("bench") +
           "; absent ones are skipped)";
}

std::vector<BenchScene> resolve_bench_scenes(const std::vector<std::string>& names,
                                             const std::filesystem::path& scenes_dir,
                                             bool scenes_dir_required) {
    const std::filesystem::path assets = std::filesystem::path(EDACRT_SOURCE_DIR) / "assets";
    std::vector<BenchScene> scenes;
    std::error_code ec;
    for (const std::string& name : names) {
        const ManifestScene* known = known_scene(name);
        if (!known) {
            if (name.starts_with("builtin:")) {
                scenes.push_back({name, name});
                continue;
            }
            if (!std::filesystem::is_regular_file(name, ec))
                throw InputError("--scene " + name +
                                 ": neither a known scene name nor an existing OBJ file");
            scenes.push_back({std::filesystem::path(name).stem().string(), name});
            continue;
        }
        const bool bundled = is_bundled(*known, assets);
        if (!bundled && !std::filesystem::is_directory(scenes_dir, ec)) {
            if (scenes_dir_required)
                throw InputError("scenes directory " + scenes_dir.string() +
                                 " not found (needed for " + name +
                                 "; set --scenes or $EDACRT_SCENES)");
            std::cerr << "bench: skipping " << name << ": scenes directory " << scenes_dir.string()
                      << " not found\n";
            continue;
        }
        const std::filesystem::path path = scene_file(*known, assets, scenes_dir);
        if (!std::filesystem::is_regular_file(path, ec)) {
            std::cerr << "bench: skipping " << name << ": " << path.string() << " not found\n";
            continue;
        }
        scenes.push_back({known->name, path.string()});
    }
    return scenes;
}

BenchView bench_view(const Scene& scene, const std::string& name) {
    const Aabb box = scene.bounds();
    const glm::vec3 centre = 0.5f * (box.lo + box.hi), extent = box.hi - box.lo;
    const auto tracer = make_tracer(Method::bvh);
    tracer->set_scene(scene);

    // The interior eye: above the first surface under the box centre.
    Hit floor;
    const Ray down{centre, {0.0f, -1.0f, 0.0f}};
    tracer->trace({&down, 1}, {&floor, 1}, Query::closest);
    const float floor_y = floor.hit() ? centre.y - floor.t : box.lo.y;
    const glm::vec3 eye{centre.x, floor_y + (box.hi.y - floor_y) / 6.0f, centre.z};

    BenchView view;
    const ManifestScene* known = known_scene(name);
    const bool known_interior = known && known->interior;
    const auto [hit, front] = enclosure(scene, *tracer, eye);
    const std::string measured =
        percent(hit) + "% of rays from inside hit, " + percent(front) + "% of those front faces";
    if (known_interior || (hit >= 0.95 && front >= 2.0 / 3.0)) {
        view.inside = true;
        view.reason = (known_interior ? "known interior (" : "enclosed (") + measured + ")";
        const glm::vec3 axis = extent.x >= extent.z ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
        view.camera = {eye, eye + axis * glm::length(extent), {0, 1, 0}, 60.0f};
    } else if (scene.camera) {
        view.reason = "object, the scene's camera (" + measured + ")";
        view.camera = *scene.camera;
    } else {
        view.reason =
            std::string("object, framed from ") + framing_side(box) + " (" + measured + ")";
        view.camera = frame_box(box);
    }
    validate(view.camera);
    return view;
}

}  // namespace edacrt::cli
