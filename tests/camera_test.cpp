#include "scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <iostream>

#include "render/camera_options.h"
#include "render/default_camera.h"
#include "scene/builtin_scenes.h"
#include "test_paths.h"
#include "util/error.h"

namespace edacrt {
namespace {

TEST(Camera, CentreRayLooksAtTarget) {
    const Camera camera{{0, 1, 5}, {0, 1, 0}, {0, 1, 0}, 40.0f};
    const PinholeProjection projection(camera, 64, 32);
    const Ray ray = projection.ray(32.0f, 16.0f);
    EXPECT_EQ(ray.org, camera.eye);
    EXPECT_NEAR(ray.dir.x, 0.0f, 1e-6f);
    EXPECT_NEAR(ray.dir.y, 0.0f, 1e-6f);
    EXPECT_NEAR(ray.dir.z, -1.0f, 1e-6f);
}

TEST(Camera, CornersSpanTheFieldOfView) {
    const Camera camera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0f};
    const PinholeProjection projection(camera, 200, 100);  // aspect 2: half-width tan = 2
    const Ray top_left = projection.ray(0.0f, 0.0f);
    EXPECT_NEAR(top_left.dir.y / -top_left.dir.z, 1.0f, 1e-5f);   // top edge at 45 degrees
    EXPECT_NEAR(top_left.dir.x / -top_left.dir.z, -2.0f, 1e-5f);  // left is -x
    EXPECT_NEAR(glm::length(top_left.dir), 1.0f, 1e-6f);
}

TEST(Camera, ABoxClearlyDeeperThanWideIsFramedFromTheSide) {
    EXPECT_STREQ(framing_side(Aabb{{-1, 0, -1}, {1, 2, 1}}), "+z");
    EXPECT_STREQ(framing_side(Aabb{{-1, 0, -1.2f}, {1, 2, 1.2f}}), "+z");  // a little deeper
    EXPECT_STREQ(framing_side(Aabb{{-0.47f, 0, -0.67f}, {0.47f, 1, 1.05f}}), "+x");  // Spot's
    const Aabb deep{{-1, 0, -3}, {1, 2, 3}};
    const Camera camera = frame_box(deep, 45.0f);
    EXPECT_GT(camera.eye.x, deep.hi.x);
    EXPECT_EQ(camera.eye.z, deep.center().z);
    EXPECT_EQ(camera.look_at, deep.center());
}

TEST(Camera, FrameBoxSeesTheWholeBox) {
    const Aabb box{{-1, 0, -1}, {1, 2, 1}};
    const Camera camera = frame_box(box, 45.0f);
    EXPECT_GT(camera.eye.z, box.hi.z);
    EXPECT_EQ(camera.look_at, box.center());
    // Every corner of the box lies within the half field of view around the view axis.
    const glm::vec3 axis = glm::normalize(camera.look_at - camera.eye);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner(i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y,
                               i & 4 ? box.hi.z : box.lo.z);
        const float cosine = glm::dot(axis, glm::normalize(corner - camera.eye));
        EXPECT_GE(cosine, std::cos(glm::radians(22.5f)) - 1e-6f);
    }
}

TEST(Camera, InvalidCamerasAreRejected) {
    EXPECT_THROW(validate(Camera{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 45}), InputError);
    EXPECT_THROW(validate(Camera{{0, 0, 1}, {0, 0, 0}, {0, 0, 1}, 45}), InputError);
    EXPECT_THROW(validate(Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 0}), InputError);
    EXPECT_THROW(validate(Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 180}), InputError);
    EXPECT_THROW(validate(Camera{{NAN, 0, 1}, {0, 0, 0}, {0, 1, 0}, 45}), InputError);
    EXPECT_NO_THROW(validate(Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 45}));
}

