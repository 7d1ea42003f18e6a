#pragma once
// Binary ray and hit files: little-endian, no header. A ray is 8 float32
// (ox oy oz dx dy dz tmin tmax, 32 bytes); a hit is float32 t (+inf on a miss), int32 prim
// (-1 on a miss), float32 u, v (16 bytes). Rays and hits are stored in exactly this layout in
// memory, so the files are read and written in one block.
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "geometry/ray.h"

namespace edacrt {

/// The shortest direction a ray may have, by its longest component (see validate_ray).
inline constexpr float kShortestDirection = 0x1p-64f;

/// Empty when the ray can be traced; otherwise what is wrong with it ("NaN origin", a
/// direction whose longest component is below kShortestDirection, ...).
std::string validate_ray(const Ray& ray);

/// Reads and validates a ray file. Throws InputError naming the file and the first bad ray.
std::vector<Ray> read_rays(const std::filesystem::path& path);
void write_rays(const std::filesystem::path& path, std::span<const Ray> rays);

std::vector<Hit> read_hits(const std::filesystem::path& path);
void write_hits(const std::filesystem::path& path, std::span<const Hit> hits);

}  // namespace edacrt
