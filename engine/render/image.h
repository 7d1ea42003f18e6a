#pragma once
#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

namespace edacrt {

/// Linear RGB pixels, row-major from the top-left.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<glm::vec3> pixels;

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h)) {}
    glm::vec3& at(int x, int y) { return pixels[std::size_t(y) * width + x]; }
    const glm::vec3& at(int x, int y) const { return pixels[std::size_t(y) * width + x]; }
};

/// Writes 8-bit sRGB (values clamped to [0, 1]). Throws InputError when the file cannot be
/// written.
void write_png(const std::filesystem::path& path, const Image& image);

/// Writes 8-bit RGB, rows from the top, as PNG. Throws InputError when the file cannot be
/// written, std::invalid_argument when `rgb` is not width x height x 3 bytes.
void write_png_rgb8(const std::filesystem::path& path, std::span<const std::uint8_t> rgb, int width,
                    int height);

/// Reads an 8-bit PNG (or JPEG) back into linear RGB. Throws InputError.
Image read_png(const std::filesystem::path& path);

/// Writes 8-bit sRGB (values clamped to [0, 1]) as baseline JPEG of `quality` 1..100.
/// Throws InputError when the file cannot be written.
void write_jpg(const std::filesystem::path& path, const Image& image, int quality);

/// Writes 8-bit RGB, rows from the top, as JPEG; as write_png_rgb8.
void write_jpg_rgb8(const std::filesystem::path& path, std::span<const std::uint8_t> rgb, int width,
                    int height, int quality);

/// Writes linear RGB as Radiance RGBE (.hdr); NaN and negative values become 0, values beyond
/// its range (about 1.7e38, +inf included) its largest. Throws InputError.
void write_hdr(const std::filesystem::path& path, const Image& image);

/// Reads a Radiance .hdr into linear RGB. Throws InputError.
Image read_hdr(const std::filesystem::path& path);

/// Writes linear float RGB as a little-endian PFM ("PF", rows bottom to top). Throws InputError.
void write_pfm(const std::filesystem::path& path, const Image& image);

/// Reads a PFM (colour, either byte order). Throws InputError for malformed files.
Image read_pfm(const std::filesystem::path& path);

/// Root mean square error over all channels, and the relative MSE (mean of
/// (x - ref)^2 / (ref^2 + 0.01), channel by channel). Throws InputError for different sizes.
struct ImageError {
    double rmse = 0.0;
    double relative_mse = 0.0;
};
ImageError compare_images(const Image& image, const Image& reference);

}  // namespace edacrt