// Finite inputs whose arithmetic overflows or underflows: eye - look_at past the float range, a
// view longer than 1.8e19 (its squared length overflows), a view of 1e-30 (its squared length
// underflows), a huge up vector. Each is refused, or gives a finite orthonormal frame.
TEST(Camera, ViewsWhoseArithmeticOverflowsAreRejectedOrFinite) {
    const Camera overflows[] = {
        {{3e38f, 0, 0}, {-3e38f, 0, 0}, {0, 1, 0}, 45},
        {{0, 0, 3e38f}, {0, 0, -3e38f}, {0, 1, 0}, 45},
        {{1e20f, 0, 0}, {-1e20f, 0, 0}, {0, 1, 0}, 45},
        {{0, 0, 1e-30f}, {0, 0, 0}, {0, 1, 0}, 45},
        {{0, 0, 0}, {1e-44f, 0, 0}, {0, 1, 0}, 45},
    };
    for (const Camera& camera : overflows) {
        EXPECT_THROW(validate(camera), InputError) << camera.eye.x << " " << camera.eye.z;
        EXPECT_THROW(PinholeProjection(camera, 8, 8), InputError);
    }
    const Camera accepted[] = {
        {{0, 0, 5}, {0, 0, 0}, {0, 1e30f, 0}, 45},
        {{0, 0, 5}, {0, 0, 0}, {1e-30f, 3e38f, 0}, 45},
        {{1e18f, 0, 0}, {-1e18f, 0, 0}, {0, 1, 0}, 179.9f},
        {{0, 0, 1e-3f}, {0, 0, 0}, {0, 1e-38f, 0}, 1e-3f},
    };
    for (const Camera& camera : accepted) {
        ASSERT_NO_THROW(validate(camera));
        const PinholeProjection projection(camera, 7, 5);
        for (const Ray& ray : projection.pixel_centre_rays()) {
            EXPECT_TRUE(std::isfinite(ray.dir.x) && std::isfinite(ray.dir.y) &&
                        std::isfinite(ray.dir.z));
            EXPECT_NEAR(glm::length(ray.dir), 1.0f, 1e-5f);
        }
    }
    // Up of zero length, or parallel once scaled.
    EXPECT_THROW(validate(Camera{{0, 0, 1}, {0, 0, 0}, {0, 0, 0}, 45}), InputError);
    EXPECT_THROW(validate(Camera{{0, 0, 1}, {0, 0, 0}, {0, 0, 1e-38f}, 45}), InputError);
}

TEST(Camera, PixelIsTheInverseOfRay) {
    const Camera camera{{1, 2, 3}, {0, 0.5f, -1}, {0, 1, 0}, 50.0f};
    const PinholeProjection projection(camera, 320, 200);
    for (const glm::vec2 p : {glm::vec2(0, 0), glm::vec2(160, 100), glm::vec2(319.5f, 12.25f)}) {
        const Ray ray = projection.ray(p.x, p.y);
        const auto back = projection.pixel(ray.org + 7.0f * ray.dir);
        ASSERT_TRUE(back);
        EXPECT_NEAR(back->x, p.x, 1e-3f);
        EXPECT_NEAR(back->y, p.y, 1e-3f);
    }
    EXPECT_FALSE(projection.pixel(camera.eye - (camera.look_at - camera.eye)));  // behind
}

}  // namespace
}  // namespace edacrt

