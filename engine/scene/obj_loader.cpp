#include "scene/obj_loader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "scene/mtl_loader.h"
#include "scene/text_scan.h"
#include "scene/texture.h"
#include "util/error.h"

namespace edacrt {
namespace {

using namespace text_scan;
namespace fs = std::filesystem;

// Hit::prim and Scene::triangle_normals are int32, so no array may grow past this.
constexpr std::size_t kMaxElements = std::numeric_limits<std::int32_t>::max();

// Real files use a handful of statement kinds; many more means garbage, which would otherwise
// cost a warning per line.
constexpr std::size_t kMaxUnsupportedKinds = 32;

/// Lets a map be searched with a string_view, without building a string per line.
struct StringHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view text) const {
        return std::hash<std::string_view>{}(text);
    }
};
using NameMap = std::unordered_map<std::string, std::uint32_t, StringHash, std::equal_to<>>;

/// Reads a whole file; on failure says why. `text_only`: a NUL byte in the first block
/// refuses the file before the rest is read (an all-NUL 3 GB file once took 19 s to reach the
/// parser's check).
std::optional<std::string> read_file(const fs::path& path, std::string& why,
                                     bool text_only = false) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) {
        // Not found, or a stat error such as a symlink loop's (ELOOP).
        why = status.type() == fs::file_type::none && ec ? ec.message() : "no such file";
        return std::nullopt;
    }
    if (!fs::is_regular_file(status)) {  // an ifstream would "open" a directory
        why = "not a regular file";
        return std::nullopt;
    }
    std::ifstream in(path, std::ios::binary);
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!in || ec) {
        why = "cannot be opened for reading";
        return std::nullopt;
    }
    std::string first(std::size_t(std::min<std::uintmax_t>(size, 1 << 16)), '\0');
    in.read(first.data(), static_cast<std::streamsize>(first.size()));
    if (static_cast<std::size_t>(in.gcount()) != first.size()) {
        why = "read error";
        return std::nullopt;
    }
    if (const std::size_t nul = first.find('\0'); text_only && nul != std::string::npos) {
        why = "line " + std::to_string(1 + std::count(first.begin(), first.begin() + nul, '\n')) +
              ": NUL byte; this is not a text file";
        return std::nullopt;
    }
    std::string text;
    try {
        text.resize(size);
    } catch (const std::exception&) {  // bad_alloc, or length_error past max_size()
        why = std::to_string(size) + " bytes, more than the memory can hold";
        return std::nullopt;
    }
    std::copy(first.begin(), first.end(), text.begin());
    const std::uintmax_t rest = size - first.size();
    in.read(text.data() + first.size(), static_cast<std::streamsize>(rest));
    if (static_cast<std::uintmax_t>(in.gcount()) != rest) {
        why = "read error";
        return std::nullopt;
    }
    return text;
}

struct Corner {
    std::uint32_t position;
    std::int32_t normal;    // -1: none
    std::int32_t texcoord;  // -1: none
};

/// What a face index refers to, for messages.
struct IndexKind {
    const char* name;
    const char* plural;
};
constexpr IndexKind kVertexIndex{"vertex", "vertices"};
constexpr IndexKind kTexcoordIndex{"texture coordinate", "texture coordinates"};
constexpr IndexKind kNormalIndex{"normal", "normals"};

/// One distinct usemtl name. Names are resolved after the whole file is read, so an mtllib
/// line may come after the usemtl lines that need it.
struct MaterialUse {
    std::string name;  // empty: faces before any usemtl
    std::size_t line = 0;
    bool used = false;  // some triangle refers to it
};

class ObjParser {
  public:
    ObjParser(std::string_view text, const std::string& source, const MtlReader& read_mtl,
              std::string mtl_dir)
        : text_(text),
          lines_(text),
          source_(source),
          read_mtl_(read_mtl),
          mtl_dir_(std::move(mtl_dir)),
          uses_(1) {}

    Scene parse() {
        scene_.source = source_;
        reserve();
        std::string_view line;
        while (lines_.next(line)) parse_line(line);
        if (scene_.triangles.size() == degenerate_) {
            throw InputError(source_ + ": no triangles" +
                             (degenerate_ > 0 ? " (all " + std::to_string(degenerate_) +
                                                    " triangles are degenerate, zero area)"
                                              : " (the file has no faces)"));
        }
        if (degenerate_ > 0) {
            scene_.warnings.push_back(source_ + ": " + std::to_string(degenerate_) +
                                      " degenerate triangles (zero area), never hit");
        }
        if (has_normals_) {
            scene_.normals = std::move(normals_);
        }
        if (has_texcoords_) {
            scene_.texcoords = std::move(texcoords_);
        }
        resolve_materials();
        return std::move(scene_);
    }

