// edacrt_paper_rays: the ray sets of the EDACRT paper's experiment (Nabata et al., HPG 2013),
// written as ray files for `edacrt trace`:
//   camera_1spp, camera_4spp, camera_16spp  jittered camera rays, all samples of a pixel together
//   diffuse     one cosine-distributed ray from every hit of the 1-spp camera rays
//   reflection  the mirror ray from every such hit
//   path        bounces 2 and 3 of diffuse path tracing from those hits (diffuse = bounce 1)
// Random numbers are counter-based (render/benchmark_rays.h): a ray depends only on --seed,
// its pixel, its sample and its bounce; `edacrt bench` makes the same camera and diffuse rays.
// Secondary rays are made from bvh hits.
//   build/edacrt_paper_rays --scene ../shared/scenes/sponza/sponza.obj --out-dir out/paper/sponza
#include <CLI/CLI.hpp>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <glm/geometric.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "render/benchmark_rays.h"
#include "render/bsdf.h"
#include "render/shading_scene.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/ray_file.h"
#include "trace/tracer.h"
#include "util/error.h"

namespace edacrt {
namespace {

struct Options {
    std::string scene;
    int width = 512;
    int height = 512;
    std::filesystem::path out_dir;
    std::uint32_t seed = 1;
    std::vector<float> eye, look_at;
    float fov = 0.0f;  // 0: the scene's or frame_box's
};

Camera choose_camera(const Scene& scene, const Options& o) {
    Camera camera = scene.camera.value_or(frame_box(scene.bounds()));
    if (!o.eye.empty()) camera.eye = {o.eye[0], o.eye[1], o.eye[2]};
    if (!o.look_at.empty()) camera.look_at = {o.look_at[0], o.look_at[1], o.look_at[2]};
    if (o.fov > 0.0f) camera.vfov_degrees = o.fov;
    validate(camera);
    return camera;
}

std::vector<Hit> trace(Tracer& tracer, const std::vector<Ray>& rays) {
    std::vector<Hit> hits(rays.size());
    tracer.trace(rays, hits, Query::closest);
    return hits;
}

/// A cosine-distributed ray about the geometric normal (on the ray's side) from every hit of
/// `rays`; `keys[i]` names the path of rays[i], `bounce` the bounce the new rays make.
void diffuse_bounce(const Scene& scene, const std::vector<Ray>& rays, const std::vector<Hit>& hits,
                    std::vector<std::uint32_t>& keys, std::uint32_t seed, std::uint32_t bounce,
                    std::vector<Ray>& out) {
    std::vector<std::uint32_t> out_keys;
    out.clear();
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!hits[i].hit()) continue;
        const Surface s = make_surface(scene, rays[i], hits[i]);
        const glm::vec2 u = random_2d(sample_key(seed, kBounceStream, keys[i], bounce));
        out.push_back(spawn_ray(s, sample_cosine_hemisphere(s.ng, u)));
        out_keys.push_back(keys[i]);
    }
    keys = std::move(out_keys);
}

/// The mirror ray from every hit: reflected about the shading normal, or about the geometric
/// normal when that would leave below the surface (both are on the incoming ray's side).
std::vector<Ray> reflection_rays(const Scene& scene, const std::vector<Ray>& rays,
                                 const std::vector<Hit>& hits) {
    std::vector<Ray> out;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!hits[i].hit()) continue;
        const Surface s = make_surface(scene, rays[i], hits[i]);
        const glm::vec3 d = glm::normalize(rays[i].dir);
        glm::vec3 r = glm::reflect(d, s.ns);
        if (!(glm::dot(r, s.ng) > 0.0f)) r = glm::reflect(d, s.ng);
        out.push_back(spawn_ray(s, glm::normalize(r)));
    }
    return out;
}

void write(const Options& o, const std::string& name, const std::vector<Ray>& rays) {
    const std::filesystem::path path = o.out_dir / (name + ".rays");
    write_rays(path, rays);
    std::cout << name << " " << rays.size() << " " << path.string() << "\n";
}

void run(const Options& o) {
    const Scene scene = load_scene(o.scene);
    if (scene.triangle_count() == 0) throw InputError(o.scene + ": the scene has no triangles");
    std::error_code ec;
    std::filesystem::create_directories(o.out_dir, ec);
    if (ec || !std::filesystem::is_directory(o.out_dir))
        throw InputError(o.out_dir.string() + ": cannot create the output directory" +
                         (ec ? " (" + ec.message() + ")" : std::string()));
    const PinholeProjection projection(choose_camera(scene, o), o.width, o.height);

    const std::vector<Ray> camera = jittered_camera_rays(projection, o.width, o.height, 1, o.seed);
    write(o, "camera_1spp", camera);
    for (int spp : {4, 16})
        write(o, "camera_" + std::to_string(spp) + "spp",
              jittered_camera_rays(projection, o.width, o.height, spp, o.seed));

    const auto tracer = make_tracer(Method::bvh);
    tracer->set_scene(scene);
    const std::vector<Hit> camera_hits = trace(*tracer, camera);
    write(o, "reflection", reflection_rays(scene, camera, camera_hits));

    std::vector<std::uint32_t> keys(camera.size());
    for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = std::uint32_t(i);
    std::vector<Ray> bounce1, bounce2, bounce3;
    diffuse_bounce(scene, camera, camera_hits, keys, o.seed, 1, bounce1);
    write(o, "diffuse", bounce1);
    diffuse_bounce(scene, bounce1, trace(*tracer, bounce1), keys, o.seed, 2, bounce2);
    diffuse_bounce(scene, bounce2, trace(*tracer, bounce2), keys, o.seed, 3, bounce3);
    std::vector<Ray> path = std::move(bounce2);
    path.insert(path.end(), bounce3.begin(), bounce3.end());
    write(o, "path", path);
}

}  // namespace
}  // namespace edacrt

int main(int argc, char** argv) {
    edacrt::Options o;
    CLI::App app{
        "Writes the ray sets of the EDACRT paper's experiment (camera rays at 1, 4, 16 spp; "
        "diffuse, reflection and path rays from the 1-spp hits) for 'edacrt trace'.\n"
        "Prints one line per file: name, ray count, path.",
        "edacrt_paper_rays"};
    app.add_option("--scene", o.scene, "OBJ file or builtin:NAME")->required();
    app.add_option("--width", o.width, "pixels per row")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    app.add_option("--height", o.height, "rows")
        ->check(CLI::Range(1, 16384))
        ->capture_default_str();
    app.add_option("--out-dir", o.out_dir, "directory for the ray files (created)")->required();
    app.add_option("--seed", o.seed, "seed of the jitter and the bounces")->capture_default_str();
    app.add_option("--eye", o.eye, "camera position X,Y,Z (default: the scene's, else framing)")
        ->expected(3)
        ->delimiter(',');
    app.add_option("--look-at", o.look_at, "point the camera looks at X,Y,Z")
        ->expected(3)
        ->delimiter(',');
    app.add_option("--fov", o.fov, "vertical field of view in degrees");
    CLI11_PARSE(app, argc, argv);
    try {
        edacrt::run(o);
    } catch (const edacrt::InputError& e) {
        std::cerr << "edacrt_paper_rays: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "edacrt_paper_rays: error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
