// Image files: the extension chooses the format, EXR and HDR round trips, the errors.
#include "render/image_format.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <vector>

#include "cli_runner.h"
#include "test_paths.h"
#include "util/error.h"

namespace edacrt {
namespace {

class ImageFormatTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("edacrt_image_format_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path path(const std::string& name) const { return dir_ / name; }

    std::filesystem::path dir_;
};

/// Values over many octaves, both signs, and ones that need every mantissa bit.
Image test_image() {
    Image image(7, 5);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float v = std::ldexp(1.0f + float(x * 5 + y) / 37.0f, x - 3 * y);
            image.at(x, y) = {v, -v * 0.3f, std::nextafter(v, 2.0f * v)};
        }
    return image;
}

std::string head(const std::filesystem::path& file, std::size_t n) {
    std::ifstream in(file, std::ios::binary);
    std::string bytes(n, '\0');
    in.read(bytes.data(), std::streamsize(n));
    return bytes.substr(0, std::size_t(in.gcount()));
}

TEST_F(ImageFormatTest, ExrFloatRoundTripIsExactAndKeepsTheMetadata) {
    const Image image = test_image();
    const ImageMetadata metadata = {{"method", "edacrt"}, {"spp", "64"}};
    write_exr(path("f.exr"), image, ExrPixel::single, metadata);
    ImageMetadata read_back;
    const Image back = read_exr(path("f.exr"), &read_back);
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(back.pixels[i][c], image.pixels[i][c]) << "pixel " << i << " channel " << c;
    for (const auto& entry : metadata)
        EXPECT_NE(std::find(read_back.begin(), read_back.end(), entry), read_back.end())
            << entry.first;
}

TEST_F(ImageFormatTest, ExrHalfRoundTripIsWithinHalfPrecision) {
    const Image image = test_image();
    write_exr(path("h.exr"), image, ExrPixel::half);
    const Image back = read_exr(path("h.exr"));
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = image.pixels[i][c];
            // Half has 11 significant bits: rounding is within 2^-11 relative for normal
            // values, within half the smallest subnormal (2^-25) below 2^-14.
            const float tolerance = std::max(std::abs(v) * 0x1p-11f, 0x1p-25f);
            EXPECT_NEAR(back.pixels[i][c], v, tolerance) << "pixel " << i << " channel " << c;
        }
    // Beyond half's range is infinite; float keeps it.
    Image big(1, 1);
    big.pixels[0] = {1e5f, 65504.0f, -1e6f};
    write_exr(path("big.exr"), big, ExrPixel::half);
    const Image big_back = read_exr(path("big.exr"));
    EXPECT_EQ(big_back.pixels[0].x, std::numeric_limits<float>::infinity());
    EXPECT_EQ(big_back.pixels[0].y, 65504.0f);
    EXPECT_EQ(big_back.pixels[0].z, -std::numeric_limits<float>::infinity());
}

TEST_F(ImageFormatTest, TheExtensionChoosesTheFormat) {
    const Image image = test_image();
    const struct {
        const char* name;
        ImageFormat format;
        std::string magic;
    } cases[] = {
        {"a.png", ImageFormat::png, "\x89PNG"},
        {"a.jpg", ImageFormat::jpg, "\xFF\xD8\xFF"},
        {"a.JPEG", ImageFormat::jpg, "\xFF\xD8\xFF"},
        {"a.hdr", ImageFormat::hdr, "#?RADIANCE"},
        {"a.pfm", ImageFormat::pfm, "PF\n"},
        {"a.Exr", ImageFormat::exr, std::string("\x76\x2f\x31\x01", 4)},
    };
    for (const auto& c : cases) {
        EXPECT_EQ(image_format(c.name), c.format) << c.name;
        save_image(path(c.name), image, {});
        EXPECT_EQ(head(path(c.name), c.magic.size()), c.magic) << c.name;
        const Image back = load_image(path(c.name));
        EXPECT_EQ(back.width, image.width) << c.name;
        EXPECT_EQ(back.height, image.height) << c.name;
        EXPECT_EQ(is_linear(c.format),
                  c.format != ImageFormat::png && c.format != ImageFormat::jpg);
    }
}

TEST_F(ImageFormatTest, UnknownExtensionsAreRefusedWithTheKnownOnes) {
    for (const char* name : {"a.tiff", "a", "a.png.bak"}) {
        try {
            save_image(path(name), test_image(), {});
            ADD_FAILURE() << name << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(".png, .jpg, .jpeg, .hdr, .pfm, .exr"),
                      std::string::npos)
                << e.what();
        }
        EXPECT_FALSE(std::filesystem::exists(path(name))) << name;
        EXPECT_THROW(load_image(path(name)), InputError) << name;
    }
}