  private:
    [[noreturn]] void fail(const std::string& what) const { throw InputError(where() + what); }

    std::string where() const { return source_ + ":" + std::to_string(lines_.number()) + ": "; }

    /// Sizes the big arrays from a quick count of line starts, so they are allocated once.
    void reserve() {
        std::size_t vertices = 0;
        std::size_t normals = 0;
        std::size_t texcoords = 0;
        for (std::size_t pos = 0; pos + 1 < text_.size();) {
            const char c0 = text_[pos];
            const char c1 = text_[pos + 1];
            vertices += c0 == 'v' && is_blank(c1);
            normals += c0 == 'v' && c1 == 'n';
            texcoords += c0 == 'v' && c1 == 't';
            faces_ += c0 == 'f' && is_blank(c1);
            pos = text_.find('\n', pos);
            if (pos == std::string_view::npos) break;
            ++pos;
        }
        scene_.positions.reserve(vertices);
        normals_.reserve(normals);
        texcoords_.reserve(texcoords);
        scene_.triangles.reserve(faces_);
        scene_.triangle_materials.reserve(faces_);
    }

    void parse_line(std::string_view line) {
        if (line.find('\0') != std::string_view::npos) {
            fail("NUL byte; this is not a text OBJ file");
        }
        line = strip_comment(line);
        if (line.ends_with('\\')) fail("line continuation '\\' is not supported");
        Tokens tokens(line);
        std::string_view keyword;
        if (!tokens.next(keyword)) return;
        if (keyword == "v") {
            parse_vertex(tokens);
        } else if (keyword == "f") {
            parse_face(tokens);
        } else if (keyword == "vn") {
            parse_normal(tokens);
        } else if (keyword == "vt") {
            parse_texcoord(tokens);
        } else if (keyword == "usemtl") {
            use_material(tokens.rest());
        } else if (keyword == "mtllib") {
            load_libraries(tokens);
        } else if (keyword == "o" || keyword == "g" || keyword == "s") {
            // Object, group and smoothing-group names do not affect the triangles.
        } else if (is_keyword(keyword)) {
            ignore_statement(keyword);
        } else {
            fail("unexpected " + quote(keyword) + " (not an OBJ statement)");
        }
    }

    float number(std::string_view token) const {
        float value = 0.0f;
        const NumberStatus status = parse_float(token, value);
        if (status != NumberStatus::ok) fail(describe(status, token));
        return value;
    }

    /// Reads `min_count` to `max_count` numbers into `values`; returns how many there were.
    int numbers(Tokens& tokens, const char* keyword, int min_count, int max_count,
                float* values) const {
        int count = 0;
        std::string_view token;
        while (tokens.next(token)) {
            if (count == max_count) {
                fail(std::string("too many numbers after '") + keyword + "' (at most " +
                     std::to_string(max_count) + ")");
            }
            const float value = number(token);
            if (count < 3) values[count] = value;
            ++count;
        }
        if (count < min_count) {
            fail(std::string("'") + keyword + "' needs " + std::to_string(min_count) +
                 " numbers, found " + std::to_string(count));
        }
        return count;
    }

    void parse_vertex(Tokens& tokens) {
        // x y z, optionally followed by w or by r g b (vertex colours): checked, then ignored.
        float xyz[3];
        numbers(tokens, "v", 3, 7, xyz);
        if (scene_.positions.size() == kMaxElements) fail("too many vertices");
        scene_.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
    }

