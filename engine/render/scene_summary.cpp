#include "render/scene_summary.h"

#include <cstdio>
#include <filesystem>

#include "render/bsdf.h"
#include "scene/obj_loader.h"
#include "scene/text_scan.h"

namespace edacrt {
namespace {

std::string number(float x) {
    char text[24];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

std::string colour(glm::vec3 c) { return number(c.x) + " " + number(c.y) + " " + number(c.z); }

/// What make_bsdf() and the lights make of a material, in MTL terms.
std::string describe(const Material& m, const Bsdf& bsdf) {
    std::string text;
    switch (bsdf.kind) {
        case Bsdf::Kind::mirror:
            text = "mirror Ks " + colour(bsdf.ks);
            break;
        case Bsdf::Kind::dielectric:
            text = "smooth dielectric Ni " + number(bsdf.eta) + ", Tf " + colour(bsdf.tint);
            break;
        case Bsdf::Kind::diffuse_glossy:
            text = "Lambertian Kd " + colour(bsdf.kd);
            if (bsdf.ks != glm::vec3(0.0f))
                text += " + Phong Ks " + colour(bsdf.ks) + ", Ns " + number(bsdf.exponent);
            break;
    }
    if (m.diffuse_map && bsdf.kind == Bsdf::Kind::diffuse_glossy)
        text += " times map_Kd (" + std::to_string(m.diffuse_map->width) + "x" +
                std::to_string(m.diffuse_map->height) + ")";
    if (m.emissive()) text += "; emits Ke " + colour(m.ke);
    return text + " (illum " + std::to_string(m.illum) + ")";
}

}  // namespace

SceneSummary summarize_scene(const Scene& scene) {
    SceneSummary s;
    s.triangles = scene.triangle_count();
    s.vertices = scene.positions.size();
    s.shading_normals = scene.normals.size();
    s.bounds = scene.bounds();
    s.warnings = scene.warnings;
    std::vector<std::string> notes;
    // One material may name thousands of textures: their warnings stop after ten, as the
    // loader's do.
    text_scan::WarningLimit missing("missing textures");
    for (const Material& m : scene.materials) {
        MaterialSummary& summary = s.materials.emplace_back();
        summary.name = m.name;
        summary.model = describe(m, make_bsdf(m, &notes));
        summary.emissive = m.emissive();
        summary.textures = m.textures;
        // load_obj decodes one map_Kd, and warns when it cannot.
        const TextureMap* statement = diffuse_map_statement(m);
        const std::size_t decoded =
            statement ? std::size_t(statement - m.textures.data()) : std::size_t(-1);
        if (m.diffuse_map) summary.rendered_texture = decoded;
        for (std::size_t k = 0; k < m.textures.size(); ++k) {
            const TextureMap& texture = m.textures[k];
            if (k != decoded && !texture.path.empty() &&
                !std::filesystem::is_regular_file(texture.path))
                missing.add(s.warnings, "material '" + m.name + "': " + texture.keyword + " " +
                                            texture.file + " is missing (" + texture.path + ")");
        }
    }
    missing.finish(s.warnings, scene.source);
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
        const Triangle tri = scene.corners(i);
        const bool degenerate = is_degenerate(tri);
        s.degenerate_triangles += degenerate;
        const std::uint32_t material = scene.triangle_materials[i];
        ++s.materials[material].triangles;
        if (scene.materials[material].emissive() && !degenerate) {
            ++s.emissive_triangles;
            s.emissive_area += triangle_area(tri);
        }
    }
    s.warnings.insert(s.warnings.end(), notes.begin(), notes.end());
    return s;
}

}  // namespace edacrt
