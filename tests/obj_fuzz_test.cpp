// A deterministic mutation fuzzer for the OBJ and MTL parsers: valid texts are mutated at random
// (fixed seeds) and every parse must either return a scene that satisfies the Scene invariants
// or throw InputError. Run under ASan/UBSan in CI, where a crash or an out-of-bounds read fails.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scene/mtl_loader.h"
#include "scene/obj_loader.h"
#include "scene_invariants.h"
#include "test_paths.h"
#include "util/error.h"

namespace edacrt {
namespace {

// Per seed text; the whole test stays under a few seconds in Release and ~30 s under ASan.
constexpr int kIterationsPerSeed = 20000;

const char* const kTokens[] = {"nan",
                               "-nan",
                               "inf",
                               "-0",
                               "0",
                               "-1",
                               "1e39",
                               "1e40",
                               "1e-50",
                               "-1e400",
                               "/",
                               "//",
                               "///",
                               "-99999999999",
                               "99999999999999999999999",
                               "4294967296",
                               "2147483648",
                               "-2147483649",
                               "\r",
                               "\r\n",
                               "\n",
                               " ",
                               "\t",
                               "#",
                               "\\",
                               "+",
                               "-",
                               ".",
                               "e",
                               "v ",
                               "vn ",
                               "vt ",
                               "f ",
                               "usemtl ",
                               "mtllib ",
                               "newmtl ",
                               "Kd ",
                               "illum ",
                               "m.mtl",
                               "red",
                               "\xEF\xBB\xBF",
                               "\xFF"};

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

class Mutator {
  public:
    explicit Mutator(std::uint32_t seed) : rng_(seed) {}

    std::size_t below(std::size_t n) { return n == 0 ? 0 : rng_() % n; }

    /// One to three random edits.
    std::string mutate(std::string text) {
        const std::size_t edits = 1 + below(3);
        for (std::size_t i = 0; i < edits; ++i) edit(text);
        return text;
    }

  private:
    void edit(std::string& text) {
        const std::size_t pos = below(text.size() + 1);
        switch (below(8)) {
            case 0:  // flip a byte
                if (pos < text.size()) text[pos] = static_cast<char>(rng_());
                break;
            case 1:  // delete a few bytes
                text.erase(pos, 1 + below(8));
                break;
            case 2:
            case 3: {  // insert a token
                const std::size_t count = sizeof(kTokens) / sizeof(kTokens[0]);
                text.insert(pos, kTokens[below(count)]);
                break;
            }
            case 4:  // insert a NUL byte
                text.insert(pos, 1, '\0');
                break;
            case 5:  // truncate
                text.resize(pos);
                break;
            case 6:    // duplicate the line at pos
            case 7: {  // or move it to the start (faces before their vertices)
                const std::size_t newline =
                    pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
                const std::size_t start = newline == std::string::npos ? 0 : newline + 1;
                const std::size_t end = std::min(text.find('\n', pos), text.size());
                const std::string line = text.substr(start, end - start) + "\n";
                if (below(2) == 0) {
                    text.insert(start, line);
                } else {
                    text.erase(start, std::min(line.size(), text.size() - start));
                    text.insert(0, line);
                }
                break;
            }
        }
    }

