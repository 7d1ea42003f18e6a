// libFuzzer target for the OBJ and MTL parsers. The input is an OBJ text, optionally followed by
// a NUL byte and an MTL text (both parsers reject NUL, so the split loses nothing): the MTL text
// is parsed on its own and served to every `mtllib` line. Each parse must return a scene that
// satisfies the Scene invariants or throw InputError with a short, printable message; a crash,
// a sanitizer report, a hang or any other exception is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/mtl_loader.h"
#include "scene/obj_loader.h"
#include "scene_invariants.h"
#include "util/error.h"

namespace {

using namespace edacrt;

[[noreturn]] void fail(const char* what, const std::string& detail) {
    std::fprintf(stderr, "obj_fuzzer: %s: %s\n", what, detail.c_str());
    __builtin_trap();
}

/// An error or warning stays short and quotes input only escaped (issue 9, section 4:
/// garbage must not garble the terminal).
void check_message(const std::string& message) {
    if (message.size() > 1000) fail("message too long", message);
    for (const char c : message)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            fail("control byte in message", message);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    const std::size_t split = input.find('\0');
    const std::string_view obj = input.substr(0, split);
    const std::optional<std::string> mtl =
        split == std::string_view::npos ? std::nullopt
                                        : std::optional<std::string>(input.substr(split + 1));
    try {
        if (mtl) {
            std::vector<std::string> warnings;
            try {
                for (const Material& m : parse_mtl(*mtl, "fuzz.mtl", warnings))
                    if (const std::string why = test::material_violation(m); !why.empty())
                        fail("parse_mtl", why);
                for (const std::string& warning : warnings) check_message(warning);
            } catch (const InputError& e) {
                check_message(e.what());
                if (!std::string_view(e.what()).starts_with("fuzz.mtl:"))
                    fail("error does not name its source", e.what());
            }
        }
        // Like a file system, which cannot open names longer than NAME_MAX.
        const MtlReader read_mtl = [&](const std::string& name) {
            return name.size() <= 255 ? mtl : std::nullopt;
        };
        try {
            const Scene scene = parse_obj(obj, "fuzz.obj", read_mtl);
            if (const std::string why = test::scene_violation(scene); !why.empty())
                fail("parse_obj", why);
            for (const std::string& warning : scene.warnings) check_message(warning);
        } catch (const InputError& e) {
            check_message(e.what());  // names fuzz.obj, or the mtllib name for a library's errors
        }
    } catch (const std::exception& e) {
        fail("unexpected exception", e.what());
    }
    return 0;
}
