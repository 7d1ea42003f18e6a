#pragma once
// The scattering models the bundled and shared scenes' MTL files ask for, and nothing more:
// Lambertian Kd; a normalised Phong lobe from Ks/Ns (illum 2); a mirror (illum 3, 5); a smooth
// dielectric from Ni tinted by Tf (illum 4, 6, 7). Emission (Ke) is handled by the lights.
// Directions point away from the surface; `n` is the unit shading normal on the side of wo.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene/material.h"

namespace edacrt {

struct Bsdf {
    enum class Kind { diffuse_glossy, mirror, dielectric };
    Kind kind = Kind::diffuse_glossy;
    glm::vec3 kd{0.0f};
    glm::vec3 ks{0.0f};               // Phong lobe (diffuse_glossy) or mirror reflectance
    float exponent = 0.0f;            // Phong exponent (Ns)
    float glossy_probability = 0.0f;  // of sampling the Phong lobe
    float eta = 1.0f;                 // dielectric: index of refraction (inside / outside)
    glm::vec3 tint{1.0f};             // dielectric: transmission filter

    /// Delta distributions cannot be sampled towards a light.
    bool is_delta() const { return kind != Kind::diffuse_glossy; }
};

/// The model of one material; appends a note to `notes` when an MTL setting is approximated.
Bsdf make_bsdf(const Material& material, std::vector<std::string>* notes = nullptr);

/// f(wo, wi) (without the cosine) and the solid-angle pdf of sample() producing wi.
/// Zero for delta BSDFs.
struct BsdfEval {
    glm::vec3 f{0.0f};
    float pdf = 0.0f;
};
BsdfEval evaluate(const Bsdf& bsdf, glm::vec3 n, glm::vec3 wo, glm::vec3 wi);

struct BsdfSample {
    glm::vec3 wi;
    glm::vec3 weight;  // f cos / pdf
    float pdf;         // solid angle; 0 for delta lobes
    bool delta;
};

/// Samples wi with the lobe choice `u_lobe` and direction `u`. `ng` is the geometric normal as
/// stored (its orientation tells a dielectric inside from outside). Empty when the sampled
/// direction falls below the surface.
std::optional<BsdfSample> sample(const Bsdf& bsdf, glm::vec3 n, glm::vec3 ng_stored, glm::vec3 wo,
                                 float u_lobe, glm::vec2 u);

/// A cosine-weighted direction around the unit normal n (pdf cos / pi).
glm::vec3 sample_cosine_hemisphere(glm::vec3 n, glm::vec2 u);

/// An orthonormal basis around the unit vector n (Duff et al., JCGT 2017).
void orthonormal_basis(glm::vec3 n, glm::vec3& t, glm::vec3& b);

}  // namespace edacrt
