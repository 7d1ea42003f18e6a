#include "scene/mtl_loader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <string>
#include <system_error>

#include "scene/text_scan.h"
#include "util/error.h"

namespace edacrt {
namespace {

using namespace text_scan;

// MTL has a few dozen keywords in use; many more means garbage, which would otherwise cost a
// warning per line.
constexpr std::size_t kMaxUnmodelledKinds = 64;

class MtlParser {
  public:
    MtlParser(std::string_view text, const std::string& source, std::vector<std::string>& warnings)
        : lines_(text), source_(source), warnings_(warnings) {}

    std::vector<Material> parse() {
        std::string_view line;
        while (lines_.next(line)) parse_line(line);
        if (negative_colours_ > 0)
            warnings_.push_back(
                first_negative_ + ": negative colour components are clamped to 0 (" +
                std::to_string(negative_colours_) +
                (negative_colours_ == 1 ? " statement" : " statements") + " in this file)");
        negative_ns_.finish(warnings_, source_);
        invalid_ni_.finish(warnings_, source_);
        return std::move(materials_);
    }

  private:
    [[noreturn]] void fail(const std::string& what) const { throw InputError(where() + what); }

    std::string where() const { return source_ + ":" + std::to_string(lines_.number()) + ": "; }

    static std::string number_text(float x) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", double(x));
        return text;
    }

    void parse_line(std::string_view line) {
        if (line.find('\0') != std::string_view::npos) {
            fail("NUL byte; this is not a text MTL file");
        }
        line = strip_comment(line);  // "Ka 0.63 0.065 0.05 # Red"
        Tokens tokens(line);
        std::string_view keyword;
        if (!tokens.next(keyword)) return;
        if (!is_keyword(keyword)) fail("unexpected " + quote(keyword) + " (not an MTL statement)");
        if (equals_ignoring_case(keyword, "newmtl")) {
            const std::string_view name = tokens.rest();
            if (name.empty()) fail("newmtl without a material name");
            materials_.emplace_back().name = name;
            return;
        }
        if (materials_.empty()) fail(quote(keyword) + " before any newmtl");
        Material& material = materials_.back();
        const auto is = [&](std::string_view name) { return equals_ignoring_case(keyword, name); };
        if (is("Kd")) {
            material.kd = non_negative_colour(tokens, keyword);
        } else if (is("Ks")) {
            material.ks = non_negative_colour(tokens, keyword);
        } else if (is("Ke")) {
            material.ke = non_negative_colour(tokens, keyword);
        } else if (is("Tf")) {
            material.tf = non_negative_colour(tokens, keyword);
        } else if (is("Ka")) {
            colour(tokens, keyword);  // ambient is not modelled; common enough to accept quietly
        } else if (is("Ns")) {
            material.ns = single_number(tokens, keyword);
            // The BSDF takes a negative exponent as 0 and a non-positive index as glass's 1.5
            // (render/bsdf.cpp): said here, where the line is known.
            if (material.ns < 0.0f)
                negative_ns_.add(warnings_, where() + "Ns " + number_text(material.ns) +
                                                " is negative; 0 is used");
        } else if (is("Ni")) {
            material.ni = single_number(tokens, keyword);
            if (!(material.ni > 0.0f))
                invalid_ni_.add(warnings_, where() + "Ni " + number_text(material.ni) +
                                               " is not a positive index of refraction; 1.5 "
                                               "is used");
        } else if (is("illum")) {
            material.illum = integer(tokens, keyword);
        } else {
            if (is_texture(keyword)) {
                // The file is the last token: options such as "-bm 0.5" come before it.
                std::string_view token, file;
                while (tokens.next(token)) file = token;
                if (!file.empty())
                    material.textures.push_back({std::string(keyword), std::string(file), {}});
                if (is("map_Kd")) return;  // rendered (load_obj decodes it); its options are not
            }
            ignore(keyword);
        }
    }

