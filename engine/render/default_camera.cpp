#include "render/default_camera.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <memory>
#include <numbers>
#include <vector>

#include "trace/tracer.h"

namespace edacrt {
namespace {

/// Rays from `origin` around the up axis: kAzimuths per ring, rings at -20, 0 and 20 degrees.
std::vector<Ray> horizontal_probes(const glm::vec3& origin) {
    constexpr int kAzimuths = 32;
    std::vector<Ray> rays;
    for (float elevation : {-0.35f, 0.0f, 0.35f})
        for (int i = 0; i < kAzimuths; ++i) {
            const float phi = 2.0f * std::numbers::pi_v<float> * (float(i) + 0.5f) / kAzimuths;
            Ray ray;
            ray.org = origin;
            ray.dir = {std::cos(elevation) * std::cos(phi), std::sin(elevation),
                       std::cos(elevation) * std::sin(phi)};
            rays.push_back(ray);
        }
    return rays;
}

/// By EDACRT: the naive tracer's 98 rays against every triangle took 0.4 s on Conference
/// before a render or the viewer's first frame; the recursion takes milliseconds.
std::vector<Hit> closest_hits(const Scene& scene, const std::vector<Ray>& rays) {
    const std::unique_ptr<Tracer> tracer = make_tracer(Method::edacrt);
    tracer->set_scene(scene);
    std::vector<Hit> hits(rays.size());
    tracer->trace(rays, hits, Query::closest);
    return hits;
}

/// Of the rays, the share that hit a surface facing the ray's origin.
double facing_share(const Scene& scene, const std::vector<Ray>& rays) {
    const std::vector<Hit> hits = closest_hits(scene, rays);
    std::size_t facing = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
        if (hits[i].hit()) {
            const Triangle tri = scene.corners(std::size_t(hits[i].prim));
            // The geometric normal's side: both windings occur, so only a clear majority of
            // front faces marks an inside.
            const glm::vec3 n = glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
            facing += glm::dot(n, rays[i].dir) < 0.0f;
        }
    return double(facing) / double(rays.size());
}

}  // namespace

bool is_interior(const Scene& scene) {
    if (scene.triangle_count() == 0) return false;
    return facing_share(scene, horizontal_probes(scene.bounds().center())) >= 0.8;
}

Camera default_camera(const Scene& scene) {
    if (scene.camera) return *scene.camera;
    const Aabb box = scene.bounds();
    if (!is_interior(scene)) return frame_box(box);
    // The floor and ceiling above and below the centre (the box's faces where nothing is hit:
    // an atrium open to the sky).
    const glm::vec3 centre = box.center();
    Ray down, up;
    down.org = up.org = centre;
    down.dir = {0.0f, -1.0f, 0.0f};
    up.dir = {0.0f, 1.0f, 0.0f};
    const std::vector<Hit> hits = closest_hits(scene, {down, up});
    const float floor = hits[0].hit() ? centre.y - hits[0].t : box.lo.y;
    const float ceiling = hits[1].hit() ? centre.y + hits[1].t : box.hi.y;
    Camera camera;
    camera.vfov_degrees = 60.0f;
    camera.eye = {centre.x, floor + 0.2f * (ceiling - floor), centre.z};
    const glm::vec3 extent = box.extent();
    camera.look_at = camera.eye + (extent.x >= extent.z ? glm::vec3(0.5f * extent.x, 0.0f, 0.0f)
                                                        : glm::vec3(0.0f, 0.0f, 0.5f * extent.z));
    return camera;
}

}  // namespace edacrt
