#include "render/image_format.h"

#include <algorithm>
#include <cctype>

#include "util/error.h"
#include "util/input_file.h"
#include "util/output_file.h"

namespace edacrt {

ImageFormat image_format(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (const auto format = parse_enum(kImageFormats, ext)) return *format;
    throw InputError(path.string() + ": unknown image format " +
                     (ext.empty() ? std::string("(no extension)") : "'" + ext + "'") +
                     "; the extension chooses it: " + enum_names(kImageFormats));
}

bool is_linear(ImageFormat format) {
    return format == ImageFormat::hdr || format == ImageFormat::pfm || format == ImageFormat::exr;
}

void save_image(const std::filesystem::path& path, Image linear, const ImageOutput& output) {
    const ImageFormat format = image_format(path);
    create_parent_folders(path);
    if (!is_linear(format)) linear = tone_map(std::move(linear), output.exposure, output.tone_map);
    switch (format) {
        case ImageFormat::png:
            return write_png(path, linear);
        case ImageFormat::jpg:
            return write_jpg(path, linear, output.jpeg_quality);
        case ImageFormat::hdr:
            return write_hdr(path, linear);
        case ImageFormat::pfm:
            return write_pfm(path, linear);
        case ImageFormat::exr:
            return write_exr(path, linear, output.exr_pixel, output.metadata);
    }
}

void save_srgb8(const std::filesystem::path& path, std::span<const std::uint8_t> rgb, int width,
                int height, int jpeg_quality) {
    const ImageFormat format = image_format(path);
    if (is_linear(format))
        throw InputError(path.string() +
                         ": an image as shown is 8-bit sRGB: save it as .png or "
                         ".jpg (the linear radiance can be saved as .hdr, .pfm or .exr)");
    create_parent_folders(path);
    if (format == ImageFormat::jpg)
        write_jpg_rgb8(path, rgb, width, height, jpeg_quality);
    else
        write_png_rgb8(path, rgb, width, height);
}

Image load_image(const std::filesystem::path& path) {
    const ImageFormat format = image_format(path);
    check_input_file(path, "image", kMaxImageFileBytes);  // the decoders would wait on a FIFO
    switch (format) {
        case ImageFormat::png:
        case ImageFormat::jpg:
            return read_png(path);
        case ImageFormat::hdr:
            return read_hdr(path);
        case ImageFormat::pfm:
            return read_pfm(path);
        case ImageFormat::exr:
            return read_exr(path);
    }
    return {};
}

std::uint64_t save_image_bytes_per_pixel(ImageFormat format) {
    switch (format) {
        case ImageFormat::png:  // 8-bit pixels, stb's filtered rows, stream and final copy
        case ImageFormat::jpg:
            return 4 * 3;
        case ImageFormat::hdr:  // the clamped floats and the RGBE stream
            return 3 * 4 + 4;
        case ImageFormat::pfm:  // written straight from the image
            return 0;
        case ImageFormat::exr:  // the stream in memory (at most raw floats and line tables),
            return 3 * 4 + 1;   // or the half copy and a stream of half that size
    }
    return 0;
}

}  // namespace edacrt
