// Animations: deformations, keyframed rigid objects and OBJ sequences write each frame into the
// scene's own storage, deterministically, with correct shading normals; bad specs, files and
// frames are errors that name what is wrong.
#include "scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

#include "scene/builtin_scenes.h"
#include "scene/deformations.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "util/error.h"
#include "util/frame_pattern.h"

namespace edacrt {
namespace {

using test::TempDir;

std::string spot() { return (test::source_dir() / "assets/spot/spot.obj").string(); }

/// The message of the InputError that `f` throws, or a failure.
template <class F>
std::string error_of(F f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return {};
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// A sphere with smooth shading normals (the normalised positions), one per vertex.
Scene smooth_sphere(int subdivisions) {
    Scene scene = make_builtin_scene("builtin:sphere:subdiv=" + std::to_string(subdivisions));
    for (const glm::vec3& p : scene.positions) scene.normals.push_back(glm::normalize(p));
    for (const auto& tri : scene.triangles)
        scene.triangle_normals.push_back(
            {std::int32_t(tri[0]), std::int32_t(tri[1]), std::int32_t(tri[2])});
    return scene;
}

/// The smallest dot product between a corner's shading normal and the normal of the deformed
/// surface there (the area-weighted mean of its triangles' geometric normals).
double worst_normal_agreement(const Scene& scene) {
    std::vector<glm::dvec3> surface(scene.positions.size(), glm::dvec3(0.0));
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
        const Triangle tri = scene.corners(i);
        const glm::dvec3 area_normal =
            glm::cross(glm::dvec3(tri.p1 - tri.p0), glm::dvec3(tri.p2 - tri.p0));
        for (const std::uint32_t v : scene.triangles[i]) surface[v] += area_normal;
    }
    double worst = 1.0;
    for (std::size_t i = 0; i < scene.triangle_count(); ++i)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 shading(scene.normals[std::size_t(scene.triangle_normals[i][k])]);
            worst =
                std::min(worst, glm::dot(shading, glm::normalize(surface[scene.triangles[i][k]])));
        }
    return worst;
}

TEST(Animation, SameTimeGivesTheSamePositionsInTheSameStorage) {
    for (const char* spec : {"wave", "twist", "explode"}) {
        AnimatedScene a = load_animated_scene(spot(), spec);
        AnimatedScene b = load_animated_scene(spot(), spec);
        const glm::vec3* storage = a.scene.positions.data();
        const std::size_t capacity = a.scene.positions.capacity();
        a.animation->frame(0.37, a.scene);
        const std::vector<glm::vec3> first = a.scene.positions;
        a.animation->frame(1.9, a.scene);
        EXPECT_NE(a.scene.positions, first) << spec;
        a.animation->frame(0.37, a.scene);
        EXPECT_EQ(a.scene.positions, first) << spec;
        b.animation->frame(0.37, b.scene);
        EXPECT_EQ(b.scene.positions, first) << spec;
        EXPECT_EQ(a.scene.positions.data(), storage) << spec << ": reallocated";
        EXPECT_EQ(a.scene.positions.capacity(), capacity) << spec;
        EXPECT_EQ(a.scene.triangle_count(), 5856u) << spec;
    }
}

TEST(Animation, WaveMovesPointsAlongItsAxisBySineOfTheirPlace) {
    const Scene base = make_builtin_scene("builtin:sphere:subdiv=3");
    AnimatedScene a =
        load_animated_scene("builtin:sphere:subdiv=3",
                            "wave:amplitude=0.05,wavelength=0.5,period=2,axis=z,direction=y");
    EXPECT_EQ(a.animation->spec(),
              "wave:amplitude=0.05,wavelength=0.5,period=2,axis=z,direction=y");
    EXPECT_DOUBLE_EQ(a.animation->duration(), 2.0);
    const double diagonal = glm::length(glm::dvec3(base.bounds().extent()));
    const double lo = base.bounds().lo.y;
    for (const double t : {0.0, 0.3, 1.25}) {
        a.animation->frame(t, a.scene);
        for (std::size_t v = 0; v < base.positions.size(); ++v) {
            const glm::vec3 p = base.positions[v], q = a.scene.positions[v];
            EXPECT_EQ(q.x, p.x);
            EXPECT_EQ(q.y, p.y);
            const double expected =
                0.05 * diagonal * std::sin(2 * M_PI * ((p.y - lo) / (0.5 * diagonal) - t / 2.0));
            ASSERT_NEAR(q.z - p.z, expected, 1e-6) << "vertex " << v << ", t " << t;
        }
    }
    // One period later: the same surface.
    a.animation->frame(0.3, a.scene);
    const std::vector<glm::vec3> at = a.scene.positions;
    a.animation->frame(2.3, a.scene);
    for (std::size_t v = 0; v < at.size(); ++v)
        ASSERT_NEAR(glm::length(a.scene.positions[v] - at[v]), 0.0f, 1e-6f);
}

TEST(Animation, TwistKeepsHeightAndDistanceFromTheAxis) {
    const Scene base = make_builtin_scene("builtin:cube:n=4");
    AnimatedScene a = load_animated_scene("builtin:cube:n=4", "twist:angle=180,period=4");
    a.animation->frame(0.0, a.scene);
    EXPECT_EQ(a.scene.positions, base.positions);  // sin(0) = 0: no twist yet
    a.animation->frame(1.0, a.scene);              // the most twisted: the ends at +-90 degrees
    for (std::size_t v = 0; v < base.positions.size(); ++v) {
        const glm::vec3 p = base.positions[v], q = a.scene.positions[v];
        EXPECT_EQ(q.y, p.y);
        EXPECT_NEAR(std::hypot(q.x, q.z), std::hypot(p.x, p.z), 1e-6);
        const double turned = std::remainder(std::atan2(q.z, q.x) - std::atan2(p.z, p.x), 2 * M_PI);
        // Right-handed about +y, so +x turns towards -z: atan2(z, x) falls.
        if (std::hypot(p.x, p.z) > 0.1) {
            EXPECT_NEAR(turned, -M_PI * p.y / 2.0, 1e-5) << v;
        }
    }
}

TEST(Animation, ExplodeMovesWholeTrianglesAlongTheirNormals) {
    const Scene base = load_scene(spot());
    AnimatedScene a = load_animated_scene(spot(), "explode:distance=0.2,period=3");
    ASSERT_EQ(a.scene.positions.size(), 3 * base.triangle_count());  // corners of their own
    EXPECT_EQ(a.scene.triangles[7], (std::array<std::uint32_t, 3>{21, 22, 23}));
    for (std::size_t i = 0; i < base.triangle_count(); ++i) {
        const Triangle b = base.corners(i), s = a.scene.corners(i);
        ASSERT_EQ(s.p0, b.p0);  // t = 0: as loaded
        ASSERT_EQ(s.p2, b.p2);
    }
    const double diagonal = glm::length(glm::dvec3(base.bounds().extent()));
    a.animation->frame(1.5, a.scene);  // half a period: the farthest out
    std::size_t moved = 0;
    for (std::size_t i = 0; i < base.triangle_count(); ++i) {
        const Triangle b = base.corners(i), s = a.scene.corners(i);
        const glm::vec3 offset = s.p0 - b.p0;
        ASSERT_NEAR(glm::length(s.p1 - s.p0 - (b.p1 - b.p0)), 0.0f, 1e-6f);  // same shape
        ASSERT_NEAR(glm::length(s.p2 - s.p1 - (b.p2 - b.p1)), 0.0f, 1e-6f);
        const glm::vec3 n = unit_normal(b);
        if (n == glm::vec3(0.0f)) continue;
        const float reach = glm::length(offset);
        ASSERT_GE(reach, 0.5 * 0.2 * diagonal * (1 - 1e-5));
        ASSERT_LE(reach, 1.5 * 0.2 * diagonal * (1 + 1e-5));
        ASSERT_NEAR(glm::dot(offset / reach, n), 1.0f, 1e-5f) << "triangle " << i;
        ++moved;
    }
    EXPECT_GT(moved, base.triangle_count() * 9 / 10);
}

TEST(Animation, ShadingNormalsFollowTheDeformedSurface) {
    // A fine sphere's smooth normals, turned by each deformation's inverse transpose Jacobian,
    // agree with the normals of the deformed mesh itself.
    for (const char* spec : {"wave:amplitude=0.04,wavelength=0.5", "twist:angle=120"}) {
        Scene scene = smooth_sphere(5);
        const auto animation = make_deformation(spec, scene);
        for (const double t : {0.2, 0.45, 0.9}) {
            animation->frame(t, scene);
            EXPECT_GT(worst_normal_agreement(scene), 0.995) << spec << " at t " << t;
        }
    }
    // A corner normal shared by several vertices is split so that each turns on its own.
    Scene scene = smooth_sphere(2);
    scene.normals = {glm::vec3(0, 1, 0)};
    for (auto& corners : scene.triangle_normals) corners = {0, 0, 0};
    make_deformation("twist", scene);
    EXPECT_EQ(scene.normals.size(), 3 * scene.triangle_count());
    EXPECT_EQ(scene.triangle_normals[5], (std::array<std::int32_t, 3>{15, 16, 17}));
}

TEST(Animation, BadSpecsAreErrorsNamingTheParameter) {
    const auto error = [](const std::string& spec) {
        return error_of([&] { load_animated_scene("builtin:sphere:subdiv=1", spec); });
    };
    EXPECT_TRUE(contains(error("ripple"), "unknown animation 'ripple'"));
    EXPECT_TRUE(contains(error("ripple"), "twist["));  // lists the kinds
    // On one line: a terminal shows a message's newlines as \x0A (util/printable.h).
    EXPECT_FALSE(contains(error("ripple"), "\n")) << error("ripple");
    EXPECT_TRUE(contains(error("ripple"), ", sequence:[fps=F,]pattern=")) << error("ripple");
    EXPECT_TRUE(contains(error("wave:height=3"), "unknown option 'height'"));
    EXPECT_TRUE(contains(error("wave:amplitude=nan"), "amplitude must be a number in [0, 10]"));
    EXPECT_TRUE(contains(error("wave:amplitude=-1"), "amplitude"));
    EXPECT_TRUE(contains(error("wave:period=0"), "period"));
    EXPECT_TRUE(contains(error("wave:wavelength=1e9"), "wavelength"));
    EXPECT_TRUE(contains(error("wave:axis=w"), "axis must be x, y or z, got 'w'"));
    EXPECT_TRUE(contains(error("wave:axis=x,direction=x"), "axis and direction must differ"));
    EXPECT_TRUE(contains(error("wave:axis=x,axis=y"), "'axis' is given twice"));
    EXPECT_TRUE(contains(error("twist:angle"), "expected key=value"));
    EXPECT_TRUE(contains(error("explode:distance=inf"), "distance"));
    EXPECT_TRUE(contains(error_of([] { load_animated_scene("", "wave"); }), "name one"));
    EXPECT_TRUE(contains(error_of([&] { load_animated_scene(spot(), "sequence:pattern=a%d.obj"); }),
                         "names its own geometry"));
    AnimatedScene a = load_animated_scene("builtin:sphere:subdiv=1", "wave");
    EXPECT_TRUE(contains(error_of([&] { a.animation->frame(NAN, a.scene); }), "finite"));
    EXPECT_THROW(a.animation->frame(0.0, *std::make_unique<Scene>()), std::invalid_argument);
}

TEST(Animation, NonFinitePositionsAreErrorsNamingTimeAndTriangle) {
    // Coordinates near the float limit: the diagonal, and so the wave, overflows.
    Scene scene;
    scene.source = "huge";
    scene.positions = {{0, 0, 0},     {1, 0, 0},      {0, 1, 0},
                       {3e38f, 0, 0}, {-3e38f, 1, 0}, {0, 3e38f, 0}};
    scene.triangles = {{0, 1, 2}, {3, 4, 5}};
    scene.triangle_materials = {0, 0};
    scene.materials.resize(1);
    const auto wave = make_deformation("wave:amplitude=1", scene);
    const std::string message = error_of([&] { wave->frame(0.1, scene); });
    EXPECT_TRUE(contains(message, "wave:amplitude=1,")) << message;
    EXPECT_TRUE(contains(message, "at t = 0.1 s: triangle 0 has a non-finite corner")) << message;

    // A mesh without extent has nothing to wave along: it stays.
    Scene point = scene;
    point.positions.assign(6, glm::vec3(1, 2, 3));
    const auto still = make_deformation("wave", point);
    still->frame(0.3, point);
    EXPECT_EQ(point.positions, std::vector<glm::vec3>(6, glm::vec3(1, 2, 3)));
}

TEST(FramePattern, WritesAndReadsPrintfNumbers) {
    const FramePattern p("out/frame_%04d.png", "--out");
    EXPECT_EQ(p.path(7), "out/frame_0007.png");
    EXPECT_EQ(p.path(123456), "out/frame_123456.png");
    EXPECT_EQ(p.directory(), "out");
    EXPECT_EQ(p.match("frame_0042.png"), 42);
    EXPECT_EQ(p.match("frame_123456.png"), 123456);
    EXPECT_FALSE(p.match("frame_42.png"));     // printf writes 0042
    EXPECT_FALSE(p.match("frame_00042.png"));  // ...never 00042
    EXPECT_FALSE(p.match("frame_00x2.png"));
    EXPECT_FALSE(p.match("frame_0042.png.bak"));
    const FramePattern plain("100%%_%d.obj", "pattern");
    EXPECT_EQ(plain.path(3), "100%_3.obj");
    EXPECT_EQ(plain.match("100%_12.obj"), 12);
    EXPECT_FALSE(plain.match("100%_012.obj"));
    const FramePattern folder("a%%b/c%%d_%d.png", "--out");
    EXPECT_EQ(folder.path(3), "a%b/c%d_3.png");
    EXPECT_EQ(folder.directory(), "a%b");
    EXPECT_EQ(FramePattern::literal("a%%b/100%%.png", "--out"), "a%b/100%.png");
    EXPECT_TRUE(contains(error_of([] { FramePattern::literal("5%.png", "--out"); }), "%%"));
    const auto error = [](const std::string& pattern) {
        return error_of([&] { FramePattern(pattern, "--out"); });
    };
    EXPECT_TRUE(contains(error("frame.png"), "no frame number"));
    EXPECT_TRUE(contains(error("f_%d_%d.png"), "only one"));
    EXPECT_TRUE(contains(error("f_%s.png"), "%0Nd"));
    EXPECT_TRUE(contains(error("f_%010d.png"), "%0Nd"));
    EXPECT_TRUE(contains(error("dir%d/f.png"), "in the file name"));
}

// ---- Rigid objects with keyframes ----

const char* const kTwoObjects = R"({
  "camera": {"eye": [0, 1, 6], "look_at": [0, 0, 0], "fov": 40},
  "objects": [
    {"mesh": "spot.obj",
     "keys": [{"time": 0, "translate": [1, 0, 0]},
              {"time": 2, "translate": [3, 0, 0], "rotate": [0, 1, 0, 360], "scale": 2}]},
    {"mesh": "builtin:cube:n=1"}
  ]
})";

