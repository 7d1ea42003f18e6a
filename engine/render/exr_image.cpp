#include "render/exr_image.h"

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "util/error.h"
#include "util/output_file.h"

namespace edacrt {
namespace {

/// OpenEXR seeks back to write its offset table, so the file is built in memory and then
/// written through OutputFile, which checks every write and the close.
class MemoryStream : public Imf::OStream {
  public:
    MemoryStream(const std::filesystem::path& path, std::size_t expected)
        : Imf::OStream(path.c_str()) {
        bytes_.reserve(expected);  // no doubling on the way: save_image_bytes_per_pixel()
    }
    void write(const char c[], int n) override {
        if (position_ + std::size_t(n) > bytes_.size()) bytes_.resize(position_ + std::size_t(n));
        std::copy(c, c + n, bytes_.begin() + std::ptrdiff_t(position_));
        position_ += std::size_t(n);
    }
    std::uint64_t tellp() override { return position_; }
    void seekp(std::uint64_t position) override { position_ = position; }
    const std::string& bytes() const { return bytes_; }

  private:
    std::string bytes_;
    std::size_t position_ = 0;
};

// The largest side read_exr accepts, as for PFM: a corrupt header must not allocate terabytes.
constexpr int kMaxSide = 65536;

}  // namespace

void write_exr(const std::filesystem::path& path, const Image& image, ExrPixel pixel,
               const ImageMetadata& metadata) {
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "pixels are read with a 12-byte stride");
    Imf::Header header(image.width, image.height);
    for (const auto& [name, value] : metadata) {
        if (header.find(name) != header.end())
            throw std::invalid_argument("write_exr: '" + name + "' is a reserved EXR attribute");
        header.insert(name, Imf::StringAttribute(value));
    }
    // OpenEXR converts only on input, so half channels are read from a half copy.
    std::vector<half> halves;
    if (pixel == ExrPixel::half) {
        halves.resize(image.pixels.size() * 3);
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) halves[3 * i + std::size_t(c)] = half(image.pixels[i][c]);
    }
    const Imf::PixelType type = pixel == ExrPixel::half ? Imf::HALF : Imf::FLOAT;
    const std::size_t bytes = pixel == ExrPixel::half ? sizeof(half) : sizeof(float);
    char* base = pixel == ExrPixel::half
                     ? reinterpret_cast<char*>(halves.data())
                     : const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data()));
    Imf::FrameBuffer frame;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(type));
        frame.insert(names[c], Imf::Slice(type, base + std::size_t(c) * bytes, 3 * bytes,
                                          3 * bytes * std::size_t(image.width)));
    }
    // Raw pixels, a chunk offset and header per 16 lines (ZIP), and room for the header.
    const std::size_t raw = image.pixels.size() * 3 * (pixel == ExrPixel::half ? 2 : 4);
    MemoryStream stream(path, raw + std::size_t(image.height) + 65536);
    try {
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        throw InputError(path.string() + ": cannot encode OpenEXR (" + e.what() + ")");
    }
    write_file(path, stream.bytes(), "OpenEXR");
}

Image read_exr(const std::filesystem::path& path, ImageMetadata* metadata) {
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        const Imath::Box2i window = header.dataWindow();
        const long long width = (long long)window.max.x - window.min.x + 1;
        const long long height = (long long)window.max.y - window.min.y + 1;
        if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide)
            throw InputError(path.string() + ": OpenEXR data window of " + std::to_string(width) +
                             "x" + std::to_string(height) + " pixels (1 to " +
                             std::to_string(kMaxSide) + " per side are read)");
        const Imf::ChannelList& channels = header.channels();
        const bool rgb =
            channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
        if (!rgb && !channels.findChannel("Y"))
            throw InputError(path.string() + ": OpenEXR without R, G, B or Y channels");
        Image image{int(width), int(height)};
        Imf::FrameBuffer frame;
        char* base = reinterpret_cast<char*>(image.pixels.data());
        const char* names[3] = {"R", "G", "B"};
        for (int c = 0; c < (rgb ? 3 : 1); ++c)
            frame.insert(
                rgb ? names[c] : "Y",
                Imf::Slice::Make(Imf::FLOAT, base + c * sizeof(float), window, sizeof(glm::vec3),
                                 sizeof(glm::vec3) * std::size_t(width)));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        if (!rgb)
            for (glm::vec3& p : image.pixels) p = glm::vec3(p.x);
        if (metadata)
            for (auto it = header.begin(); it != header.end(); ++it)
                if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                    metadata->emplace_back(it.name(), text->value());
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(path.string() + ": cannot read OpenEXR (" + e.what() + ")");
    }
}

}  // namespace edacrt
