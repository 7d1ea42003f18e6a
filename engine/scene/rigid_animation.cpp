#include "scene/rigid_animation.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "scene/obj_loader.h"
#include "util/error.h"
#include "util/input_file.h"
#include "util/json_limits.h"
#include "util/printable.h"

namespace edacrt {
namespace {

using nlohmann::json;

// The range of a normal float: positions are floats.
constexpr double kFloatMin = std::numeric_limits<float>::min();
constexpr double kFloatMax = std::numeric_limits<float>::max();

std::string text(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", x);
    return buffer;
}

struct Key {
    double time = 0.0;
    glm::dvec3 translate{0.0};
    glm::dvec3 axis{0.0, 1.0, 0.0};  // unit
    double degrees = 0.0;
    glm::dvec3 scale{1.0};
};

struct Object {
    std::size_t first_vertex, vertices, first_normal, normals;
    std::vector<Key> keys;  // empty: static
};

/// The JSON reader's context: the file, and where in it an entry is, for messages.
struct Reader {
    std::string file;

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw InputError(file + ": " + where + ": " + what);
    }

    void only_fields(const json& j, const std::string& where,
                     std::initializer_list<const char*> known) const {
        if (!j.is_object()) fail(where, "expected an object {...}");
        for (const auto& item : j.items()) {
            const std::string& name = item.key();
            if (std::find_if(known.begin(), known.end(),
                             [&](const char* k) { return name == k; }) != known.end())
                continue;
            std::string list;
            for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
            // A name may hold any character ("\u001b" in the file).
            fail(where, "unknown field '" + printable(name, 80) + "' (known: " + list + ")");
        }
    }

    double number(const json& j, const std::string& where) const {
        if (!j.is_number()) fail(where, "expected a number, got " + json_excerpt(j));
        const double x = j.get<double>();
        if (!std::isfinite(x)) fail(where, "expected a finite number");
        return x;
    }

    glm::dvec3 vec3(const json& j, const std::string& where) const {
        if (!j.is_array() || j.size() != 3)
            fail(where, "expected [x, y, z], got " + json_excerpt(j));
        return {number(j[0], where), number(j[1], where), number(j[2], where)};
    }

    Key key(const json& j, const std::string& where, const Key* previous) const {
        only_fields(j, where, {"time", "translate", "rotate", "scale"});
        if (!j.contains("time")) fail(where, "a key needs a \"time\" in seconds");
        Key key;
        key.time = number(j["time"], where + ".time");
        if (key.time < 0.0) fail(where + ".time", "times start at 0");
        if (previous && !(key.time > previous->time))
            fail(where + ".time", "key times must increase");
        if (j.contains("translate")) {
            key.translate = vec3(j["translate"], where + ".translate");
            // Positions are floats: a translation past their range makes no finite pose.
            for (int a = 0; a < 3; ++a)
                if (!(std::abs(key.translate[a]) <= kFloatMax))
                    fail(where + ".translate", "components must be within +-" + text(kFloatMax));
        }
        if (j.contains("rotate")) {
            const json& r = j["rotate"];
            const std::string at = where + ".rotate";
            if (!r.is_array() || r.size() != 4)
                fail(at, "expected [axis x, axis y, axis z, degrees], got " + json_excerpt(r));
            const glm::dvec3 axis(number(r[0], at), number(r[1], at), number(r[2], at));
            if (!(glm::length(axis) > 0.0) || !std::isfinite(glm::length(axis)))
                fail(at, "the axis must be a non-zero vector");
            key.axis = glm::normalize(axis);
            if (!std::isfinite(key.axis.x + key.axis.y + key.axis.z))
                fail(at, "the axis must be a non-zero vector");
            key.degrees = number(r[3], at);
        }
        if (j.contains("scale")) {
            const json& s = j["scale"];
            key.scale =
                s.is_array() ? vec3(s, where + ".scale") : glm::dvec3(number(s, where + ".scale"));
            // A denormal scale (1e-320) passes > 0 but flattens the object in float.
            for (int a = 0; a < 3; ++a)
                if (!(key.scale[a] >= kFloatMin && key.scale[a] <= kFloatMax))
                    fail(where + ".scale",
                         "scales must be > 0, from " + text(kFloatMin) + " to " + text(kFloatMax) +
                             " (a mirror or a flat object is not a rigid motion)");
        }
        return key;
    }

