// Reads with a bound: a FIFO, a device or a directory is refused without blocking, a file over
// its cap is refused with its size, deep JSON is refused before it can overflow the stack,
// and a message quotes a bad value only in part, escaped. (Every reader against such files:
// special_files_test.cpp.)
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "input_error.h"
#include "sanitizers.h"
#include "scene/obj_loader.h"
#include "scene/rigid_animation.h"
#include "temp_dir.h"
#include "util/error.h"
#include "util/input_file.h"
#include "util/json_limits.h"

namespace edacrt {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

using test::error_of;  // "" when nothing is thrown: every check below then fails

fs::path make_fifo(const TempDir& dir, const std::string& name) {
    const fs::path path = dir.path() / name;
    EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
    return path;
}

TEST(InputFile, ReadsARegularFileWhole) {
    const TempDir dir;
    const std::string text = "{\"a\": 1}\n" + std::string(100000, ' ');
    EXPECT_EQ(read_text_file(dir.write("a.json", text), "test file"), text);
    EXPECT_EQ(read_text_file(dir.write("empty", ""), "test file"), "");
}

TEST(InputFile, RefusesFifosDevicesAndDirectoriesWithoutBlocking) {
    const TempDir dir;
    const auto start = std::chrono::steady_clock::now();
    const fs::path fifo = make_fifo(dir, "fifo.json");
    EXPECT_NE(
        error_of([&] { read_text_file(fifo, "test file"); }).find("not a regular file (a FIFO)"),
        std::string::npos);
    EXPECT_NE(error_of([&] { read_text_file("/dev/zero", "test file"); }).find("a device"),
              std::string::npos);
    EXPECT_NE(error_of([&] { read_text_file(dir.path(), "test file"); }).find("a directory"),
              std::string::npos);
    EXPECT_NE(error_of([&] {
                  read_text_file(dir.path() / "none", "test file");
              }).find("cannot read test file (No such file or directory)"),
              std::string::npos);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(InputFile, RefusesAFileOverItsCapWithItsSize) {
    const TempDir dir;
    const fs::path big = dir.write("big.json", std::string(5000, 'x'));
    EXPECT_EQ(check_input_file(big, "test file", 5000), 5000u);
    EXPECT_NE(error_of([&] {
                  read_text_file(big, "test file", 4999);
              }).find("test file of 5000 bytes is larger than the 4999 bytes read"),
              std::string::npos);
    // A /proc file reports no size: the read itself stops at the cap.
    EXPECT_NE(
        error_of([] { read_text_file("/proc/self/maps", "test file", 16); }).find("more than 16"),
        std::string::npos);
}

// A huge OBJ: a binary one (all NUL, sparse) is refused from its first block, not read whole
// first (3 GB took 19 s); one larger than the memory fails naming the file, not with
// "out of memory" or "std::bad_alloc".
TEST(InputFile, AHugeObjIsRefusedNamingTheFile) {
    const TempDir dir;
    const fs::path zeros = dir.path() / "zeros.obj";
    std::ofstream(zeros).close();
    fs::resize_file(zeros, 4ull << 30);  // sparse: no disk used
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(
        error_of([&] { load_obj(zeros); }),
        zeros.string() + ": cannot read OBJ file (line 1: NUL byte; this is not a text file)");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));

    // A text start and then more than the address space allowed here (ASan reserves terabytes
    // of address space: no limit can be set under it).
    if (test::kSanitized) return;
    std::string text;
    while (text.size() < (1 << 17)) text += "v 0 0 0\n";  // past the first block read
    const fs::path big = dir.write("big.obj", text);
    fs::resize_file(big, 64ull << 30);
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_AS, &old), 0);
    rlimit limit = old;
    limit.rlim_cur = std::min<rlim_t>(old.rlim_cur, 16ull << 30);
    ASSERT_EQ(::setrlimit(RLIMIT_AS, &limit), 0);
    const std::string message = error_of([&] { load_obj(big); });
    ::setrlimit(RLIMIT_AS, &old);
    EXPECT_EQ(message, big.string() +
                           ": cannot read OBJ file (68719476736 bytes, more than the "
                           "memory can hold)");
}