TEST_F(ImageFormatTest, PixelsAsShownArePngOrJpegByExtension) {
    // What a window shows (the viewer's save-view and --screenshot): 8-bit sRGB already.
    const std::vector<std::uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
    save_srgb8(path("shown.png"), rgb, 2, 2);
    save_srgb8(path("dir/shown.jpg"), rgb, 2, 2);
    EXPECT_EQ(head(path("shown.png"), 4), "\x89PNG");
    EXPECT_EQ(head(path("dir/shown.jpg"), 3), "\xFF\xD8\xFF");
    EXPECT_EQ(read_png(path("shown.png")).at(1, 0), glm::vec3(0, 1, 0));
    for (const char* name : {"shown.exr", "shown.pfm", "shown.hdr"}) {
        try {
            save_srgb8(path(name), rgb, 2, 2);
            ADD_FAILURE() << name << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("save it as .png or .jpg"), std::string::npos)
                << e.what();
        }
    }
    EXPECT_THROW(save_srgb8(path("shown.gif"), rgb, 2, 2), InputError);
}

TEST_F(ImageFormatTest, HdrKeepsRgbePrecisionAndClampsWhatItCannotHold) {
    Image image = test_image();
    write_hdr(path("a.hdr"), image);
    const Image back = read_hdr(path("a.hdr"));
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec3 v = image.pixels[i];
        // One shared exponent and 8-bit mantissas: within 2^-7 of the largest component.
        const float tolerance = std::max({v.x, v.y, v.z}) * 0x1p-7f;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(back.pixels[i][c], std::max(v[c], 0.0f), tolerance) << i << " " << c;
    }
    Image extreme(3, 1);
    extreme.pixels = {{NAN, -1.0f, 0.5f},
                      {std::numeric_limits<float>::infinity(), 3e38f, 0.0f},
                      {1.0f, 1.0f, 1.0f}};
    write_hdr(path("x.hdr"), extreme);
    const Image x = read_hdr(path("x.hdr"));
    EXPECT_EQ(x.pixels[0].x, 0.0f);
    EXPECT_EQ(x.pixels[0].y, 0.0f);
    EXPECT_NEAR(x.pixels[0].z, 0.5f, 0.5f * 0x1p-7f);
    EXPECT_GT(x.pixels[1].x, 1e37f);  // as bright as RGBE goes, not black
    EXPECT_GT(x.pixels[1].y, 1e37f);
    EXPECT_EQ(x.pixels[2].x, 1.0f);
}

TEST_F(ImageFormatTest, BadFilesAreErrorsNamingTheFile) {
    std::ofstream(path("junk.exr")) << "not an exr";
    std::ofstream(path("junk.hdr")) << "not an hdr";
    std::filesystem::create_directories(path("dir.exr"));
    for (const char* name : {"junk.exr", "missing.exr", "dir.exr", "junk.hdr", "missing.jpg"}) {
        try {
            load_image(path(name));
            ADD_FAILURE() << name << " was read";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
    }
    std::filesystem::create_symlink("/dev/full", path("full.exr"));
    try {
        save_image(path("full.exr"), test_image(), {});
        ADD_FAILURE() << "a full disk passed";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot write OpenEXR (No space left on device)"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(ImageFormatTest, RenderWritesEveryFormatAndReadsAnExrReference) {
    const std::string small = "render --scene builtin:cornell --width 16 --height 12 --spp 2 ";
    for (const char* name : {"r.png", "r.jpg", "r.hdr", "r.pfm", "r.exr"}) {
        const auto result = test::run_cli(small + "--quiet --out " + path(name).string());
        ASSERT_EQ(result.exit_code, 0) << result.output;
        EXPECT_EQ(load_image(path(name)).width, 16) << name;
    }
    ImageMetadata metadata;
    const Image exr = read_exr(path("r.exr"), &metadata);
    const Image pfm = read_pfm(path("r.pfm"));
    EXPECT_EQ(exr.pixels, pfm.pixels) << "float EXR is the PFM's radiance";
    const auto value = [&](const std::string& name) {
        for (const auto& [key, text] : metadata)
            if (key == name) return text;
        return std::string("(missing)");
    };
    EXPECT_EQ(value("method"), "edacrt");
    EXPECT_EQ(value("integrator"), "path");
    EXPECT_EQ(value("spp"), "2");
    EXPECT_EQ(value("scene"), "builtin:cornell");
    EXPECT_NE(value("cameraEye"), "(missing)");
    EXPECT_NE(value("renderSeconds"), "(missing)");

    const auto compared = test::run_cli(small + "--reference " + path("r.exr").string() +
                                        " --out " + path("s.png").string());
    ASSERT_EQ(compared.exit_code, 0) << compared.output;
    EXPECT_NE(compared.output.find("rmse"), std::string::npos) << compared.output;

    const auto unknown = test::run_cli(small + "--out " + path("r.tiff").string());
    EXPECT_EQ(unknown.exit_code, 2) << unknown.output;  // a usage error
    EXPECT_NE(unknown.output.find("r.tiff: unknown image format '.tiff'; the extension chooses "
                                  "it: .png, .jpg, .jpeg, .hdr, .pfm, .exr"),
              std::string::npos)
        << unknown.output;
    EXPECT_EQ(unknown.output.find("loaded"), std::string::npos) << "refused before any work";
    EXPECT_NE(test::run_cli(small + "--jpeg-quality 0 --out " + path("q.jpg").string()).exit_code,
              0);
    EXPECT_NE(test::run_cli(small + "--exr-pixel double --out " + path("q.exr").string()).exit_code,
              0);
}

}  // namespace
}  // namespace edacrt