    std::mt19937 rng_;
};

std::string printable(std::string_view text) {
    std::string out;
    for (char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '\n' || (u >= 0x20 && u < 0x7f)) {
            out += c;
        } else {
            constexpr char kHex[] = "0123456789ABCDEF";
            out += "\\x";
            out += kHex[u >> 4];
            out += kHex[u & 15];
        }
    }
    return out;
}

using test::material_violation;
using test::scene_violation;

const std::string kMtl =
    "newmtl red\nKd 1 0 0\nKs 0.1 0.1 0.1\nNs 10\n"
    "newmtl green\nkd 0 1 0\nKe 0 0.5 0\nillum 1\nmap_Kd g.png\n";

std::vector<std::string> obj_seeds() {
    return {
        // A cube of quads with all corner forms.
        "# cube\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 -1\nvn 0 0 1\nvn 1 0 0\n"
        "f 1/1/1 4/2/1 3/3/1 2/1/1\nf 5//2 6//2 7//2 8//2\nf 2/1 3/2 7/3 6/1\n"
        "f 1 5 8 4\nf 4 8 7 3\nf 1 2 6 5\n",
        // Negative indices, an n-gon, CRLF, tabs, groups.
        "o fan\r\ng a\r\nv\t0 0 0\r\nv 2 0 0\r\nv 3 1 0\r\nv 2 2 0\r\nv 0 2 0\r\nv -1 1 0\r\n"
        "s 1\r\nf -6 -5 -4 -3 -2 -1\r\nv 0 0 1\r\nf -7 -1 -6\r\n",
        // Materials, with one usemtl before the mtllib and one undefined name.
        "usemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nmtllib m.mtl\n"
        "usemtl green\nf 1 2 4\nusemtl blue\nf 1 3 4\nusemtl red\nf 2 3 4\n",
        // Degenerate triangles mixed with good ones.
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 1 4\nf 4 2 1 3\n",
        read_text(test::source_dir() / "assets/cornell-box/CornellBox-Original.obj"),
    };
}

TEST(ObjFuzz, ParseObjReturnsAValidSceneOrThrowsInputError) {
    const std::string cornell_mtl =
        read_text(test::source_dir() / "assets/cornell-box/CornellBox-Original.mtl");
    ASSERT_FALSE(cornell_mtl.empty());
    const std::vector<std::string> seeds = obj_seeds();
    int scenes = 0;
    int errors = 0;
    for (std::size_t s = 0; s < seeds.size(); ++s) {
        Mutator mutator(static_cast<std::uint32_t>(1000 + s));
        for (int i = 0; i < kIterationsPerSeed; ++i) {
            // Mostly valid libraries; sometimes a mutated one.
            const bool mutate_mtl = mutator.below(4) == 0;
            const std::string mtl = mutate_mtl ? mutator.mutate(kMtl) : kMtl;
            const std::string cornell = mutate_mtl ? mutator.mutate(cornell_mtl) : cornell_mtl;
            const MtlReader read_mtl = [&](const std::string& name) -> std::optional<std::string> {
                if (name == "m.mtl") return mtl;
                if (name == "CornellBox-Original.mtl") return cornell;
                return std::nullopt;
            };
            const std::string text = mutator.mutate(seeds[s]);
            try {
                const Scene scene = parse_obj(text, "fuzz.obj", read_mtl);
                const std::string why = scene_violation(scene);
                ASSERT_TRUE(why.empty())
                    << why << " (seed " << s << ", iteration " << i << ") for:\n"
                    << printable(text);
                ++scenes;
            } catch (const InputError& e) {
                const std::string_view message = e.what();
                ASSERT_TRUE(message.starts_with("fuzz.obj:") || message.starts_with("m.mtl:") ||
                            message.starts_with("CornellBox-Original.mtl:"))
                    << "an error names its source: " << message;
                ++errors;
            }
        }
    }
    // Both outcomes must be common, or the mutations are too mild or too wild to test much.
    const int total = scenes + errors;
    EXPECT_GT(scenes, total / 10);
    EXPECT_GT(errors, total / 10);
}

TEST(ObjFuzz, ParseMtlReturnsValidMaterialsOrThrowsInputError) {
    const std::vector<std::string> seeds = {
        kMtl, read_text(test::source_dir() / "assets/cornell-box/CornellBox-Original.mtl")};
    int parsed = 0;
    int errors = 0;
    for (std::size_t s = 0; s < seeds.size(); ++s) {
        Mutator mutator(static_cast<std::uint32_t>(2000 + s));
        for (int i = 0; i < kIterationsPerSeed; ++i) {
            const std::string text = mutator.mutate(seeds[s]);
            std::vector<std::string> warnings;
            try {
                for (const Material& m : parse_mtl(text, "fuzz.mtl", warnings)) {
                    const std::string why = material_violation(m);
                    ASSERT_TRUE(why.empty()) << why << " for:\n" << printable(text);
                }
                ++parsed;
            } catch (const InputError& e) {
                ASSERT_EQ(std::string_view(e.what()).substr(0, 9), "fuzz.mtl:") << e.what();
                ++errors;
            }
        }
    }
    const int total = parsed + errors;
    EXPECT_GT(parsed, total / 10);
    EXPECT_GT(errors, total / 10);
}

}  // namespace
}  // namespace edacrt
