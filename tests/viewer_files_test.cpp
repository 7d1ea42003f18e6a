// The viewer's own files: bookmarks keep every entry they can read and never overwrite a file
// they could not (a backup first), a save reports its failure; a script or scene manifest that
// is a FIFO or a directory is refused without blocking.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>

#include "bookmarks.h"
#include "input_error.h"
#include "scene_catalog.h"
#include "script.h"
#include "script_runner.h"
#include "temp_dir.h"
#include "util/error.h"
#include "util/output_file.h"
#include "viewer_jobs.h"

namespace edacrt::app {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

using test::bytes_of;
using test::error_of;

std::string entry(const std::string& name, const std::string& fov = "45") {
    return R"({"name": ")" + name +
           R"(", "eye": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": )" + fov + "}";
}

/// A bookmarks file of `count` entries for builtin:cornell, `bad` spliced in
/// after the first.
std::string bookmarks_file(int count, const std::string& bad = "") {
    std::string list;
    for (int i = 0; i < count; ++i) {
        list += (i ? ", " : "") + entry("view " + std::to_string(i));
        if (i == 0 && !bad.empty()) list += ", " + bad;
    }
    return R"({"version": 1, "scenes": {"builtin:cornell": [)" + list + "]}}\n";
}

TEST(Bookmarks, ABadEntryIsSkippedAndTheOthersKept) {
    const TempDir dir;
    const fs::path file = dir.write("bookmarks.json", bookmarks_file(20, entry("flat", "0")));
    Bookmarks bookmarks;
    const std::vector<std::string> problems = bookmarks.load(file.string());
    EXPECT_EQ(bookmarks.of("builtin:cornell").size(), 20u);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_NE(problems[0].find("scenes[\"builtin:cornell\"][1]: skipped"), std::string::npos)
        << problems[0];
    EXPECT_TRUE(bookmarks.damaged());
}

TEST(Bookmarks, ATrailingCommaIsReadPast) {
    const TempDir dir;
    std::string text = bookmarks_file(20);
    text.insert(text.rfind(']'), ",\n");
    const fs::path file = dir.write("bookmarks.json", text);
    Bookmarks bookmarks;
    const std::vector<std::string> problems = bookmarks.load(file.string());
    EXPECT_EQ(bookmarks.of("builtin:cornell").size(), 20u);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_NE(problems[0].find("trailing commas ignored"), std::string::npos) << problems[0];
}

TEST(Bookmarks, ADamagedFileIsBackedUpBeforeTheFirstSave) {
    const TempDir dir;
    const std::string damaged = bookmarks_file(20) + "garbage";
    const fs::path file = dir.write("bookmarks.json", damaged);
    Bookmarks bookmarks;
    const std::vector<std::string> problems = bookmarks.load(file.string());
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_NE(problems[0].find("not valid JSON"), std::string::npos) << problems[0];
    bookmarks.put("builtin:cornell", {"new", Camera{}});
    EXPECT_EQ(bookmarks.save(file.string()), file.string() + ".bak");
    EXPECT_EQ(bytes_of(file.string() + ".bak"), damaged);
    EXPECT_FALSE(bookmarks.damaged());
    EXPECT_EQ(bookmarks.save(file.string()), "");  // backed up once
    // A later damaged load backs up beside the first backup, not over it.
    dir.write("bookmarks.json", "{");
    EXPECT_EQ(bookmarks.load(file.string()).size(), 1u);
    bookmarks.put("builtin:cornell", {"again", Camera{}});
    EXPECT_EQ(bookmarks.save(file.string()), file.string() + ".bak.1");
    EXPECT_EQ(bytes_of(file.string() + ".bak"), damaged);
    Bookmarks reread;
    EXPECT_TRUE(reread.load(file.string()).empty());
    EXPECT_EQ(reread.of("builtin:cornell").size(), 1u);
}

TEST(Bookmarks, AFailedSaveThrowsAndLeavesTheFile) {
    const TempDir dir;
    const fs::path file = dir.write("bookmarks.json", bookmarks_file(3));
    Bookmarks bookmarks;
    EXPECT_TRUE(bookmarks.load(file.string()).empty());
    bookmarks.put("builtin:cornell", {"new", Camera{}});
    EXPECT_THROW(bookmarks.save("/dev/full"), InputError);
    // The temporary beside the file cannot be made: a 255-byte name plus its suffix.
    const fs::path long_name = dir.write(std::string(250, 'b'), bookmarks_file(3));
    EXPECT_THROW(bookmarks.save(long_name.string()), InputError);
    EXPECT_EQ(bytes_of(long_name), bookmarks_file(3));
}

