#pragma once
// The invariants every parsed Scene and Material satisfies, shared by the mutation test
// (obj_fuzz_test.cpp) and the libFuzzer fuzzer (fuzz/obj_fuzzer.cpp).
#include <cmath>
#include <string>

#include "scene/scene.h"

namespace edacrt::test {

inline bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Why a material breaks the invariants; empty when it is fine.
inline std::string material_violation(const Material& m) {
    if (m.name.empty()) return "material without a name";
    if (!finite(m.kd) || !finite(m.ks) || !finite(m.ke) || !finite(m.tf) || !std::isfinite(m.ns) ||
        !std::isfinite(m.ni)) {
        return "non-finite material value in " + m.name;
    }
    return {};
}

/// Why a scene breaks the invariants of Scene; empty when it is fine.
inline std::string scene_violation(const Scene& scene) {
    if (scene.triangles.empty()) return "no triangles";
    if (scene.materials.empty()) return "no materials";
    for (const glm::vec3& p : scene.positions)
        if (!finite(p)) return "non-finite position";
    for (const auto& tri : scene.triangles)
        for (std::uint32_t i : tri)
            if (i >= scene.positions.size()) return "triangle index out of range";
    if (scene.triangle_materials.size() != scene.triangles.size()) return "material count";
    for (std::uint32_t m : scene.triangle_materials)
        if (m >= scene.materials.size()) return "material id out of range";
    for (const Material& m : scene.materials)
        if (std::string why = material_violation(m); !why.empty()) return why;
    if (!scene.triangle_normals.empty()) {
        if (scene.triangle_normals.size() != scene.triangles.size()) return "normal count";
        for (const auto& corners : scene.triangle_normals) {
            for (std::int32_t n : corners) {
                if (n < -1 || (n >= 0 && static_cast<std::size_t>(n) >= scene.normals.size())) {
                    return "normal index out of range";
                }
            }
        }
    }
    for (const glm::vec3& n : scene.normals)
        if (!finite(n)) return "non-finite normal";
    return {};
}

}  // namespace edacrt::test
