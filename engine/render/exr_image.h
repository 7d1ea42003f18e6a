#pragma once
// OpenEXR images (libopenexr): linear RGB as half or float, with string metadata in the header.
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "render/image.h"
#include "util/enum_table.h"

namespace edacrt {

/// How an EXR stores a channel: half (16-bit, what compositors default to; values beyond 65504
/// become infinite) or float (32-bit, exact).
enum class ExrPixel { half, single };
inline constexpr auto kExrPixels = enum_table<ExrPixel>(
    "EXR pixel type", {{ExrPixel::half, "half", "16-bit, as compositors default to"},
                       {ExrPixel::single, "float", "32-bit, exact"}});

/// Name and value pairs, kept in order; EXR writes each as a string attribute of the header.
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

/// Writes R, G, B channels (ZIP compressed) with `metadata`; throws InputError when the file
/// cannot be written, std::invalid_argument for a metadata name the format reserves.
void write_exr(const std::filesystem::path& path, const Image& image, ExrPixel pixel,
               const ImageMetadata& metadata = {});

/// Reads R, G, B (or Y, as grey) of any scanline or tiled EXR into float; the header's string
/// attributes go to `metadata` when given. Throws InputError.
Image read_exr(const std::filesystem::path& path, ImageMetadata* metadata = nullptr);

}  // namespace edacrt
