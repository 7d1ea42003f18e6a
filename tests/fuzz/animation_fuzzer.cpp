// libFuzzer target for animation files (scene/rigid_animation.h, through util/json_limits.h's
// parse_json): the input is the text of an animation file, written to a temporary folder that
// also holds the meshes a file may name (small OBJ files, one with an MTL library, broken
// ones, and a FIFO, a directory, a symlink loop and /dev/zero under .obj names). A load returns
// a scene that satisfies the Scene invariants, whose frames at a few times are finite or refused
// with InputError; otherwise it throws InputError with a short message without control bytes.
// A crash, a sanitizer report, a hang, an allocation beyond libFuzzer's limit or any other
// exception is a bug.
//
// Inputs that name other meshes are skipped: an absolute path or ".." could read any file on
// the machine, and builtin:sphere:subdiv=9 makes 5M triangles (the builtin parser is not what
// this fuzzer tests).
#include <sys/stat.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <string_view>

#include "scene/rigid_animation.h"
#include "scene_invariants.h"
#include "temp_dir.h"
#include "util/error.h"
#include "util/json_limits.h"

namespace {

using namespace edacrt;
namespace fs = std::filesystem;

[[noreturn]] void fail(const char* what, const std::string& detail) {
    std::fprintf(stderr, "animation_fuzzer: %s: %s\n", what, detail.c_str());
    __builtin_trap();
}

/// An error or warning stays short and quotes input only escaped (the CLI escapes what it
/// prints, but the viewer and other callers show messages as they are).
void check_message(const std::string& message) {
    if (message.size() > 1000) fail("message too long", message);
    for (const char c : message)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            fail("control byte in message", message);
}

/// The folder of the animation file and its meshes; removed at exit.
const test::TempDir& folder() {
    static const test::TempDir dir;
    static const bool filled = [](const test::TempDir& d) {
        d.write("tri.obj",
                "mtllib materials.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
                "f 1//1 2//1 3//1\n");
        d.write("materials.mtl", "newmtl red\nKd 1 0 0\n");
        d.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n");
        d.write("missing-material.obj",
                "mtllib none.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n");
        d.write("bad.obj", "v 0 0 0\nf 1 2 3\n");
        d.write("empty.obj", "# nothing\n");
        fs::create_directories(d.path() / "sub");
        d.write("sub/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        fs::create_directories(d.path() / "dir.obj");
        ::mkfifo((d.path() / "fifo.obj").c_str(), 0600);
        fs::create_symlink("loop.obj", d.path() / "loop.obj");
        fs::create_symlink("/dev/zero", d.path() / "zero.obj");
        return true;
    }(dir);
    (void)filled;
    return dir;
}

/// Whether the loader may open `mesh`: a builtin small enough, or a name inside the folder.
bool allowed_mesh(const std::string& mesh) {
    if (mesh.starts_with("builtin:")) {
        static const std::regex small(
            "builtin:(cornell|cube(:n=[1-8])?|sphere(:subdiv=[0-3])?|soup(:count=[1-9])?)");
        return std::regex_match(mesh, small);
    }
    const fs::path path(mesh);
    if (path.has_root_path()) return false;
    for (const fs::path& part : path)
        if (part == "..") return false;
    return mesh.find('\0') == std::string::npos;
}

/// False when the text parses and some object names a mesh allowed_mesh() refuses.
bool meshes_allowed(std::string_view text) {
    nlohmann::json root;
    try {
        root = parse_json(text, "check");
    } catch (const InputError&) {
        return true;  // the loader refuses it before any mesh
    }
    if (!root.is_object() || !root.contains("objects") || !root["objects"].is_array()) return true;
    for (const nlohmann::json& object : root["objects"])
        if (object.is_object() && object.contains("mesh") && object["mesh"].is_string() &&
            !allowed_mesh(object["mesh"].get<std::string>()))
            return false;
    return true;
}

void check_animation(AnimatedScene& animated) {
    Scene& scene = animated.scene;
    if (const std::string why = test::scene_violation(scene); !why.empty())
        fail("load_rigid_animation", why);
    for (const std::string& warning : scene.warnings) check_message(warning);
    if (!animated.animation) fail("load_rigid_animation", "no animation");
    const double duration = animated.animation->duration();
    if (!(duration >= 0.0 && std::isfinite(duration))) fail("duration", std::to_string(duration));
    for (const double t : {0.0, duration / 3.0, duration, duration + 1.0, -1.0}) {
        try {
            animated.animation->frame(t, scene);
        } catch (const InputError& e) {
            check_message(e.what());
            return;  // the scene is partly written
        }
        if (const std::string why = test::scene_violation(scene); !why.empty())
            fail("frame", why + " at t = " + std::to_string(t));
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    folder();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    if (!meshes_allowed(text)) return 0;
    const fs::path file = folder().write("anim.json", text);
    try {
        AnimatedScene animated = load_rigid_animation(file);
        check_animation(animated);
    } catch (const InputError& e) {
        check_message(e.what());
    } catch (const std::exception& e) {
        fail("unexpected exception", e.what());
    }
    return 0;
}
