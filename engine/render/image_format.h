#pragma once
// Image files by extension: the one place that knows which formats exist, which are tone-mapped
// 8-bit and which linear, for the CLI's --out and --reference and the viewer's save.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "render/exr_image.h"
#include "render/film.h"
#include "render/image.h"
#include "util/enum_table.h"

namespace edacrt {

enum class ImageFormat { png, jpg, hdr, pfm, exr };
/// The formats by extension (.jpeg is another name of jpg).
inline constexpr auto kImageFormats = enum_table<ImageFormat>(
    "image format",
    {{ImageFormat::png, ".png", "8-bit sRGB, tone-mapped"},
     {ImageFormat::jpg, ".jpg", "8-bit sRGB, tone-mapped"},
     {ImageFormat::jpg, ".jpeg"},
     {ImageFormat::hdr, ".hdr", "Radiance RGBE"},
     {ImageFormat::pfm, ".pfm", "float"},
     {ImageFormat::exr, ".exr", "OpenEXR with the render's settings in its header"}});

/// The format of a path's extension (.png, .jpg or .jpeg, .hdr, .pfm, .exr, any letter case).
/// Throws InputError naming the known extensions.
ImageFormat image_format(const std::filesystem::path& path);

/// The largest image file load_image() reads: a 16384 x 16384 float image and its headers.
constexpr std::uint64_t kMaxImageFileBytes = 4ull << 30;

/// PNG and JPEG hold tone-mapped 8-bit sRGB; HDR, PFM and EXR the linear radiance.
bool is_linear(ImageFormat format);

/// How save_image() encodes: exposure and tone map for 8-bit formats, JPEG quality, EXR pixel
/// type, and metadata (written where the format has room for it: EXR).
struct ImageOutput {
    float exposure = 0.0f;  // stops
    ToneMap tone_map = ToneMap::clamp;
    int jpeg_quality = 90;  // 1..100
    ExrPixel exr_pixel = ExrPixel::single;
    ImageMetadata metadata;
};

/// Writes linear radiance in the format of the path's extension (tone-mapped for 8-bit
/// formats), creating missing parent directories. Throws InputError.
void save_image(const std::filesystem::path& path, Image linear, const ImageOutput& output);

/// Writes pixels already tone-mapped and sRGB-encoded (rows from the top: what a window shows)
/// as PNG or JPEG by the path's extension, creating missing parent directories. Throws
/// InputError, also for the linear formats, which 8-bit pixels cannot fill.
void save_srgb8(const std::filesystem::path& path, std::span<const std::uint8_t> rgb, int width,
                int height, int jpeg_quality = 90);

/// Reads any of the formats into linear RGB (8-bit ones decoded from sRGB). Throws InputError.
Image load_image(const std::filesystem::path& path);

/// Bytes per pixel save_image() holds besides its argument: encoder buffers (8-bit pixels and
/// the compressed stream, RGBE floats, the in-memory EXR).
std::uint64_t save_image_bytes_per_pixel(ImageFormat format);

}  // namespace edacrt
