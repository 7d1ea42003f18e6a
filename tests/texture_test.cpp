// Diffuse textures: decoding (FreeImage), sRGB, bilinear filtering with wrap-around, texture
// coordinates from OBJ files, and what the renderer makes of them.
#include "scene/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <iterator>
#include <limits>
#include <string>

#include "render/image_format.h"
#include "render/renderer.h"
#include "scene/obj_loader.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "trace/tracer.h"
#include "util/error.h"

namespace edacrt {
namespace {

/// A binary PPM, rows from the top: red, green / blue, white.
std::string two_by_two() {
    std::string ppm = "P6\n2 2\n255\n";
    for (const unsigned char c : {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255})
        ppm.push_back(char(c));
    return ppm;
}

/// The same in blocks of 2 x 2 texels: bilinear filtering is constant within the middle half
/// of each block (u and v in [1/8, 3/8] or [5/8, 7/8]).
std::string four_by_four() {
    const unsigned char top[] = {255, 0, 0, 255, 0, 0, 0, 255, 0, 0, 255, 0};
    const unsigned char bottom[] = {0, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255, 255};
    std::string ppm = "P6\n4 4\n255\n";
    for (const unsigned char* row : {top, top, bottom, bottom}) ppm.append((const char*)row, 12);
    return ppm;
}

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-6f) {
    EXPECT_LT(glm::length(actual - expected), tolerance)
        << actual.x << " " << actual.y << " " << actual.z << " != " << expected.x << " "
        << expected.y << " " << expected.z;
}

TEST(Texture, SrgbDecodesToLinear) {
    EXPECT_EQ(srgb_to_linear(0), 0.0f);
    EXPECT_EQ(srgb_to_linear(255), 1.0f);
    EXPECT_NEAR(srgb_to_linear(10), 10.0f / 255.0f / 12.92f, 1e-7f);  // the linear segment
    EXPECT_NEAR(srgb_to_linear(188), 0.5029f, 1e-4f);                 // about half
    for (int i = 1; i < 256; ++i)
        EXPECT_GT(srgb_to_linear(std::uint8_t(i)), srgb_to_linear(std::uint8_t(i - 1)));
}

TEST(Texture, TexelCentresBlendsAndWrapAround) {
    const test::TempDir dir;
    const Texture t = load_texture(dir.write("t.ppm", two_by_two()).string());
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 2);
    // v = 0 is the image's bottom row (OBJ's convention).
    expect_near(t.lookup({0.25f, 0.25f}), {0, 0, 1});  // blue, bottom left
    expect_near(t.lookup({0.75f, 0.25f}), {1, 1, 1});  // white
    expect_near(t.lookup({0.25f, 0.75f}), {1, 0, 0});  // red, top left
    expect_near(t.lookup({0.75f, 0.75f}), {0, 1, 0});  // green
    // Halfway between blue and white, in linear light.
    expect_near(t.lookup({0.5f, 0.25f}), {0.5f, 0.5f, 1.0f});
    // Outside [0, 1] the texture repeats; at the edge it blends with the opposite one.
    for (const float shift : {-3.0f, -1.0f, 1.0f, 7.0f})
        expect_near(t.lookup({0.25f + shift, 0.75f - shift}), {1, 0, 0}, 1e-5f);
    expect_near(t.lookup({0.0f, 0.25f}), {0.5f, 0.5f, 1.0f});
    // Coordinates that are not finite, or huge, give a texel blend, never a read out of range.
    const float inf = std::numeric_limits<float>::infinity();
    for (const float bad : {std::nanf(""), inf, -inf, 1e30f, -1e30f}) {
        const glm::vec3 c = t.lookup({bad, bad});
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(c[k], 0.0f) << bad;
            EXPECT_LE(c[k], 1.0f) << bad;
        }
    }
}

