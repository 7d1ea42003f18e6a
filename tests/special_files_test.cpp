// Every file the engine and the command line read, given something that is not a regular file:
// a FIFO (no writer: an open or read would wait forever), a directory, /dev/zero (endless),
// /dev/null (empty, size 0) or a symlink loop. Each must fail at once with an error that names
// the file and says what it is. (read_text_file itself is tested in input_limits_test.cpp, the
// viewer's files in viewer_files_test.cpp.)
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "render/image_format.h"
#include "scene/animation.h"
#include "scene/obj_loader.h"
#include "scene/rigid_animation.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "trace/ray_file.h"
#include "util/error.h"

namespace edacrt {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

/// One kind of non-regular file, under a name with the extension a reader expects (readers
/// such as load_image choose by extension, so devices are reached through symlinks).
struct Special {
    std::string kind;     // for failure messages
    fs::path path;        // what the reader is given
    std::string because;  // what the error must say
};

std::vector<Special> make_specials(const TempDir& dir, const std::string& ext) {
    const fs::path fifo = dir.path() / ("fifo" + ext), folder = dir.path() / ("dir" + ext);
    const fs::path zero = dir.path() / ("zero" + ext), null = dir.path() / ("null" + ext);
    const fs::path loop = dir.path() / ("loop" + ext);
    EXPECT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    fs::create_directory(folder);
    fs::create_symlink("/dev/zero", zero);
    fs::create_symlink("/dev/null", null);
    fs::create_symlink(loop.filename(), loop);
    return {{"a FIFO", fifo, "not a regular file"},
            {"a directory", folder, "not a regular file"},
            {"/dev/zero", zero, "not a regular file"},
            {"/dev/null", null, "not a regular file"},
            {"a symlink loop", loop, "Too many levels of symbolic links"}};
}

/// The message of the InputError `read` throws, or what went wrong instead. A read still
/// waiting after 10 s fails the test: `fifo` is then opened for writing and closed, so a reader
/// stuck on it sees its end and the test can finish.
std::string error_of(const std::function<void()>& read, const fs::path& fifo) {
    auto result = std::async(std::launch::async, [&]() -> std::string {
        try {
            read();
        } catch (const InputError& e) {
            return e.what();
        } catch (const std::exception& e) {
            return std::string("not an InputError: ") + e.what();
        }
        return "no error";
    });
    if (result.wait_for(std::chrono::seconds(10)) == std::future_status::timeout) {
        for (int attempt = 0;
             result.wait_for(std::chrono::milliseconds(100)) == std::future_status::timeout;
             ++attempt) {
            const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
            if (fd >= 0) ::close(fd);
        }
        return "blocked for 10 s (" + result.get() + ")";
    }
    return result.get();
}

void expect_refused(const std::string& reader, const Special& s, const std::string& message) {
    EXPECT_NE(message.find(s.path.filename().string()), std::string::npos)
        << reader << ", " << s.kind << ": the error does not name the file: " << message;
    EXPECT_NE(message.find(s.because), std::string::npos)
        << reader << ", " << s.kind << ": expected '" << s.because << "' in: " << message;
}

TEST(SpecialFiles, EveryEngineReaderRefusesThemAtOnce) {
    const TempDir dir;
    const struct {
        std::string name, ext;
        bool by_extension;  // refuses /dev/zero by its name alone
        std::function<void(const fs::path&)> read;
    } readers[] = {
        {"OBJ", ".obj", false, [](const fs::path& p) { load_obj(p); }},
        {"ray file", ".bin", false, [](const fs::path& p) { read_rays(p); }},
        {"hit file", ".hits", false, [](const fs::path& p) { read_hits(p); }},
        {"animation", ".json", false, [](const fs::path& p) { load_rigid_animation(p); }},
        {"PNG", ".png", true, [](const fs::path& p) { load_image(p); }},
        {"JPEG", ".jpg", true, [](const fs::path& p) { load_image(p); }},
        {"HDR", ".hdr", true, [](const fs::path& p) { load_image(p); }},
        {"PFM", ".pfm", true, [](const fs::path& p) { load_image(p); }},
        {"EXR", ".exr", true, [](const fs::path& p) { load_image(p); }},
    };
    for (const auto& reader : readers) {
        const std::vector<Special> specials = make_specials(dir, reader.ext);
        const fs::path& fifo = specials[0].path;
        for (const Special& s : specials)
            expect_refused(reader.name, s, error_of([&] { reader.read(s.path); }, fifo));
        if (reader.by_extension) continue;
        for (const char* device : {"/dev/zero", "/dev/null"})
            expect_refused(reader.name, {device, device, "not a regular file"},
                           error_of([&] { reader.read(device); }, fifo));
    }
}

TEST(SpecialFiles, AMaterialLibraryThatIsNotAFileIsAWarning) {
    const TempDir dir;
    for (const Special& s : make_specials(dir, ".mtl")) {
        const fs::path obj = dir.write("uses.obj", "mtllib " + s.path.filename().string() +
                                                       "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        Scene scene;
        EXPECT_EQ(error_of([&] { scene = load_obj(obj); }, s.path), "no error") << s.kind;
        ASSERT_FALSE(scene.warnings.empty()) << s.kind;
        EXPECT_NE(scene.warnings[0].find("cannot read material library '" +
                                         s.path.filename().string() + "'"),
                  std::string::npos)
            << s.kind << ": " << scene.warnings[0];
    }
}

// A key frame of an OBJ sequence that is not a file, in the middle or last: refused by name
// (once the last was silently dropped, and one in the middle read as "is missing").
TEST(SpecialFiles, AKeyFrameThatIsNotAFileIsRefusedByName) {
    const TempDir dir;
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    int n = 0;
    for (const bool last : {false, true})
        for (const Special& s : make_specials(dir, ".obj")) {
            const fs::path folder = dir.path() / ("seq" + std::to_string(n++));
            fs::create_directory(folder);
            std::ofstream(folder / "f_0000.obj") << obj;
            if (!last) std::ofstream(folder / "f_0002.obj") << obj;
            const fs::path frame = folder / "f_0001.obj";
            fs::rename(s.path, frame);
            if (fs::is_symlink(frame) && fs::read_symlink(frame) == s.path.filename()) {
                fs::remove(frame);
                fs::create_symlink(frame.filename(), frame);  // a loop under its new name
            }
            const std::string message = error_of(
                [&] {
                    load_animated_scene("", "sequence:pattern=" + folder.string() + "/f_%04d.obj");
                },
                frame);
            EXPECT_NE(message.find(frame.string()), std::string::npos)
                << s.kind << (last ? " last" : " in the middle") << ": " << message;
            EXPECT_NE(message.find(s.because), std::string::npos)
                << s.kind << (last ? " last" : " in the middle") << ": " << message;
        }
}

TEST(SpecialFiles, EveryCommandRefusesThemAtOnce) {
    const TempDir dir;
    const std::string out = (dir.path() / "out").string();
    fs::create_directory(out);
    write_rays(out + "/one.bin", std::vector<Ray>{Ray{}});
    // Each command with the special file in place of FILE.
    const struct {
        std::string ext, args;
    } commands[] = {
        {".obj", "info FILE"},
        {".obj", "render --scene FILE --width 8 --height 8 --out " + out + "/a.png"},
        {".obj", "trace --scene FILE --rays " + out + "/one.bin --out " + out + "/h.bin"},
        {".obj", "camera-rays --scene FILE --width 8 --height 8 --out " + out + "/r.bin"},
        {".bin", "trace --scene builtin:cube --rays FILE --out " + out + "/h.bin"},
        {".json", "render --animate FILE --width 8 --height 8 --out " + out + "/b.png"},
        {".pfm", "render --scene builtin:cube --width 8 --height 8 --reference FILE --out " + out +
                     "/c.png"},
        {".png", "render --scene builtin:cube --width 8 --height 8 --reference FILE --out " + out +
                     "/d.png"},
    };
    for (const auto& command : commands) {
        for (const Special& s : make_specials(dir, command.ext)) {
            std::string args = command.args;
            args.replace(args.find("FILE"), 4, "'" + s.path.string() + "'");
            const auto start = std::chrono::steady_clock::now();
            // timeout: a command that waits on the FIFO is killed (status 124), not the test.
            const test::CliResult r =
                test::run_command("timeout 10 '" + test::cli_path().string() + "' " + args);
            const std::string what = command.args + " with " + s.kind + ":\n" + r.output;
            EXPECT_EQ(r.exit_code, 1) << what;
            EXPECT_NE(r.output.find("edacrt: error: "), std::string::npos) << what;
            EXPECT_NE(r.output.find(s.path.filename().string()), std::string::npos) << what;
            EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5)) << what;
        }
        for (const auto& entry : fs::directory_iterator(dir.path()))
            if (entry.path().filename() != "out") fs::remove_all(entry.path());  // anew
    }
}

}  // namespace
}  // namespace edacrt