TEST(Bookmarks, AFifoIsAProblemNotAHang) {
    const TempDir dir;
    const fs::path fifo = dir.path() / "bookmarks.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    Bookmarks bookmarks;
    const std::vector<std::string> problems = bookmarks.load(fifo.string());
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_NE(problems[0].find("a FIFO"), std::string::npos) << problems[0];
    // Neither copied nor replaced.
    EXPECT_THROW(bookmarks.save(fifo.string()), InputError);
}

/// A file-size limit (`ulimit -f`) for one scope, SIGXFSZ ignored as the viewer ignores it, so
/// a write past the limit fails with EFBIG.
class FileSizeLimit {
  public:
    explicit FileSizeLimit(rlim_t bytes) {
        ::getrlimit(RLIMIT_FSIZE, &old_);
        old_signal_ = std::signal(SIGXFSZ, SIG_IGN);
        rlimit limit = old_;
        limit.rlim_cur = bytes;
        ::setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
        ::setrlimit(RLIMIT_FSIZE, &old_);
        std::signal(SIGXFSZ, old_signal_);
    }

  private:
    rlimit old_{};
    void (*old_signal_)(int) = nullptr;
};

// A damaged file is renamed aside, not copied: no size limit or full disk can leave a partial
// backup (an empty .bak once made the next save use .bak.1), and a huge file takes no time.
TEST(Bookmarks, TheBackupIsTheDamagedFileRenamedWhateverItsSize) {
    const TempDir dir;
    const std::string damaged = bookmarks_file(20) + "garbage";
    const fs::path file = dir.write("bookmarks.json", damaged);
    struct stat before {};
    ASSERT_EQ(::stat(file.c_str(), &before), 0);
    Bookmarks bookmarks;
    ASSERT_EQ(bookmarks.load(file.string()).size(), 1u);
    bookmarks.put("builtin:cornell", {"new", Camera{}});
    {
        // The damaged file is larger than the limit; the new one (one bookmark) is not.
        const FileSizeLimit limit(damaged.size() / 2);
        EXPECT_EQ(bookmarks.save(file.string()), file.string() + ".bak");
    }
    struct stat backup {};
    ASSERT_EQ(::stat((file.string() + ".bak").c_str(), &backup), 0);
    EXPECT_EQ(backup.st_ino, before.st_ino);
    EXPECT_EQ(bytes_of(file.string() + ".bak"), damaged);
    EXPECT_FALSE(fs::exists(file.string() + ".bak.1"));

    // A sparse file past the size read (17 MB here; the tester's took minutes at 50 GB).
    const fs::path big = dir.path() / "big.json";
    std::ofstream(big).close();
    fs::resize_file(big, 17u << 20);
    ASSERT_EQ(::stat(big.c_str(), &before), 0);
    Bookmarks of_big;
    ASSERT_EQ(of_big.load(big.string()).size(), 1u);
    EXPECT_EQ(of_big.save(big.string()), big.string() + ".bak");
    ASSERT_EQ(::stat((big.string() + ".bak").c_str(), &backup), 0);
    EXPECT_EQ(backup.st_ino, before.st_ino);
    EXPECT_EQ(backup.st_size, 17 << 20);
}

// When the new file cannot be written the damaged one goes back: no backup is left beside it,
// and the next save backs up to .bak again.
TEST(Bookmarks, AFailedWriteAfterTheBackupRestoresTheDamagedFile) {
    const TempDir dir;
    const std::string damaged = bookmarks_file(1) + "garbage";
    const fs::path file = dir.write("bookmarks.json", damaged);
    Bookmarks bookmarks;
    ASSERT_EQ(bookmarks.load(file.string()).size(), 1u);
    for (int i = 0; i < 40; ++i) bookmarks.put("builtin:cornell", {std::to_string(i), Camera{}});
    {
        const FileSizeLimit limit(1024);  // below forty bookmarks
        EXPECT_THROW(bookmarks.save(file.string()), InputError);
    }
    EXPECT_EQ(bytes_of(file), damaged);
    EXPECT_FALSE(fs::exists(file.string() + ".bak"));
    EXPECT_TRUE(bookmarks.damaged());
    EXPECT_EQ(bookmarks.save(file.string()), file.string() + ".bak");
    EXPECT_EQ(bytes_of(file.string() + ".bak"), damaged);
}

