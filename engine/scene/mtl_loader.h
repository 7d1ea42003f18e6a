#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "scene/material.h"

namespace edacrt {

/// Parses Wavefront MTL text (keywords case-insensitive: newmtl, Kd, Ks, Ke, Ns, Ni, illum).
/// Keywords the renderer does not model are reported once each in `warnings`.
/// Throws InputError "SOURCE:LINE: what" on malformed input.
std::vector<Material> parse_mtl(std::string_view text, const std::string& source_name,
                                std::vector<std::string>& warnings);

}  // namespace edacrt