    /// Texture statements: map_Kd, map_Ks, map_bump, ..., and the bare bump, disp, decal, refl.
    static bool is_texture(std::string_view keyword) {
        if (keyword.size() > 4 && equals_ignoring_case(keyword.substr(0, 4), "map_")) return true;
        for (std::string_view name : {"bump", "disp", "decal", "refl", "norm"})
            if (equals_ignoring_case(keyword, name)) return true;
        return false;
    }

    /// A whole token as a finite float; same rules as the OBJ parser.
    float number(std::string_view token) const {
        float value = 0.0f;
        const NumberStatus status = parse_float(token, value);
        if (status != NumberStatus::ok) fail(describe(status, token));
        return value;
    }

    /// Three numbers, or one for a grey.
    glm::vec3 colour(Tokens& tokens, std::string_view keyword) const {
        float values[3];
        int count = 0;
        std::string_view token;
        while (tokens.next(token)) {
            if (count == 3) fail(quote(keyword) + " needs 1 or 3 numbers, found more");
            values[count++] = number(token);
        }
        if (count == 1) return glm::vec3(values[0]);
        if (count == 3) return glm::vec3(values[0], values[1], values[2]);
        fail(quote(keyword) + " needs 1 or 3 numbers, found " + std::to_string(count));
    }

    /// colour() with negative components clamped to 0: they would make negative radiance.
    /// Counted, and reported once per file with the first place.
    glm::vec3 non_negative_colour(Tokens& tokens, std::string_view keyword) {
        glm::vec3 value = colour(tokens, keyword);
        if (value.x >= 0.0f && value.y >= 0.0f && value.z >= 0.0f) return value;
        if (negative_colours_++ == 0)
            first_negative_ = source_ + ":" + std::to_string(lines_.number()) + ": " +
                              quote(keyword) + " has a negative component";
        return glm::max(value, glm::vec3(0.0f));
    }

    float single_number(Tokens& tokens, std::string_view keyword) const {
        std::string_view token;
        if (!tokens.next(token)) fail(quote(keyword) + " needs a number");
        const float value = number(token);
        if (tokens.next(token)) fail(quote(keyword) + " needs exactly one number");
        return value;
    }

    int integer(Tokens& tokens, std::string_view keyword) const {
        std::string_view token;
        if (!tokens.next(token)) fail(quote(keyword) + " needs an integer");
        int value = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc{} || end != token.data() + token.size()) {
            fail("bad integer " + quote(token) + " after " + quote(keyword));
        }
        if (tokens.next(token)) fail(quote(keyword) + " needs exactly one integer");
        return value;
    }

    /// Reports each unmodelled keyword once, at its first line.
    void ignore(std::string_view keyword) {
        std::string lower(keyword);
        for (char& c : lower) c = to_lower(c);
        for (const std::string& seen : ignored_)
            if (seen == lower) return;
        if (ignored_.size() == kMaxUnmodelledKinds) {
            fail("more than " + std::to_string(kMaxUnmodelledKinds) +
                 " kinds of unknown statement; this does not look like an MTL file");
        }
        ignored_.push_back(std::move(lower));
        warnings_.push_back(source_ + ":" + std::to_string(lines_.number()) + ": MTL feature " +
                            quote(keyword) + " is not modelled (ignored)");
    }

    LineReader lines_;
    const std::string& source_;
    std::vector<std::string>& warnings_;
    std::vector<Material> materials_;
    std::vector<std::string> ignored_;  // lower case
    std::size_t negative_colours_ = 0;  // statements with a negative component
    std::string first_negative_;        // where the first one is, for the warning
    WarningLimit negative_ns_{"negative Ns values"};
    WarningLimit invalid_ni_{"invalid Ni values"};
};

}  // namespace

std::vector<Material> parse_mtl(std::string_view text, const std::string& source_name,
                                std::vector<std::string>& warnings) {
    return MtlParser(text, source_name, warnings).parse();
}

}  // namespace edacrt