// A backup through a symbolic link moves the file it names and keeps the link.
TEST(Bookmarks, ADamagedFileBehindALinkIsBackedUpBesideItsTarget) {
    const TempDir dir;
    const fs::path target = dir.write("real.json", "{");
    const fs::path link = dir.path() / "bookmarks.json";
    fs::create_symlink(target, link);
    Bookmarks bookmarks;
    ASSERT_EQ(bookmarks.load(link.string()).size(), 1u);
    bookmarks.put("builtin:cornell", {"new", Camera{}});
    EXPECT_EQ(bookmarks.save(link.string()), target.string() + ".bak");
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_EQ(bytes_of(target.string() + ".bak"), "{");
    Bookmarks reread;
    EXPECT_TRUE(reread.load(link.string()).empty());
    EXPECT_EQ(reread.of("builtin:cornell").size(), 1u);
}

// A loop of symbolic links is a file that cannot be read, not a missing one: a warning at load,
// and a save that fails instead of replacing the link with a file.
TEST(Bookmarks, ALoopOfSymbolicLinksIsWarnedAboutAndNotReplaced) {
    const TempDir dir;
    const fs::path a = dir.path() / "a.json";
    const fs::path b = dir.path() / "b.json";
    fs::create_symlink(b, a);
    fs::create_symlink(a, b);
    Bookmarks bookmarks;
    const std::vector<std::string> problems = bookmarks.load(a.string());
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_NE(problems[0].find("symbolic links"), std::string::npos) << problems[0];
    EXPECT_TRUE(bookmarks.unreadable());
    bookmarks.put("builtin:cornell", {"new", Camera{}});
    EXPECT_THROW(bookmarks.save(a.string()), InputError);
    EXPECT_TRUE(fs::is_symlink(a));
    EXPECT_EQ(fs::read_symlink(a), b);
    // Any output refuses a loop (OutputFile), not only bookmarks.
    EXPECT_THROW(write_file(a, "x", "test file"), InputError);
    EXPECT_TRUE(fs::is_symlink(a));
}

// No output of the viewer (layout, write-command, save-view, save-linear, screenshot, bookmarks)
// may replace a file it reads: the scene OBJ, its MTL library, the animation file and the
// meshes it names, the script being run, the bookmarks file; through a link too.
TEST(ViewerFiles, OutputsNeverReplaceTheViewersInputs) {
    const TempDir dir;
    const fs::path mtl = dir.write("box.mtl", "newmtl red\nKd 1 0 0\n");
    const fs::path obj = dir.write("box.obj",
                                   "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                   "usemtl red\nf 1 2 3\n");
    const fs::path animation = dir.write(
        "anim.json", R"({"objects": [{"mesh": "box.obj", "keys": [{"time": 0}, {"time": 1}]}]})");
    const fs::path script = dir.write("script.txt", "quit\n");
    const fs::path bookmarks = dir.write("bookmarks.json", bookmarks_file(1));
    fs::create_symlink(obj, dir.path() / "link.obj");
    ViewerState s;
    s.script_path = script.string();
    s.bookmarks_path = bookmarks.string();
    for (const fs::path& scene : {obj, animation}) {
        load_into(s, scene.string());
        ASSERT_TRUE(s.scene) << s.scene_error;
        for (const fs::path& input : {obj, mtl, script, bookmarks, dir.path() / "link.obj"})
            for (const char* what : {"layout", "write-command", "save-view", "screenshot"}) {
                const std::string error =
                    error_of([&] { check_output_spares_inputs(s, input.string(), what); });
                EXPECT_NE(error.find(": writing it would replace what is read"), std::string::npos)
                    << what << " " << input << ": " << error;
            }
        EXPECT_EQ(error_of([&] {
                      check_output_spares_inputs(s, (dir.path() / "x.png").string(), "save-view");
                  }),
                  "");
    }
    EXPECT_NE(error_of([&] {
                  check_output_spares_inputs(s, animation.string(), "save-linear");
              }).find("save-linear " + animation.string() + " is the scene's input"),
              std::string::npos);
    // The bookmarks file is the one output that may replace itself.
    EXPECT_EQ(error_of([&] { check_output_spares_inputs(s, bookmarks.string(), "bookmarks"); }),
              "");
    // The script's writes fail at their line and leave the file as it was.
    const std::string obj_text = bytes_of(obj);
    for (const std::string verb : {"layout", "write-command"}) {
        ScriptRunner runner(parse_script(verb + " " + obj.string() + "\n", "s"));
        std::string screenshot;
        bool quit = false;
        EXPECT_NE(error_of([&] {
                      runner.step(s, {}, screenshot, quit);
                  }).find("script line 1: " + verb + " " + obj.string() + " is the scene's"),
                  std::string::npos)
            << verb;
        EXPECT_EQ(bytes_of(obj), obj_text);
    }
    s.bookmarks_path = mtl.string();
    const std::string mtl_text = bytes_of(mtl);
    EXPECT_NE(error_of([&] { save_bookmark(s, "front"); }).find("bookmarks not saved: "),
              std::string::npos);
    EXPECT_EQ(bytes_of(mtl), mtl_text);
}

TEST(ViewerFiles, AScriptMustBeARegularFile) {
    const TempDir dir;
    const fs::path fifo = dir.path() / "script.txt";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const fs::path& path : {fifo, dir.path(), fs::path("/dev/zero"), fs::path("/dev/null")}) {
        try {
            load_script(path.string());
            ADD_FAILURE() << path;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos)
                << e.what();
        }
    }
}