TEST(JsonLimits, DepthIsCountedOutsideStrings) {
    EXPECT_NO_THROW(check_json_depth(std::string(64, '[') + std::string(64, ']'), "f"));
    EXPECT_NO_THROW(check_json_depth("[\"" + std::string(100, '[') + "\\\"[\"]", "f", 2));
    EXPECT_EQ(error_of([] { check_json_depth("{\"a\":\n  [[[1]]]}", "f.json", 3); }),
              "f.json:2:5: JSON nested deeper than 3 levels");
    EXPECT_EQ(shorten(std::string(100, 'a'), 10), "aaaaaaaaaa...");
    EXPECT_EQ(shorten("short", 10), "short");
}

TEST(JsonLimits, DeepAnimationFileIsRefusedWithItsPosition) {
    const TempDir dir;
    // Valid JSON: the parser takes it, and the message for the bad "eye" dumped it recursively.
    const std::string prefix =
        R"({"objects": [{"mesh": "builtin:cornell"}], "camera": {"look_at": [0, 0, 0], "eye": )";
    const fs::path file = dir.write(
        "deep.anim.json", prefix + std::string(60000, '[') + std::string(60000, ']') + "}}");
    // The camera object is at depth 2, so the 63rd '[' is the 65th level.
    EXPECT_EQ(error_of([&] { load_rigid_animation(file); }),
              file.string() + ":1:" + std::to_string(prefix.size() + 63) +
                  ": JSON nested deeper than 64 levels");
    // Deep but inside the limit, and wrong: the message quotes the value in part.
    const fs::path nested = dir.write("nested.anim.json",
                                      "{\"objects\": [{\"mesh\": \"builtin:cornell\", \"keys\": "
                                      "[{\"time\": " +
                                          std::string(50, '[') + std::string(50, ']') + "}]}]}");
    const std::string message = error_of([&] { load_rigid_animation(nested); });
    EXPECT_NE(message.find("expected a number, got [[[["), std::string::npos) << message;
    EXPECT_LT(message.size(), 300u) << message;
}

TEST(JsonLimits, AnAnimationErrorQuotesALongValueInPart) {
    const TempDir dir;
    const std::string huge(600000, 'x');
    const fs::path file =
        dir.write("long.anim.json",
                  "{\"objects\": [{\"mesh\": \"builtin:cornell\", \"keys\": [{\"time\": \"" + huge +
                      "\", \"" + huge + "\": 1}]}]}");
    const std::string message = error_of([&] { load_rigid_animation(file); });
    EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
    EXPECT_NE(message.find("..."), std::string::npos) << message.substr(0, 400);
    // A syntax error in a long string quotes the string in part too.
    const fs::path broken = dir.write("broken.anim.json", "{\"objects\": \"" + huge + "\u0001\"}");
    const std::string syntax = error_of([&] { load_rigid_animation(broken); });
    EXPECT_NE(syntax.find("not valid JSON"), std::string::npos) << syntax.substr(0, 400);
    EXPECT_LT(syntax.size(), 600u) << syntax.substr(0, 400);
}

TEST(JsonLimits, MessagesQuoteNamesAndValuesEscaped) {
    // Found by animation_fuzzer: a field or mesh name holds any character ("\u0001" in the
    // file), and nlohmann's dump() and parse errors escape controls only below 0x20.
    const TempDir dir;
    const auto message = [&](const std::string& text) {
        return error_of([&] { load_rigid_animation(dir.write("a.anim.json", text)); });
    };
    const auto printable = [](const std::string& text) {
        for (const char c : text)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
        return true;
    };
    const std::string field = message(R"({"objects": [], "x\u0001\u001b[2J": 1})");
    EXPECT_NE(field.find("unknown field 'x\\x01\\x1B[2J'"), std::string::npos) << field;
    const std::string mesh = message(R"({"objects": [{"mesh": "a\u0007.obj"}]})");
    EXPECT_NE(mesh.find("a\\x07.obj"), std::string::npos) << mesh;
    const std::string value = message(
        "{\"objects\": [{\"mesh\": \"builtin:cube\", \"keys\": "
        "[{\"time\": \"\x7f\xc2\x85\"}]}]}");
    EXPECT_NE(value.find("expected a number, got \"\\x7F\\xC2\\x85\""), std::string::npos) << value;
    const std::string syntax = message("{\"objects\": \x7f}");
    EXPECT_NE(syntax.find("not valid JSON"), std::string::npos) << syntax;
    for (const std::string& m : {field, mesh, value, syntax}) EXPECT_TRUE(printable(m)) << m;
}

}  // namespace
}  // namespace edacrt
