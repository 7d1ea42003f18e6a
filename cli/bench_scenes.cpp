#include "bench_scenes.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "trace/tracer.h"
#include "util/error.h"

namespace edacrt::cli {
namespace {

struct KnownScene {
    const char* name;
    bool bundled;  // in assets/, else in the scenes directory
    const char* file;
};

constexpr KnownScene kKnownScenes[] = {
    {"bunny", false, "bunny/stanford-bunny.obj"},
    {"dragon", false, "dragon/dragon_vrip_res3.obj"},
    {"buddha", false, "buddha/buddha.obj"},
    {"suzanne", false, "suzanne/suzanne.obj"},
    {"sponza", false, "sponza/sponza.obj"},
    {"sibenik", false, "sibenik/sibenik.obj"},
    {"conference", false, "conference/conference.obj"},
    {"cornell", true, "cornell-box/CornellBox-Original.obj"},
    {"spot", true, "spot/spot.obj"},
    {"teapot", true, "teapot/teapot.obj"},
};

constexpr const char* kInteriors[] = {"sponza", "sibenik", "conference"};

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return text;
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

std::vector<std::string> default_bench_scene_names() {
    return {"bunny", "sponza", "sibenik", "conference", "cornell", "spot", "teapot"};
}

std::vector<BenchScene> resolve_bench_scenes(const std::vector<std::string>& names,
                                             const std::filesystem::path& scenes_dir,
                                             bool scenes_dir_required) {
    std::vector<BenchScene> scenes;
    std::error_code ec;
    for (const std::string& name : names) {
        const auto known = std::find_if(std::begin(kKnownScenes), std::end(kKnownScenes),
                                        [&](const KnownScene& k) { return lower(name) == k.name; });
        if (known == std::end(kKnownScenes)) {
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
        const std::filesystem::path dir =
            known->bundled ? std::filesystem::path(EDACRT_SOURCE_DIR) / "assets" : scenes_dir;
        if (!known->bundled && !std::filesystem::is_directory(dir, ec)) {
            if (scenes_dir_required)
                throw InputError("scenes directory " + dir.string() + " not found (needed for " +
                                 name + "; set --scenes or $EDACRT_SCENES)");
            std::cerr << "bench: skipping " << name << ": scenes directory " << dir.string()
                      << " not found\n";
            continue;
        }
        const std::filesystem::path path = dir / known->file;
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
    const bool known_interior = std::find(std::begin(kInteriors), std::end(kInteriors),
                                          lower(name)) != std::end(kInteriors);
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
        view.reason = "object, framed from +z (" + measured + ")";
        view.camera = frame_box(box);
    }
    validate(view.camera);
    return view;
}

}  // namespace edacrt::cli