    Camera camera(const json& j) const {
        only_fields(j, "camera", {"eye", "look_at", "up", "fov"});
        if (!j.contains("eye") || !j.contains("look_at"))
            fail("camera", "needs \"eye\" and \"look_at\"");
        Camera c;
        c.eye = glm::vec3(vec3(j["eye"], "camera.eye"));
        c.look_at = glm::vec3(vec3(j["look_at"], "camera.look_at"));
        if (j.contains("up")) c.up = glm::vec3(vec3(j["up"], "camera.up"));
        if (j.contains("fov")) c.vfov_degrees = float(number(j["fov"], "camera.fov"));
        try {
            validate(c);
        } catch (const InputError& e) {
            fail("camera", e.what());
        }
        return c;
    }
};

/// Per-corner indices (shading normals or texture coordinates) of `part`'s triangles after
/// those of the scene's `first_triangle`, for all triangles once any object has them (-1: none).
void append_corner_indices(std::vector<std::array<std::int32_t, 3>>& to,
                           const std::vector<std::array<std::int32_t, 3>>& from,
                           std::size_t first_triangle, std::size_t triangles, std::int32_t base) {
    if (from.empty() && to.empty()) return;
    to.resize(first_triangle, {-1, -1, -1});
    for (std::size_t i = 0; i < triangles; ++i) {
        std::array<std::int32_t, 3> n = {-1, -1, -1};
        if (!from.empty())
            for (int k = 0; k < 3; ++k)
                if (from[i][k] >= 0) n[k] = from[i][k] + base;
        to.push_back(n);
    }
}

/// Appends `part` to `scene`: its vertices, normals, texture coordinates and materials after
/// those already there.
void append(Scene& scene, Scene part, const std::string& name) {
    const auto vertex_base = std::uint32_t(scene.positions.size());
    const auto normal_base = std::int32_t(scene.normals.size());
    const auto texcoord_base = std::int32_t(scene.texcoords.size());
    const auto material_base = std::uint32_t(scene.materials.size());
    const std::size_t first_triangle = scene.triangles.size();
    scene.inputs.insert(scene.inputs.end(), part.inputs.begin(), part.inputs.end());
    scene.positions.insert(scene.positions.end(), part.positions.begin(), part.positions.end());
    scene.normals.insert(scene.normals.end(), part.normals.begin(), part.normals.end());
    scene.texcoords.insert(scene.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
    scene.materials.insert(scene.materials.end(), part.materials.begin(), part.materials.end());
    for (auto tri : part.triangles) {
        for (std::uint32_t& v : tri) v += vertex_base;
        scene.triangles.push_back(tri);
    }
    for (const std::uint32_t m : part.triangle_materials)
        scene.triangle_materials.push_back(m + material_base);
    append_corner_indices(scene.triangle_normals, part.triangle_normals, first_triangle,
                          part.triangles.size(), normal_base);
    append_corner_indices(scene.triangle_texcoords, part.triangle_texcoords, first_triangle,
                          part.triangles.size(), texcoord_base);
    for (const std::string& warning : part.warnings)
        scene.warnings.push_back(name + ": " + warning);
}

struct Pose {
    glm::dmat3 rotation;
    glm::dvec3 translate, scale;
};

glm::dquat rotation(const Key& key) { return glm::angleAxis(glm::radians(key.degrees), key.axis); }

/// The object's pose at time t (see load_rigid_animation for the interpolation).
Pose pose_at(const std::vector<Key>& keys, double t) {
    const auto after = std::upper_bound(keys.begin(), keys.end(), t,
                                        [](double time, const Key& k) { return time < k.time; });
    if (after == keys.begin() || after == keys.end()) {
        const Key& k = after == keys.begin() ? keys.front() : keys.back();
        return {glm::mat3_cast(rotation(k)), k.translate, k.scale};
    }
    const Key &a = *(after - 1), &b = *after;
    const double w = (t - a.time) / (b.time - a.time);
    const glm::dquat r =
        a.axis == b.axis
            ? glm::angleAxis(glm::radians(a.degrees + (b.degrees - a.degrees) * w), a.axis)
            : glm::slerp(rotation(a), rotation(b), w);
    return {glm::mat3_cast(r), a.translate + (b.translate - a.translate) * w,
            a.scale + (b.scale - a.scale) * w};
}

class RigidAnimation final : public Animation {
  public:
    RigidAnimation(std::string spec, const Scene& scene, std::vector<Object> objects)
        : Animation(std::move(spec), scene),
          objects_(std::move(objects)),
          base_(scene.positions),
          base_normals_(scene.normals) {
        for (const Object& o : objects_)
            if (!o.keys.empty()) duration_ = std::max(duration_, o.keys.back().time);
    }

    double duration() const override { return duration_; }

  private:
    void write_frame(double t, Scene& scene) override {
        for (const Object& o : objects_) {
            if (o.keys.empty()) continue;  // static: as loaded, never written
            const Pose pose = pose_at(o.keys, t);
            tbb::parallel_for(
                tbb::blocked_range<std::size_t>(o.first_vertex, o.first_vertex + o.vertices, 4096),
                [&](const auto& range) {
                    for (std::size_t v = range.begin(); v != range.end(); ++v)
                        scene.positions[v] = glm::vec3(
                            pose.translate + pose.rotation * (pose.scale * glm::dvec3(base_[v])));
                });
            // Normals by the inverse transpose of R diag(scale): R diag(1 / scale).
            for (std::size_t n = o.first_normal; n < o.first_normal + o.normals; ++n)
                scene.normals[n] = glm::vec3(
                    glm::normalize(pose.rotation * (glm::dvec3(base_normals_[n]) / pose.scale)));
        }
    }

    std::vector<Object> objects_;
    std::vector<glm::vec3> base_, base_normals_;
    double duration_ = 0.0;
};

}  // namespace

AnimatedScene load_rigid_animation(const std::filesystem::path& path) {
    const Reader reader{path.string()};
    const std::string text = read_text_file(path, "animation file");
    const json root = parse_json(text, path.string());
    reader.only_fields(root, "the file", {"camera", "objects"});
    if (!root.contains("objects") || !root["objects"].is_array() || root["objects"].empty())
        reader.fail("objects", "expected a non-empty list of objects");

    Scene scene;
    std::vector<Object> objects;
    for (std::size_t i = 0; i < root["objects"].size(); ++i) {
        const json& j = root["objects"][i];
        const std::string where = "objects[" + std::to_string(i) + "]";
        reader.only_fields(j, where, {"mesh", "keys"});
        if (!j.contains("mesh") || !j["mesh"].is_string())
            reader.fail(where, "needs a \"mesh\": an OBJ path or builtin:...");
        const std::string mesh = j["mesh"].get<std::string>();
        Object object{scene.positions.size(), 0, scene.normals.size(), 0, {}};
        if (j.contains("keys")) {
            if (!j["keys"].is_array()) reader.fail(where + ".keys", "expected a list of keys");
            for (std::size_t k = 0; k < j["keys"].size(); ++k)
                object.keys.push_back(
                    reader.key(j["keys"][k], where + ".keys[" + std::to_string(k) + "]",
                               object.keys.empty() ? nullptr : &object.keys.back()));
        }
        Scene part;
        try {
            part = mesh.starts_with("builtin:") ? load_scene(mesh)
                                                : load_obj(path.parent_path() / mesh);
        } catch (const InputError& e) {
            // It quotes the mesh's name, which may be long or hold control characters.
            reader.fail(where + ".mesh", printable(e.what(), 600));
        }
        object.vertices = part.positions.size();
        object.normals = part.normals.size();
        append(scene, std::move(part), mesh);
        objects.push_back(std::move(object));
    }
    if (root.contains("camera")) scene.camera = reader.camera(root["camera"]);
    scene.source = path.string();
    scene.inputs.insert(scene.inputs.begin(), path.string());

    AnimatedScene out{std::move(scene), nullptr};
    out.animation = std::make_unique<RigidAnimation>(path.string(), out.scene, std::move(objects));
    out.animation->frame(0.0, out.scene);
    return out;
}

}  // namespace edacrt