    void parse_normal(Tokens& tokens) {
        float xyz[3];
        numbers(tokens, "vn", 3, 3, xyz);
        if (normals_.size() == kMaxElements) fail("too many normals");
        // Stored unit length; a zero-length normal is kept as zero and treated as absent.
        const glm::dvec3 n(xyz[0], xyz[1], xyz[2]);
        const double length = glm::length(n);
        normals_.push_back(length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.0f));
    }

    void parse_texcoord(Tokens& tokens) {
        float uvw[3] = {0.0f, 0.0f, 0.0f};  // v defaults to 0 (a 1D texture); w is unused
        numbers(tokens, "vt", 1, 3, uvw);
        if (texcoords_.size() == kMaxElements) fail("too many texture coordinates");
        texcoords_.emplace_back(uvw[0], uvw[1]);
    }

    void parse_face(Tokens& tokens) {
        corners_.clear();
        std::string_view token;
        while (tokens.next(token)) corners_.push_back(parse_corner(token));
        if (corners_.size() < 3) {
            fail("face with " + std::to_string(corners_.size()) +
                 " corner(s); a face needs at least 3");
        }
        for (std::size_t i = 1; i + 1 < corners_.size(); ++i) {
            add_triangle(corners_[0], corners_[i], corners_[i + 1]);
        }
    }

    /// "v", "v/vt", "v//vn" or "v/vt/vn".
    Corner parse_corner(std::string_view token) const {
        const std::size_t slash1 = token.find('/');
        const std::string_view v = token.substr(0, slash1);
        std::string_view vt;
        std::string_view vn;
        if (slash1 != std::string_view::npos) {
            const std::string_view rest = token.substr(slash1 + 1);
            const std::size_t slash2 = rest.find('/');
            vt = rest.substr(0, slash2);
            if (slash2 != std::string_view::npos) vn = rest.substr(slash2 + 1);
            if (vn.find('/') != std::string_view::npos) {
                fail("bad face corner " + quote(token) + " (expected v, v/vt, v//vn or v/vt/vn)");
            }
        }
        if (v.empty()) fail("face corner " + quote(token) + " has no vertex index");
        Corner corner{resolve(v, scene_.positions.size(), kVertexIndex), -1, -1};
        if (!vt.empty())
            corner.texcoord = std::int32_t(resolve(vt, texcoords_.size(), kTexcoordIndex));
        if (!vn.empty()) {
            const std::uint32_t n = resolve(vn, normals_.size(), kNormalIndex);
            if (normals_[n] != glm::vec3(0.0f)) corner.normal = static_cast<std::int32_t>(n);
        }
        return corner;
    }

    /// A 1-based index, or a negative one counted back from the end of what is defined so far.
    std::uint32_t resolve(std::string_view token, std::size_t count, const IndexKind& kind) const {
        long long index = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
        if (ec == std::errc::invalid_argument || end != token.data() + token.size()) {
            fail(std::string("bad face ") + kind.name + " index " + quote(token));
        }
        const auto out_of_range = [&] {
            fail(std::string("face ") + kind.name + " index " + escape(token) + " out of range (" +
                 std::to_string(count) + " " + kind.plural + " defined so far)");
        };
        if (ec == std::errc::result_out_of_range) out_of_range();
        if (index == 0) {
            fail(std::string("face ") + kind.name + " index 0 is invalid (OBJ indices start at 1)");
        }
        const auto n = static_cast<long long>(count);
        const long long resolved = index > 0 ? index - 1 : n + index;
        if (resolved < 0 || resolved >= n) out_of_range();
        return static_cast<std::uint32_t>(resolved);
    }

    void add_triangle(const Corner& a, const Corner& b, const Corner& c) {
        const auto& p = scene_.positions;
        // Kept, so triangles are numbered in file order (the `prim` of hits); never hit.
        degenerate_ += is_degenerate({p[a.position], p[b.position], p[c.position]});
        if (scene_.triangles.size() == kMaxElements) fail("too many triangles");
        scene_.triangles.push_back({a.position, b.position, c.position});
        scene_.triangle_materials.push_back(current_use_);
        uses_[current_use_].used = true;
        if (!has_normals_ && (a.normal >= 0 || b.normal >= 0 || c.normal >= 0)) {
            has_normals_ = true;
            scene_.triangle_normals.reserve(std::max(faces_, scene_.triangles.size()));
            scene_.triangle_normals.assign(scene_.triangles.size() - 1, {-1, -1, -1});
        }
        if (has_normals_) scene_.triangle_normals.push_back({a.normal, b.normal, c.normal});
        if (!has_texcoords_ && (a.texcoord >= 0 || b.texcoord >= 0 || c.texcoord >= 0)) {
            has_texcoords_ = true;
            scene_.triangle_texcoords.reserve(std::max(faces_, scene_.triangles.size()));
            scene_.triangle_texcoords.assign(scene_.triangles.size() - 1, {-1, -1, -1});
        }
        if (has_texcoords_)
            scene_.triangle_texcoords.push_back({a.texcoord, b.texcoord, c.texcoord});
    }

    void use_material(std::string_view name) {
        if (name.empty()) fail("usemtl without a material name");
        if (const auto it = use_ids_.find(name); it != use_ids_.end()) {
            current_use_ = it->second;
            return;
        }
        current_use_ = static_cast<std::uint32_t>(uses_.size());
        uses_.push_back({std::string(name), lines_.number(), false});
        use_ids_.emplace(name, current_use_);
    }

    /// The argument is the rest of the line, as file names may contain spaces; when no file has
    /// that whole name, it is taken as several names. A library that cannot be read is
    /// reported and its materials become the default one, as other viewers do.
    void load_libraries(Tokens& tokens) {
        const std::string_view names = tokens.rest();
        if (names.empty()) fail("mtllib without a file name");
        if (load_library(names)) return;
        std::vector<std::string_view> parts;
        Tokens split(names);
        for (std::string_view name; split.next(name);) parts.push_back(name);
        std::vector<std::string_view> missing;
        for (const std::string_view name : parts)
            if (parts.size() == 1 || !load_library(name)) missing.push_back(name);
        if (missing.size() == parts.size()) missing = {names};  // none read: name the whole line
        for (const std::string_view name : missing) {
            ++missing_libraries_;
            missing_library_warnings_.add(
                scene_.warnings,
                where() + "cannot read material library " + quote(name) +
                    (mtl_dir_.empty() ? std::string() : " (looked in " + mtl_dir_ + ")") +
                    "; its materials are replaced by the default material");
        }
    }

    /// Reads and parses one library (once per name); false when it cannot be read.
    bool load_library(std::string_view name_view) {
        const std::string name(name_view);
        for (const std::string& loaded : libraries_)
            if (loaded == name) return true;
        const std::optional<std::string> text =
            read_mtl_ ? read_mtl_(name) : std::optional<std::string>();
        if (!text) return false;
        libraries_.push_back(name);
        if (!mtl_dir_.empty()) scene_.inputs.push_back((fs::path(mtl_dir_) / name).string());
        // The name comes from the OBJ file, so messages show it escaped and shortened.
        const std::string mtl_source =
            mtl_dir_.empty() ? escape(name) : (fs::path(mtl_dir_) / escape(name)).string();
        for (Material& material : parse_mtl(*text, mtl_source, scene_.warnings)) {
            if (!mtl_dir_.empty())  // texture names are relative to their MTL file
                for (TextureMap& texture : material.textures)
                    texture.path = (fs::path(mtl_dir_) / name).parent_path() / texture.file;
            // The first definition wins, as in tinyobjloader.
            const auto id = static_cast<std::uint32_t>(scene_.materials.size());
            if (material_ids_.emplace(material.name, id).second) {
                scene_.materials.push_back(std::move(material));
            } else {
                redefined_.add(scene_.warnings,
                               mtl_source + ": material " + quote(material.name) +
                                   " is defined more than once; the first one is used");
            }
        }
        return true;
    }

    void ignore_statement(std::string_view keyword) {
        for (const std::string& seen : ignored_keywords_)
            if (seen == keyword) return;
        if (ignored_keywords_.size() == kMaxUnsupportedKinds) {
            fail("more than " + std::to_string(kMaxUnsupportedKinds) +
                 " kinds of unsupported statement; this does not look like an OBJ file");
        }
        ignored_keywords_.emplace_back(keyword);
        scene_.warnings.push_back(where() + "OBJ statement " + quote(keyword) +
                                  " is not supported (ignored)");
    }

    /// Turns the per-triangle usemtl slots into material ids; faces without a defined
    /// material get the default material, appended once.
    void resolve_materials() {
        std::vector<std::uint32_t> ids(uses_.size(), 0);
        std::optional<std::uint32_t> default_id;
        std::size_t undefined = 0;
        for (std::size_t i = 0; i < uses_.size(); ++i) {
            const MaterialUse& use = uses_[i];
            if (!use.name.empty()) {
                if (const auto it = material_ids_.find(use.name); it != material_ids_.end()) {
                    ids[i] = it->second;
                    continue;
                }
                ++undefined;
                // With a library missing, its materials are expected to be undefined.
                if (missing_libraries_ == 0)
                    undefined_.add(scene_.warnings,
                                   source_ + ":" + std::to_string(use.line) + ": material " +
                                       quote(use.name) +
                                       " is not defined; the default material is used");
            }
            if (!use.used) continue;
            if (!default_id) {
                default_id = static_cast<std::uint32_t>(scene_.materials.size());
                scene_.materials.emplace_back();
            }
            ids[i] = *default_id;
        }
        missing_library_warnings_.finish(scene_.warnings, source_);
        redefined_.finish(scene_.warnings, source_);
        undefined_.finish(scene_.warnings, source_);
        for (std::uint32_t& material : scene_.triangle_materials) material = ids[material];
        if (missing_libraries_ > 0 && undefined > 0)
            scene_.warnings.push_back(source_ + ": " + std::to_string(undefined) +
                                      " materials are not defined (a material library is "
                                      "missing); the default material is used");
    }

    std::string_view text_;
    LineReader lines_;
    const std::string& source_;
    const MtlReader& read_mtl_;
    std::string mtl_dir_;  // where load_obj looks for MTL files; empty for parse_obj

    Scene scene_;
    std::vector<glm::vec3> normals_;
    std::vector<glm::vec2> texcoords_;
    std::size_t faces_ = 0;        // estimated by reserve()
    std::vector<Corner> corners_;  // of the current face, reused
    bool has_normals_ = false;
    bool has_texcoords_ = false;
    std::size_t degenerate_ = 0;

    std::vector<MaterialUse> uses_;  // [0]: faces before any usemtl
    NameMap use_ids_;                // usemtl name -> index into uses_
    std::uint32_t current_use_ = 0;
    std::vector<std::string> libraries_;  // names already read
    std::size_t missing_libraries_ = 0;
    NameMap material_ids_;
    std::vector<std::string> ignored_keywords_;
    WarningLimit missing_library_warnings_{"unreadable material libraries"};
    WarningLimit redefined_{"materials defined more than once"};
    WarningLimit undefined_{"undefined materials"};
};

}  // namespace

