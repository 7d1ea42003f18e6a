#include "scene/texture.h"

#include <FreeImage.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <mutex>

#include "util/error.h"

namespace edacrt {
namespace {

/// srgb_to_linear of every 8-bit value.
const std::array<float, 256>& srgb_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double c = i / 255.0;
            t[std::size_t(i)] =
                float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}

/// The index of coordinate `x` (in texels, already offset by the half texel) wrapped into
/// [0, size).
int wrap(long long x, int size) {
    const long long m = x % size;
    return int(m < 0 ? m + size : m);
}

/// What FreeImage reports while this thread decodes (a truncated JPEG or PNG is a message and a
/// partly grey image, not a failed load).
thread_local std::string* decoder_messages = nullptr;

void record_message(FREE_IMAGE_FORMAT, const char* message) {
    if (decoder_messages && message)
        *decoder_messages += (decoder_messages->empty() ? "" : "; ") + std::string(message);
}

struct BitmapDeleter {
    void operator()(FIBITMAP* bitmap) const { FreeImage_Unload(bitmap); }
};
using Bitmap = std::unique_ptr<FIBITMAP, BitmapDeleter>;

}  // namespace

float srgb_to_linear(std::uint8_t encoded) { return srgb_table()[encoded]; }

glm::vec3 Texture::lookup(glm::vec2 uv) const {
    const auto& table = srgb_table();
    // Texel centres at half-integers. The coordinate is first brought into [0, size) so that a
    // huge one cannot overflow the index; wrap() catches what rounding leaves outside.
    const auto coordinate = [](float t, int size, long long& i0, float& f) {
        double x = std::isfinite(t) ? double(t) * size - 0.5 : 0.0;
        x -= std::floor(x / size) * size;  // into [0, size): keeps the fraction of large ones
        const double lo = std::floor(x);
        i0 = (long long)lo;
        f = float(x - lo);
    };
    long long x0, y0;
    float fx, fy;
    coordinate(uv.x, width, x0, fx);
    coordinate(uv.y, height, y0, fy);
    const int xs[2] = {wrap(x0, width), wrap(x0 + 1, width)};
    const int ys[2] = {wrap(y0, height), wrap(y0 + 1, height)};
    const auto texel = [&](int x, int y) {
        const auto& t = texels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        return glm::vec3(table[t[0]], table[t[1]], table[t[2]]);
    };
    const glm::vec3 bottom = (1.0f - fx) * texel(xs[0], ys[0]) + fx * texel(xs[1], ys[0]);
    const glm::vec3 top = (1.0f - fx) * texel(xs[0], ys[1]) + fx * texel(xs[1], ys[1]);
    return (1.0f - fy) * bottom + fy * top;
}

Texture load_texture(const std::string& path) {
    static std::once_flag initialised;  // (FreeImage_Initialise: for a static FreeImage only)
    std::call_once(initialised, [] {
        FreeImage_Initialise(FALSE);
        FreeImage_SetOutputMessage(record_message);
    });
    const auto fail = [&](const std::string& why) {
        throw InputError(path + ": cannot read the texture (" + why + ")");
    };
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) fail("no such file");
    FREE_IMAGE_FORMAT format = FreeImage_GetFileType(path.c_str(), 0);
    if (format == FIF_UNKNOWN) format = FreeImage_GetFIFFromFilename(path.c_str());
    if (format == FIF_UNKNOWN || !FreeImage_FIFSupportsReading(format))
        fail("not a format FreeImage reads, or not readable");
    std::string messages;
    decoder_messages = &messages;
    const Bitmap loaded(FreeImage_Load(format, path.c_str(), 0));
    decoder_messages = nullptr;
    if (!messages.empty()) fail(messages);
    if (!loaded) fail("cannot decode it");
    const Bitmap rgb(FreeImage_ConvertTo24Bits(loaded.get()));
    if (!rgb) fail("its pixel type has no 8-bit RGB form");
    Texture texture;
    texture.width = int(FreeImage_GetWidth(rgb.get()));
    texture.height = int(FreeImage_GetHeight(rgb.get()));
    if (texture.width <= 0 || texture.height <= 0) fail("it has no pixels");
    texture.texels.resize(std::size_t(texture.width) * std::size_t(texture.height));
    // FreeImage's scanline 0 is the image's bottom row, where OBJ's v = 0 is.
    for (int y = 0; y < texture.height; ++y) {
        const BYTE* row = FreeImage_GetScanLine(rgb.get(), y);
        for (int x = 0; x < texture.width; ++x, row += 3)
            texture.texels[std::size_t(y) * std::size_t(texture.width) + std::size_t(x)] = {
                row[FI_RGBA_RED], row[FI_RGBA_GREEN], row[FI_RGBA_BLUE]};
    }
    return texture;
}

}  // namespace edacrt
