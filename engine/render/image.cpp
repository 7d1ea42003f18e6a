#include "render/image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "scene/texture.h"  // srgb_to_linear
#include "util/error.h"
#include "util/output_file.h"

namespace edacrt {
namespace {

float linear_to_srgb(float c) {
    c = c > 0.0f ? std::min(c, 1.0f) : 0.0f;  // NaN too becomes 0, not an undefined lround
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::vector<std::uint8_t> to_srgb8(const Image& image) {
    std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            bytes[3 * i + c] =
                static_cast<std::uint8_t>(std::lround(255.0f * linear_to_srgb(image.pixels[i][c])));
    return bytes;
}

/// stb's writers ignore write and close errors, so stb encodes and OutputFile writes.
void append_to_file(void* context, void* data, int size) {
    static_cast<OutputFile*>(context)->write(data, std::size_t(size));
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& image) {
    write_png_rgb8(path, to_srgb8(image), image.width, image.height);
}

void write_png_rgb8(const std::filesystem::path& path, std::span<const std::uint8_t> rgb, int width,
                    int height) {
    if (rgb.size() != std::size_t(width) * std::size_t(height) * 3)
        throw std::invalid_argument("write_png_rgb8: " + std::to_string(rgb.size()) +
                                    " bytes for " + std::to_string(width) + "x" +
                                    std::to_string(height) + " pixels");
    OutputFile file(path, "PNG");
    if (!stbi_write_png_to_func(append_to_file, &file, width, height, 3, rgb.data(), width * 3))
        throw InputError(path.string() + ": cannot encode PNG");
    file.close();
}

Image read_png(const std::filesystem::path& path) {
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
        stbi_load(path.c_str(), &width, &height, &channels, 3), &stbi_image_free);
    if (!data)
        throw InputError(path.string() + ": cannot read image (" + stbi_failure_reason() + ")");
    Image image(width, height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels[i][c] = srgb_to_linear(data.get()[3 * i + c]);
    return image;
}

void write_jpg(const std::filesystem::path& path, const Image& image, int quality) {
    write_jpg_rgb8(path, to_srgb8(image), image.width, image.height, quality);
}

void write_jpg_rgb8(const std::filesystem::path& path, std::span<const std::uint8_t> rgb, int width,
                    int height, int quality) {
    if (rgb.size() != std::size_t(width) * std::size_t(height) * 3)
        throw std::invalid_argument("write_jpg_rgb8: " + std::to_string(rgb.size()) +
                                    " bytes for " + std::to_string(width) + "x" +
                                    std::to_string(height) + " pixels");
    if (quality < 1 || quality > 100)
        throw InputError("JPEG quality must be 1..100, not " + std::to_string(quality));
    OutputFile file(path, "JPEG");
    if (!stbi_write_jpg_to_func(append_to_file, &file, width, height, 3, rgb.data(), quality))
        throw InputError(path.string() + ": cannot encode JPEG");
    file.close();
}

void write_hdr(const std::filesystem::path& path, const Image& image) {
    // RGBE holds exponents up to 127: larger values, and inf, would wrap to black.
    std::vector<float> values(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = image.pixels[i][c];
            values[3 * i + c] = v > 0.0f ? std::min(v, 1e38f) : 0.0f;  // NaN too becomes 0
        }
    OutputFile file(path, "HDR");
    if (!stbi_write_hdr_to_func(append_to_file, &file, image.width, image.height, 3, values.data()))
        throw InputError(path.string() + ": cannot encode HDR");
    file.close();
}

Image read_hdr(const std::filesystem::path& path) {
    if (!stbi_is_hdr(path.c_str()))
        throw InputError(path.string() + ": cannot read HDR (not a Radiance RGBE file)");
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, decltype(&stbi_image_free)> data(
        stbi_loadf(path.c_str(), &width, &height, &channels, 3), &stbi_image_free);
    if (!data)
        throw InputError(path.string() + ": cannot read HDR (" + stbi_failure_reason() + ")");
    Image image(width, height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = {data.get()[3 * i], data.get()[3 * i + 1], data.get()[3 * i + 2]};
    return image;
}

void write_pfm(const std::filesystem::path& path, const Image& image) {
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "a pixel is written as one block");
    OutputFile file(path, "PFM");
    file.write("PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) +
               "\n-1.0\n");
    for (int y = image.height - 1; y >= 0; --y)
        file.write(&image.at(0, y), std::size_t(image.width) * sizeof(glm::vec3));
    file.close();
}

Image read_pfm(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open");
    std::string magic;
    long long width = 0, height = 0;
    double scale = 0.0;
    in >> magic >> width >> height >> scale;
    if (!in || magic != "PF" || width < 1 || height < 1 || width > 65536 || height > 65536 ||
        !std::isfinite(scale) || scale == 0.0)
        throw InputError(path.string() + ": not a colour PFM (header 'PF', size, scale)");
    in.get();  // the single whitespace character before the data
    Image image{int(width), int(height)};
    const bool big_endian = scale > 0.0;
    for (int y = image.height - 1; y >= 0; --y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                std::uint32_t bits = 0;
                if (!in.read(reinterpret_cast<char*>(&bits), 4))
                    throw InputError(path.string() + ": PFM data ends early");
                if (big_endian) bits = __builtin_bswap32(bits);
                float value;
                std::memcpy(&value, &bits, 4);
                image.at(x, y)[c] = value;
            }
    return image;
}

ImageError compare_images(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height)
        throw InputError("cannot compare a " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " image with a " +
                         std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                         " reference");
    double squared = 0.0, relative = 0.0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(image.pixels[i][c]) - double(reference.pixels[i][c]);
            const double r = double(reference.pixels[i][c]);
            squared += d * d;
            relative += d * d / (r * r + 0.01);
        }
    const double n = 3.0 * double(image.pixels.size());
    return {std::sqrt(squared / n), relative / n};
}

}  // namespace edacrt