TEST(ViewerFiles, AManifestThatIsAFifoFallsBackToTheFolder) {
    const TempDir dir;
    fs::create_directories(dir.path() / "assets");
    fs::create_directories(dir.path() / "scenes/b");
    std::ofstream(dir.path() / "scenes/b/b.obj") << "v 0 0 0\n";
    ASSERT_EQ(::mkfifo((dir.path() / "assets/scenes.json").c_str(), 0600), 0);
    const SceneCatalog catalog = scene_catalog(dir.path() / "assets", dir.path() / "scenes");
    EXPECT_TRUE(std::any_of(catalog.entries.begin(), catalog.entries.end(), [&](const auto& e) {
        return e.path == (dir.path() / "scenes/b/b.obj").string();
    }));
}

/// Polls until the scene being read is taken (at most 60 s).
void finish_loads(ViewerState& s) {
    for (int i = 0; i < 6000 && (s.loading || !s.pending_loads.empty()); ++i) {
        poll_loads(s);
        if (s.loading) s.loading->scene.wait_for(std::chrono::milliseconds(10));
    }
    ASSERT_FALSE(s.loading);
    ASSERT_TRUE(s.pending_loads.empty());
}

// Scenes asked for are read on a thread of their own, one at a time in the order asked, while
// the frames go on with the previous scene; a failed read keeps it and shows the error.
TEST(ViewerFiles, ScenesAreReadOffTheFrameLoopInTheOrderAsked) {
    ViewerState s;
    load_into(s, "builtin:cornell");
    ASSERT_TRUE(s.scene);
    const std::shared_ptr<const Scene> cornell = s.scene;
    const int first = s.scene_number;
    s.pending_loads = {"builtin:sphere:subdiv=2", "/no/such/scene.obj", "builtin:cube:n=2"};
    poll_loads(s);
    ASSERT_TRUE(s.loading);
    EXPECT_EQ(s.loading->spec, "builtin:sphere:subdiv=2");
    EXPECT_EQ(s.pending_loads.size(), 2u);
    EXPECT_EQ(s.scene, cornell) << "the previous scene stays while the next is read";
    // The sphere is taken, then the missing file fails, then the cube is read.
    s.loading->scene.wait();
    poll_loads(s);
    EXPECT_NE(s.scene, cornell);
    EXPECT_EQ(s.scene_path, "builtin:sphere:subdiv=2");
    EXPECT_EQ(s.scene_number, first + 1);
    ASSERT_TRUE(s.loading);
    EXPECT_EQ(s.loading->spec, "/no/such/scene.obj");
    s.loading->scene.wait();
    poll_loads(s);
    EXPECT_NE(s.scene_error.find("/no/such/scene.obj"), std::string::npos) << s.scene_error;
    EXPECT_EQ(s.scene_path, "builtin:sphere:subdiv=2") << "a failed read keeps the scene";
    EXPECT_EQ(s.scene_number, first + 1);
    finish_loads(s);
    EXPECT_EQ(s.scene_path, "builtin:cube:n=2");
    EXPECT_TRUE(s.scene_error.empty()) << "the next load clears the error";
    EXPECT_EQ(s.scene_number, first + 2);
}

}  // namespace
}  // namespace edacrt::app