TEST(Texture, UnreadableFilesAreRefusedWithTheirName) {
    const test::TempDir dir;
    const auto message = [](const std::filesystem::path& path) {
        try {
            load_texture(path.string());
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string missing = message(dir.path() / "gone.png");
    EXPECT_NE(missing.find("gone.png: cannot read the texture (no such file)"), std::string::npos)
        << missing;
    EXPECT_NE(message(dir.write("text.png", "not an image")).find("text.png: cannot read"),
              std::string::npos);
    // Cut short, a JPEG or PNG decodes with grey or black rows and a decoder message.
    Image image(64, 64);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = glm::vec3(float(i % 64) / 64.0f, 0.5f, float(i / 64) / 64.0f);
    for (const char* name : {"whole.jpg", "whole.png"}) {
        const auto whole = dir.path() / name;
        save_image(whole, image, ImageOutput{});
        EXPECT_EQ(load_texture(whole.string()).width, 64);
        std::ifstream in(whole, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        const std::string cut = std::string("cut") + name;
        EXPECT_NE(message(dir.write(cut, bytes.substr(0, bytes.size() / 2)))
                      .find(cut + ": cannot read the texture ("),
                  std::string::npos)
            << cut;
    }
    EXPECT_NE(message(dir.write("empty.jpg", "")).find("empty.jpg: cannot read"),
              std::string::npos);
    EXPECT_NE(message(dir.path()).find("no such file"), std::string::npos);  // a directory
}

/// A unit square in z = 0 whose texture coordinates span [0, 2] x [0, 1] (the texture twice
/// across), with a material `m` that names `map` (written beside it).
std::filesystem::path textured_square(const test::TempDir& dir, const std::string& map) {
    dir.write("m.mtl", "newmtl m\nKd 1 1 1\nmap_Kd " + map + "\nnewmtl same\nmap_Kd " + map +
                           "\nnewmtl plain\nKd 0.5 0.5 0.5\n");
    return dir.write("square.obj",
                     "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                     "vt 0 0\nvt 2 0\nvt 2 1\nvt 0 1\n"
                     "usemtl m\nf 1/1 2/2 3/3\nusemtl same\nf 1/-4 3/-2 4/-1\n"
                     "usemtl plain\nf 1 2 3\n");
}

TEST(Texture, ObjTextureCoordinatesAndMapKdAreLoaded) {
    const test::TempDir dir;
    dir.write("t.ppm", two_by_two());
    const Scene scene = load_obj(textured_square(dir, "t.ppm"));
    ASSERT_EQ(scene.texcoords.size(), 4u);
    EXPECT_EQ(scene.texcoords[2], glm::vec2(2, 1));
    ASSERT_EQ(scene.triangle_texcoords.size(), 3u);
    EXPECT_EQ(scene.triangle_texcoords[0], (std::array<std::int32_t, 3>{0, 1, 2}));
    EXPECT_EQ(scene.triangle_texcoords[1], (std::array<std::int32_t, 3>{0, 2, 3}));  // negative
    EXPECT_EQ(scene.triangle_texcoords[2], (std::array<std::int32_t, 3>{-1, -1, -1}));
    ASSERT_EQ(scene.materials.size(), 3u);
    ASSERT_TRUE(scene.materials[0].diffuse_map);
    EXPECT_EQ(scene.materials[0].diffuse_map, scene.materials[1].diffuse_map);  // decoded once
    EXPECT_FALSE(scene.materials[2].diffuse_map);
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings[0];
}

TEST(Texture, AMissingOrBrokenMapLeavesKdAndAWarning) {
    for (const std::string map : {"gone.png", "broken.png"}) {
        const test::TempDir dir;
        dir.write("broken.png", "\x89PNG\r\n\x1a\n truncated");
        const Scene scene = load_obj(textured_square(dir, map));
        EXPECT_FALSE(scene.materials[0].diffuse_map) << map;
        ASSERT_EQ(scene.warnings.size(), 1u) << map;  // once for both materials
        EXPECT_NE(scene.warnings[0].find(map + ": cannot read the texture"), std::string::npos)
            << scene.warnings[0];
        EXPECT_NE(scene.warnings[0].find("Kd alone is used"), std::string::npos);
    }
}

/// The albedo image of the square seen head-on, filling the view.
Image albedo_of(const Scene& scene, Integrator integrator) {
    RenderSettings settings;
    settings.width = settings.height = 16;
    settings.integrator = integrator;
    settings.primary = PrimaryShading::albedo;
    settings.ao_samples = 4;
    settings.ao_distance = 1e-3f;  // nothing occludes within it: ao is the albedo
    const auto tracer = make_tracer(Method::edacrt);
    tracer->set_scene(scene);
    // 2 * atan(0.5 / 1) = 53.13 degrees: the square [0, 1]^2 exactly.
    const Camera camera{{0.5f, 0.5f, 1.0f}, {0.5f, 0.5f, 0.0f}, {0, 1, 0}, 53.130102f};
    Renderer renderer(scene, *tracer, camera, settings);
    renderer.render_pass();
    return renderer.film().mean();
}

TEST(Texture, TheAlbedoAndAoShowTheTextureTimesKd) {
    const test::TempDir dir;
    dir.write("t.ppm", four_by_four());
    Scene scene = load_obj(textured_square(dir, "t.ppm"));
    scene.triangles.pop_back();  // the plain triangle, drawn over the others
    scene.triangle_materials.pop_back();
    scene.triangle_texcoords.pop_back();
    scene.materials[0].kd = scene.materials[1].kd = glm::vec3(0.5f);
    for (const Integrator integrator : {Integrator::primary, Integrator::ao}) {
        const Image image = albedo_of(scene, integrator);
        // Pixel (x, y) from the top covers u in [x / 8, (x + 1) / 8] (the texture twice across)
        // and v in [1 - (y + 1) / 16, 1 - y / 16]: columns 1, 5 and 9, rows 4 and 11 lie where
        // the filtered texture is constant, whatever the sample's place in the pixel.
        const auto pixel = [&](int x, int y) { return image.pixels[std::size_t(y * 16 + x)]; };
        expect_near(pixel(1, 11), 0.5f * glm::vec3(0, 0, 1));  // blue, bottom left
        expect_near(pixel(5, 11), 0.5f * glm::vec3(1, 1, 1));  // white
        expect_near(pixel(1, 4), 0.5f * glm::vec3(1, 0, 0));   // red
        expect_near(pixel(5, 4), 0.5f * glm::vec3(0, 1, 0));   // green
        expect_near(pixel(9, 4), pixel(1, 4));                 // repeated from u = 1
    }
}

TEST(Texture, SponzaAndSibenikDecodeEveryMap) {
    for (const char* file : {"sponza/sponza.obj", "sibenik/sibenik.obj"}) {  // JPEG, DDS
        if (const std::string why = test::missing_scene(file); !why.empty()) GTEST_SKIP() << why;
        const Scene scene = load_obj(test::scenes_dir() / file);
        std::size_t mapped = 0;
        for (const Material& m : scene.materials) {
            bool names_one = false;
            for (const TextureMap& t : m.textures) names_one |= t.keyword == "map_Kd";
            EXPECT_EQ(bool(m.diffuse_map), names_one) << file << " " << m.name;
            if (m.diffuse_map) {
                ++mapped;
                EXPECT_GT(m.diffuse_map->width, 16) << m.name;
            }
        }
        EXPECT_GT(mapped, 3u) << file;
        EXPECT_FALSE(scene.texcoords.empty()) << file;
        for (const std::string& w : scene.warnings)
            EXPECT_EQ(w.find("texture"), std::string::npos) << w;
    }
}

}  // namespace
}  // namespace edacrt
