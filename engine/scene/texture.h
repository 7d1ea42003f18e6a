#pragma once
// Diffuse textures (MTL map_Kd), decoded by FreeImage when the scene is loaded. Texels stay
// 8-bit sRGB, as the files store them (3 bytes each, a quarter of linear floats), and are
// filtered bilinearly in linear light: each of the four texels is decoded before blending,
// since blending encoded values darkens edges. OBJ texture coordinates repeat outside [0, 1].
#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace edacrt {

struct Texture {
    int width = 0, height = 0;
    std::vector<std::array<std::uint8_t, 3>> texels;  // RGB, row 0 at v = 0 (the image's bottom)

    /// The linear RGB at (u, v), texel centres at ((x + 1/2) / width, (y + 1/2) / height);
    /// a coordinate that is not finite reads as 0.
    glm::vec3 lookup(glm::vec2 uv) const;
};

/// The linear value of an 8-bit sRGB-encoded one (IEC 61966-2-1): texels, and the PNG and JPEG
/// images read_png() reads.
float srgb_to_linear(std::uint8_t encoded);

/// Decodes an image file (any format FreeImage reads: JPEG, PNG, TGA, BMP, DDS, ...). Throws
/// InputError naming the file and why.
Texture load_texture(const std::string& path);

}  // namespace edacrt