namespace edacrt {
namespace {

bool inside(const Aabb& box, const glm::vec3& p) {
    return p.x >= box.lo.x && p.y >= box.lo.y && p.z >= box.lo.z && p.x <= box.hi.x &&
           p.y <= box.hi.y && p.z <= box.hi.z;
}

TEST(DefaultCamera, ObjectsAreFramedFromOutsideInteriorsSeenFromInside) {
    // Bundled objects, and the open Cornell box (its front is missing: not enclosed).
    for (const char* path : {"assets/cornell-box/CornellBox-Original.obj",
                             "assets/teapot/teapot.obj", "assets/spot/spot.obj"}) {
        const Scene scene = load_scene((test::source_dir() / path).string());
        EXPECT_FALSE(is_interior(scene)) << path;
        EXPECT_EQ(default_camera(scene), frame_box(scene.bounds())) << path;
    }
    // A scene's own camera wins.
    const Scene cornell = load_scene("builtin:cornell");
    EXPECT_EQ(default_camera(cornell), *cornell.camera);
    // A closed cube seen from its centre: inside faces point inwards.
    Scene box = load_scene("builtin:cube:n=1");
    EXPECT_FALSE(is_interior(box)) << "the outside of a closed cube faces away from its centre";
    for (auto& tri : box.triangles) std::swap(tri[1], tri[2]);  // turned inside out: a room
    EXPECT_TRUE(is_interior(box));
    const Camera room = default_camera(box);
    EXPECT_TRUE(inside(box.bounds(), room.eye));
    validate(room);

    for (const auto& [file, interior] :
         {std::pair{"sponza/sponza.obj", true}, std::pair{"sibenik/sibenik.obj", true},
          std::pair{"conference/conference.obj", true},
          std::pair{"bunny/stanford-bunny.obj", false},
          std::pair{"dragon/dragon_vrip_res3.obj", false}, std::pair{"buddha/buddha.obj", false}}) {
        if (const std::string why = test::missing_scene(file); !why.empty()) {
            std::cout << "skipped " << file << ": " << why << "\n";
            continue;
        }
        const Scene scene = load_scene((test::scenes_dir() / file).string());
        EXPECT_EQ(is_interior(scene), interior) << file;
        const Camera camera = default_camera(scene);
        validate(camera);
        if (interior) {
            EXPECT_TRUE(inside(scene.bounds(), camera.eye)) << file;
        }
    }
}

// The camera flags (render/camera_options.h): each given setting overrides the scene's view,
// the others keep it, and the result is validated.
TEST(CameraOptions, EachGivenSettingOverridesTheScenesView) {
    const Scene scene = make_builtin_scene("builtin:cornell");
    const Camera scene_view = default_camera(scene);
    EXPECT_EQ(choose_camera(scene, {}), scene_view);
    CameraOptions options;
    EXPECT_FALSE(options.given());
    options.fov = {30.0f};
    options.eye = {1.0f, 2.0f, 3.0f};
    EXPECT_TRUE(options.given());
    const Camera camera = choose_camera(scene, options);
    EXPECT_EQ(camera.eye, glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(camera.vfov_degrees, 30.0f);
    EXPECT_EQ(camera.look_at, scene_view.look_at);
    EXPECT_EQ(camera.up, scene_view.up);
    options.fov = {180.0f};
    EXPECT_THROW(choose_camera(scene, options), InputError);

    // A default camera beyond float range names the scene and the flags that replace it.
    Scene huge;
    huge.source = "huge.obj";
    huge.positions = {{1e38f, 0.0f, 0.0f}, {-1e38f, 0.0f, 0.0f}, {0.0f, 1e38f, 0.0f}};
    huge.triangles = {{0, 1, 2}};
    huge.triangle_materials = {0};
    huge.materials.resize(1);
    try {
        choose_camera(huge, {});
        ADD_FAILURE() << "a camera past the float limit was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "huge.obj: the default camera from its bounds is not finite (coordinates near "
                  "the float limit); give --eye and --look-at");
    }
    CameraOptions given;
    given.eye = {0.0f, 0.0f, 5.0f};
    given.look_at = {0.0f, 0.0f, 0.0f};
    given.up = {0.0f, 1.0f, 0.0f};
    EXPECT_EQ(choose_camera(huge, given).eye, glm::vec3(0.0f, 0.0f, 5.0f));
    // One description per flag: the keys are the flags of both tools, each with help.
    std::vector<std::string> keys;
    for (const CameraParam& param : camera_params()) {
        keys.emplace_back(param.key);
        EXPECT_FALSE(param.help.empty()) << param.key;
        EXPECT_TRUE(param.count == 1 || param.count == 3) << param.key;
    }
    EXPECT_EQ(keys, (std::vector<std::string>{"eye", "look-at", "up", "fov"}));
}

}  // namespace
}  // namespace edacrt
