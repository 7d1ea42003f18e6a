#include "trace/ray_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "util/error.h"

namespace edacrt {
namespace {

std::filesystem::path temp_file(const std::string& name) {
    return std::filesystem::temp_directory_path() /
           ("edacrt_" + std::to_string(::getpid()) + "_" + name);
}

std::string error_of(const std::filesystem::path& path) {
    try {
        read_rays(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(RayFile, RoundTripsRaysAndHits) {
    const std::vector<Ray> rays = {{{1, 2, 3}, {0, 0, -1}, 0.5f, 10.0f},
                                   {{-1, 0, 0}, {1, -0.0f, 0}, 0.0f, kInfinity}};
    const auto ray_path = temp_file("rays.bin");
    write_rays(ray_path, rays);
    EXPECT_EQ(std::filesystem::file_size(ray_path), 64u);
    const std::vector<Ray> back = read_rays(ray_path);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(std::memcmp(back.data(), rays.data(), 64), 0);

    const std::vector<Hit> hits = {{1.5f, 3, 0.25f, 0.5f}, {}};
    const auto hit_path = temp_file("hits.bin");
    write_hits(hit_path, hits);
    const std::vector<Hit> hits_back = read_hits(hit_path);
    ASSERT_EQ(hits_back.size(), 2u);
    EXPECT_EQ(hits_back[0].prim, 3);
    EXPECT_EQ(hits_back[1].prim, -1);
    EXPECT_EQ(hits_back[1].t, kInfinity);
    std::filesystem::remove(ray_path);
    std::filesystem::remove(hit_path);
}

TEST(RayFile, RejectsTruncatedFiles) {
    const auto path = temp_file("truncated.bin");
    std::ofstream(path, std::ios::binary) << std::string(33, '\0');
    EXPECT_NE(error_of(path).find("not a multiple of the 32-byte ray record"), std::string::npos);
    std::filesystem::remove(path);
}

TEST(RayFile, RejectsInvalidRaysNamingTheRay) {
    const auto path = temp_file("bad.bin");
    const auto expect_error = [&](const Ray& bad, const std::string& what) {
        write_rays(path, std::vector<Ray>{{{0, 0, 0}, {0, 0, 1}}, bad});
        const std::string message = error_of(path);
        EXPECT_NE(message.find("ray 1: " + what), std::string::npos) << message;
    };
    expect_error({{NAN, 0, 0}, {0, 0, 1}}, "non-finite (NaN or inf) origin");
    expect_error({{kInfinity, 0, 0}, {0, 0, 1}}, "non-finite (NaN or inf) origin");
    expect_error({{0, 0, 0}, {0, NAN, 1}}, "non-finite (NaN or inf) direction");
    expect_error({{0, 0, 0}, {0, 0, 0}}, "zero-length");
    expect_error({{0, 0, 0}, {0, -0.0f, 1e-45f}}, "zero-length");
    expect_error({{0, 0, 0}, {2e-38f, -1e-39f, 0}}, "direction too short (longest component 2e-38");
    expect_error({{0, 0, 0}, {0, 5e-20f, 0}}, "direction too short");
    expect_error({{0, 0, 0}, {0, 0, 1}, NAN, 1.0f}, "NaN tmin or tmax");
    expect_error({{0, 0, 0}, {0, 0, 1}, 2.0f, 1.0f}, "tmin greater than tmax");
    std::filesystem::remove(path);
}

TEST(RayFile, MissingFileIsAnError) {
    EXPECT_NE(error_of("/no/such/rays.bin").find("cannot open ray file"), std::string::npos);
}

TEST(RayFile, OnlyRegularFilesAreRead) {
    // A directory "opens" with a size of 2^63 - 1; /dev/zero reports 0 bytes (no rays).
    for (const std::filesystem::path& path :
         {std::filesystem::temp_directory_path(), std::filesystem::path("/dev/zero")}) {
        const std::string message = error_of(path);
        EXPECT_NE(message.find(path.string() + ": not a regular file"), std::string::npos)
            << message;
    }
}

TEST(RayFile, WriteErrorsAreReported) {
    // /dev/full accepts the open and fails the write, here at the final flush.
    const std::vector<Ray> rays(2);
    const std::vector<Hit> hits(1);
    const auto message = [](const auto& write) -> std::string {
        try {
            write();
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_EQ(message([&] { write_rays("/dev/full", rays); }),
              "/dev/full: cannot write ray file (No space left on device)");
    EXPECT_EQ(message([&] { write_hits("/dev/full", hits); }),
              "/dev/full: cannot write hit file (No space left on device)");
    EXPECT_EQ(message([&] { write_rays("/no/such/dir/rays.bin", rays); }),
              "/no/such/dir/rays.bin: cannot create ray file (No such file or directory)");
}

}  // namespace
}  // namespace edacrt
