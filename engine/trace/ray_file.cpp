#include "trace/ray_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "util/error.h"
#include "util/output_file.h"

namespace edacrt {
namespace {

static_assert(std::endian::native == std::endian::little, "ray files are little-endian");

template <typename Record>
std::vector<Record> read_records(const std::filesystem::path& path, const char* what) {
    // Only a regular file has a size to trust: a directory "opens" with a size of 2^63 - 1
    // and a device such as /dev/zero reports 0 bytes.
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    // A stat error other than "not found" (a symlink loop) says more than the open would.
    if (status.type() == std::filesystem::file_type::none && ec)
        throw InputError(path.string() + ": cannot open " + what + " file (" + ec.message() + ")");
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw InputError(path.string() + ": not a regular file (a " + what +
                         " file must be a file of known size)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open " + what + " file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path.string() + ": cannot read the size (" + ec.message() + ")");
    if (size % sizeof(Record) != 0)
        throw InputError(path.string() + ": size " + std::to_string(size) +
                         " bytes is not a multiple of the " + std::to_string(sizeof(Record)) +
                         "-byte " + what + " record");
    std::vector<Record> records(std::size_t(size) / sizeof(Record));
    if (!in.read(reinterpret_cast<char*>(records.data()), std::streamsize(size)))
        throw InputError(path.string() + ": read error");
    return records;
}

template <typename Record>
void write_records(const std::filesystem::path& path, std::span<const Record> records,
                   const char* what) {
    OutputFile file(path, std::string(what) + " file");
    file.write(records.data(), records.size_bytes());
    file.close();
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

std::string validate_ray(const Ray& ray) {
    if (!finite(ray.org)) return "non-finite (NaN or inf) origin";
    if (!finite(ray.dir)) return "non-finite (NaN or inf) direction";
    // A direction below the normal range would overflow the reciprocals the tests precompute.
    const float longest = std::max({std::abs(ray.dir.x), std::abs(ray.dir.y), std::abs(ray.dir.z)});
    if (longest < std::numeric_limits<float>::min()) return "zero-length (or denormal) direction";
    // t counts lengths of the direction, so a short one makes every distance a huge t, and its
    // other components denormal: near 2e-38 the box tests' reciprocals overflow and the methods
    // disagree (tested down to 1e-30). Such a ray is the same ray with a longer direction.
    if (longest < kShortestDirection) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "direction too short (longest component %.3g, below 2^-64 = 5.4e-20): scale "
                      "it up, and tmin and tmax down by the same factor",
                      double(longest));
        return text;
    }
    if (std::isnan(ray.tmin) || std::isnan(ray.tmax)) return "NaN tmin or tmax";
    if (!(ray.tmin <= ray.tmax)) return "tmin greater than tmax";
    return {};
}

std::vector<Ray> read_rays(const std::filesystem::path& path) {
    std::vector<Ray> rays = read_records<Ray>(path, "ray");
    for (std::size_t i = 0; i < rays.size(); ++i)
        if (const std::string problem = validate_ray(rays[i]); !problem.empty())
            throw InputError(path.string() + ": ray " + std::to_string(i) + ": " + problem);
    return rays;
}

void write_rays(const std::filesystem::path& path, std::span<const Ray> rays) {
    write_records(path, rays, "ray");
}

std::vector<Hit> read_hits(const std::filesystem::path& path) {
    return read_records<Hit>(path, "hit");
}

void write_hits(const std::filesystem::path& path, std::span<const Hit> hits) {
    write_records(path, hits, "hit");
}

}  // namespace edacrt