Scene parse_obj(std::string_view text, const std::string& source_name, const MtlReader& read_mtl) {
    return ObjParser(text, source_name, read_mtl, std::string()).parse();
}

const TextureMap* diffuse_map_statement(const Material& material) {
    const TextureMap* map = nullptr;
    for (const TextureMap& texture : material.textures)
        if (equals_ignoring_case(texture.keyword, "map_Kd") && !texture.path.empty())
            map = &texture;
    return map;
}

namespace {

/// Decodes each material's diffuse_map_statement(), each file once. A file that cannot be
/// decoded leaves its materials with Kd alone, and a warning.
void load_diffuse_maps(Scene& scene) {
    std::unordered_map<std::string, std::shared_ptr<const Texture>> decoded;
    WarningLimit unreadable{"unreadable textures"};
    for (Material& material : scene.materials) {
        const TextureMap* map = diffuse_map_statement(material);
        if (!map) continue;
        auto [it, inserted] = decoded.try_emplace(map->path);
        if (inserted) try {
                it->second = std::make_shared<const Texture>(load_texture(map->path));
            } catch (const InputError& e) {
                unreadable.add(scene.warnings, std::string(e.what()) + "; Kd alone is used");
            }
        material.diffuse_map = it->second;
    }
    unreadable.finish(scene.warnings, scene.source);
}

}  // namespace

Scene load_obj(const std::filesystem::path& path) {
    const std::string source = path.string();
    std::string why;
    const std::optional<std::string> text = read_file(path, why, true);
    if (!text) throw InputError(source + ": cannot read OBJ file (" + why + ")");
    const fs::path dir = path.parent_path();
    const MtlReader read_mtl = [&dir](const std::string& name) {
        std::string ignored;
        return read_file(dir / name, ignored);
    };
    Scene scene;
    try {
        scene = ObjParser(*text, source, read_mtl, dir.empty() ? "." : dir.string()).parse();
    } catch (const std::bad_alloc&) {  // a message that names the file, not "out of memory"
        throw InputError(source + ": out of memory loading the OBJ file of " +
                         std::to_string(text->size()) + " bytes");
    }
    scene.inputs.insert(scene.inputs.begin(), source);
    load_diffuse_maps(scene);
    return scene;
}

}  // namespace edacrt