class RigidAnimation : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_.write("spot.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
    }
    TempDir dir_;
};

TEST_F(RigidAnimation, KeysInterpolateTranslationScaleAndRotation) {
    AnimatedScene a = load_animated_scene("", dir_.write("two.anim.json", kTwoObjects).string());
    ASSERT_EQ(a.scene.triangle_count(), 1u + 12u);
    ASSERT_EQ(a.scene.materials.size(), 2u);  // each object's own default material
    EXPECT_EQ(a.scene.triangle_materials[1], 1u);
    for (std::size_t i = 1; i < a.scene.triangle_count(); ++i)  // the cube's corners come after
        for (const std::uint32_t v : a.scene.triangles[i]) EXPECT_GE(v, 3u);
    EXPECT_DOUBLE_EQ(a.animation->duration(), 2.0);
    ASSERT_TRUE(a.scene.camera);
    EXPECT_EQ(a.scene.camera->eye, glm::vec3(0, 1, 6));
    const std::vector<glm::vec3> cube(a.scene.positions.begin() + 3, a.scene.positions.end());
    EXPECT_EQ(a.scene.positions[1], glm::vec3(2, 0, 0));  // t = 0: translated by 1

    // Half way: translation 2, scale 1.5, and 180 degrees about y (the same axis: the angle
    // goes linearly from 0 to 360; slerp would see no rotation at all).
    a.animation->frame(1.0, a.scene);
    EXPECT_NEAR(glm::length(a.scene.positions[1] - glm::vec3(0.5f, 0, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(a.scene.positions[2] - glm::vec3(2, 1.5f, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(a.scene.normals[0] - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    // A quarter: 90 degrees, which takes +x to -z.
    a.animation->frame(0.5, a.scene);
    EXPECT_NEAR(glm::length(a.scene.positions[1] - glm::vec3(1.5f, 0, -1.25f)), 0.0f, 1e-6f);
    // After the last key it holds: a whole turn, translation 3, scale 2.
    a.animation->frame(5.0, a.scene);
    EXPECT_NEAR(glm::length(a.scene.positions[1] - glm::vec3(5, 0, 0)), 0.0f, 1e-5f);
    const std::vector<glm::vec3> still(a.scene.positions.begin() + 3, a.scene.positions.end());
    EXPECT_EQ(still, cube);  // the object without keys never moves
}

TEST_F(RigidAnimation, DifferentAxesSlerpAlongTheShorterArc) {
    const auto path = dir_.write("slerp.anim.json", R"({"objects": [{"mesh": "spot.obj", "keys": [
        {"time": 0, "rotate": [1, 0, 0, 0]}, {"time": 1, "rotate": [0, 0, 1, 90]}]}]})");
    AnimatedScene a = load_animated_scene("", path.string());
    a.animation->frame(0.5, a.scene);
    const glm::dquat half =
        glm::slerp(glm::dquat(1, 0, 0, 0), glm::angleAxis(M_PI / 2, glm::dvec3(0, 0, 1)), 0.5);
    EXPECT_NEAR(glm::length(glm::dvec3(a.scene.positions[1]) - half * glm::dvec3(1, 0, 0)), 0.0,
                1e-6);
}

TEST_F(RigidAnimation, BadFilesAreErrorsNamingTheEntry) {
    const auto error = [&](const std::string& text) {
        const auto path = dir_.write("bad.anim.json", text);
        return error_of([&] { load_animated_scene("", path.string()); });
    };
    EXPECT_TRUE(
        contains(error_of([&] { load_animated_scene("", (dir_.path() / "none.json").string()); }),
                 "cannot read"));
    EXPECT_TRUE(contains(error("{\"objects\": [}"), "not valid JSON"));
    EXPECT_TRUE(contains(error("{\"objects\": []}"), "non-empty list"));
    EXPECT_TRUE(contains(
        error(
            R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 0, "rotation": [0,1,0,5]}]}]})"),
        "objects[0].keys[0]: unknown field 'rotation' (known: time, translate, rotate, scale)"));
    EXPECT_TRUE(contains(
        error(R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 1}, {"time": 1}]}]})"),
        "objects[0].keys[1].time: key times must increase"));
    EXPECT_TRUE(contains(
        error(R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 0, "scale": -1}]}]})"),
        "scale: scales must be > 0"));
    // Numbers a double holds but a float pose does not: a denormal scale flattens the object.
    for (const char* key : {R"("scale": 1e-320)", R"("scale": [1, 1e-39, 1])", R"("scale": 1e39)"})
        EXPECT_TRUE(contains(error(R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 0, )" +
                                   std::string(key) + "}]}]}"),
                             "scale: scales must be > 0, from 1.17549e-38 to 3.40282e+38"))
            << key;
    EXPECT_TRUE(contains(error(R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 0, )"
                               R"("translate": [0, 1e300, 0]}]}]})"),
                         "translate: components must be within +-3.40282e+38"));
    EXPECT_TRUE(contains(error(R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 0, )"
                               R"("rotate": [1e-170, 0, 0, 9]}]}]})"),
                         "rotate: the axis must be a non-zero vector"));
    EXPECT_TRUE(contains(
        error(R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 0, "rotate": [0,0,0,9]}]}]})"),
        "rotate: the axis must be a non-zero vector"));
    EXPECT_TRUE(contains(
        error(R"({"objects": [{"mesh": "spot.obj", "keys": [{"time": 0, "translate": [1, 2]}]}]})"),
        "translate: expected [x, y, z]"));
    EXPECT_TRUE(contains(error(R"({"objects": [{"mesh": "missing.obj"}]})"), "objects[0].mesh"));
    EXPECT_TRUE(contains(
        error(
            R"({"objects": [{"mesh": "spot.obj"}], "camera": {"eye": [0,0,0], "look_at": [0,0,0]}})"),
        "camera"));
    EXPECT_TRUE(
        contains(error_of([&] { load_animated_scene(spot(), (dir_.path() / "x.json").string()); }),
                 "names its own geometry"));
}

