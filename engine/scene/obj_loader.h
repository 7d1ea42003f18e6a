#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace edacrt {

/// Returns the text of the MTL file that an OBJ names in `mtllib NAME`, or nullopt when it
/// cannot be read.
using MtlReader = std::function<std::optional<std::string>(const std::string& name)>;

/// Parses Wavefront OBJ text: v, vn, f (any corner form v, v/vt, v//vn, v/vt/vn, negative
/// indices), usemtl, mtllib; polygons are fan-triangulated. Degenerate triangles are skipped and
/// counted in Scene::warnings. Throws InputError "SOURCE:LINE: what" on malformed input.
Scene parse_obj(std::string_view text, const std::string& source_name, const MtlReader& read_mtl);

/// The map_Kd statement load_obj decodes into Material::diffuse_map: the material's last one
/// whose file was resolved; null when it has none.
const TextureMap* diffuse_map_statement(const Material& material);

/// Reads and parses an OBJ file; MTL files are looked up beside it.
Scene load_obj(const std::filesystem::path& path);

}  // namespace edacrt
