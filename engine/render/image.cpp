#include "render/image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "util/error.h"

namespace edacrt {
namespace {

float linear_to_srgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& image) {
    std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            bytes[3 * i + c] =
                static_cast<std::uint8_t>(std::lround(255.0f * linear_to_srgb(image.pixels[i][c])));
    if (!stbi_write_png(path.c_str(), image.width, image.height, 3, bytes.data(), image.width * 3))
        throw InputError(path.string() + ": cannot write PNG");
}

Image read_png(const std::filesystem::path& path) {
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
        stbi_load(path.c_str(), &width, &height, &channels, 3), &stbi_image_free);
    if (!data)
        throw InputError(path.string() + ": cannot read PNG (" + stbi_failure_reason() + ")");
    Image image(width, height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            image.pixels[i][c] = srgb_to_linear(float(data.get()[3 * i + c]) / 255.0f);
    return image;
}

}  // namespace edacrt