// ---- OBJ sequences ----

/// A quad of two triangles whose top edge is at height `height`.
std::string quad(float height, bool extra_triangle = false, bool other_corners = false) {
    std::string text = "v 0 0 0\nv 1 0 0\nv 1 " + std::to_string(height) + " 0\nv 0 " +
                       std::to_string(height) + " 0\n";
    text += other_corners ? "f 1 2 4\nf 2 3 4\n" : "f 1 2 3\nf 1 3 4\n";
    if (extra_triangle) text += "f 1 2 4\n";
    return text;
}

TEST(ObjSequence, KeyFramesPlayAtTheirRateAndInterpolate) {
    const TempDir dir;
    for (int k = 1; k <= 4; ++k)
        dir.write("q_" + std::to_string(k).insert(0, 3, '0') + ".obj", quad(float(k)));
    dir.write("q_1.obj", quad(100.0f));  // not what %04d writes: ignored
    AnimatedScene a =
        load_animated_scene("", "sequence:fps=2,pattern=" + (dir.path() / "q_%04d.obj").string());
    EXPECT_DOUBLE_EQ(a.animation->duration(), 1.5);  // 4 keys at 2 per second
    EXPECT_EQ(a.scene.positions[2].y, 1.0f);
    a.animation->frame(1.0, a.scene);  // key 2: q_0003
    EXPECT_EQ(a.scene.positions[2].y, 3.0f);
    a.animation->frame(0.25, a.scene);  // half way from q_0001 to q_0002
    EXPECT_EQ(a.scene.positions[2].y, 1.5f);
    a.animation->frame(9.0, a.scene);  // after the last key: it holds
    EXPECT_EQ(a.scene.positions[3].y, 4.0f);
    a.animation->frame(-1.0, a.scene);  // before the first
    EXPECT_EQ(a.scene.positions[3].y, 1.0f);
}

TEST(ObjSequence, KeysAreReadWhenNeeded) {
    const TempDir dir;
    for (int k = 0; k < 5; ++k) {
        std::string name = "s";  // appended: GCC 12 warns falsely on "s" + std::string&&
        name.append(std::to_string(k)).append(".obj");
        dir.write(name, quad(float(k + 1)));
    }
    AnimatedScene a =
        load_animated_scene("", "sequence:pattern=" + (dir.path() / "s%d.obj").string());
    std::filesystem::remove(dir.path() / "s4.obj");  // not read yet: streamed
    a.animation->frame(2.5 / 24.0, a.scene);
    EXPECT_EQ(a.scene.positions[2].y, 3.5f);
    EXPECT_TRUE(contains(error_of([&] { a.animation->frame(4.0 / 24.0, a.scene); }), "s4.obj"));
}

TEST(ObjSequence, GapsAndMismatchedFramesAreErrors) {
    const auto sequence = [](const TempDir& dir) {
        return "sequence:pattern=" + (dir.path() / "f%02d.obj").string();
    };
    {
        const TempDir dir;
        for (int k : {1, 2, 4}) dir.write("f0" + std::to_string(k) + ".obj", quad(1.0f));
        const std::string message = error_of([&] { load_animated_scene("", sequence(dir)); });
        EXPECT_TRUE(
            contains(message, "key frame " + (dir.path() / "f03.obj").string() + " is missing"))
            << message;
    }
    {
        const TempDir dir;
        dir.write("f01.obj", quad(1.0f));
        dir.write("f02.obj", quad(2.0f, true));
        AnimatedScene a = load_animated_scene("", sequence(dir));
        const std::string message = error_of([&] { a.animation->frame(1.0, a.scene); });
        EXPECT_TRUE(contains(message, "f02.obj: 3 triangles, other than the first key frame"))
            << message;
        EXPECT_TRUE(contains(message, "f01.obj")) << message;
    }
    {
        const TempDir dir;
        dir.write("f01.obj", quad(1.0f));
        dir.write("f02.obj", quad(2.0f, false, true));
        AnimatedScene a = load_animated_scene("", sequence(dir));
        EXPECT_TRUE(contains(error_of([&] { a.animation->frame(0.01, a.scene); }),
                             "triangle 0 has other corners"));
    }
    {
        const TempDir dir;
        EXPECT_TRUE(
            contains(error_of([&] { load_animated_scene("", sequence(dir)); }), "no file in"));
        EXPECT_TRUE(contains(error_of([&] { load_animated_scene("", "sequence:f%d.obj"); }),
                             "pattern comes last"));
        EXPECT_TRUE(contains(
            error_of([&] { load_animated_scene("", "sequence:fps=0,pattern=f%d.obj"); }), "fps"));
        EXPECT_TRUE(contains(error_of([&] { load_animated_scene("", "sequence:pattern=f.obj"); }),
                             "no frame number"));
    }
}

}  // namespace
}  // namespace edacrt
