#include "render/bsdf.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

namespace edacrt {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float luminance(glm::vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

glm::vec3 reflect(glm::vec3 wo, glm::vec3 n) { return 2.0f * glm::dot(wo, n) * n - wo; }

/// Fresnel reflectance of a smooth dielectric interface; cos_i > 0 on the incident side.
float fresnel_dielectric(float cos_i, float eta) {
    const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
    const float cos_t = std::sqrt(1.0f - sin2_t);
    const float r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

/// The Phong lobe's value and pdf around the mirror direction of wo.
void phong(const Bsdf& bsdf, glm::vec3 n, glm::vec3 wo, glm::vec3 wi, glm::vec3& f, float& pdf) {
    const float cos_alpha = glm::dot(reflect(wo, n), wi);
    if (cos_alpha <= 0.0f) return;
    const float lobe = std::pow(cos_alpha, bsdf.exponent) / (2.0f * kPi);
    f += bsdf.ks * ((bsdf.exponent + 2.0f) * lobe);
    pdf += bsdf.glossy_probability * (bsdf.exponent + 1.0f) * lobe;
}

/// A direction around `axis` with density proportional to cos^exponent.
glm::vec3 sample_phong_lobe(glm::vec3 axis, float exponent, glm::vec2 u) {
    const float cos_theta = std::pow(u.x, 1.0f / (exponent + 1.0f));
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = 2.0f * kPi * u.y;
    glm::vec3 t, b;
    orthonormal_basis(axis, t, b);
    return sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * b + cos_theta * axis;
}

}  // namespace

void orthonormal_basis(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

glm::vec3 sample_cosine_hemisphere(glm::vec3 n, glm::vec2 u) {
    // Concentric-free variant: r = sqrt(u1), phi = 2 pi u2 (Malley's method).
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    glm::vec3 t, b;
    orthonormal_basis(n, t, b);
    return r * std::cos(phi) * t + r * std::sin(phi) * b +
           std::sqrt(std::max(0.0f, 1.0f - u.x)) * n;
}

Bsdf make_bsdf(const Material& material, std::vector<std::string>* notes) {
    Bsdf bsdf;
    const auto note = [&](const std::string& text) {
        if (notes) notes->push_back("material '" + material.name + "': " + text);
    };
    switch (material.illum) {
        case 3:
        case 5:
            bsdf.kind = Bsdf::Kind::mirror;
            bsdf.ks = material.ks;
            if (material.illum == 5) note("illum 5 rendered as a mirror without Fresnel");
            return bsdf;
        case 4:
        case 6:
        case 7:
            bsdf.kind = Bsdf::Kind::dielectric;
            bsdf.eta = material.ni > 0.0f ? material.ni : 1.5f;
            bsdf.tint = material.tf;
            return bsdf;
        default:
            break;
    }
    if (material.illum < 0 || material.illum > 2)
        note("illum " + std::to_string(material.illum) + " rendered as illum 2");
    bsdf.kd = glm::clamp(material.kd, 0.0f, 1.0f);
    if (material.illum != 1) bsdf.ks = glm::clamp(material.ks, 0.0f, 1.0f);
    // Keep kd + ks <= 1 per channel so the surface never creates energy.
    const glm::vec3 total = bsdf.kd + bsdf.ks;
    const float excess = std::max({total.x, total.y, total.z});
    if (excess > 1.0f) {
        bsdf.kd /= excess;
        bsdf.ks /= excess;
        note("Kd + Ks > 1 scaled down to conserve energy");
    }
    bsdf.exponent = std::max(material.ns, 0.0f);
    const float diffuse = luminance(bsdf.kd), glossy = luminance(bsdf.ks);
    bsdf.glossy_probability = diffuse + glossy > 0.0f ? glossy / (diffuse + glossy) : 0.0f;
    return bsdf;
}

BsdfEval evaluate(const Bsdf& bsdf, glm::vec3 n, glm::vec3 wo, glm::vec3 wi) {
    BsdfEval result;
    const float cos_i = glm::dot(n, wi);
    if (bsdf.is_delta() || cos_i <= 0.0f || glm::dot(n, wo) <= 0.0f) return result;
    result.f = bsdf.kd / kPi;
    result.pdf = (1.0f - bsdf.glossy_probability) * cos_i / kPi;
    if (bsdf.glossy_probability > 0.0f) phong(bsdf, n, wo, wi, result.f, result.pdf);
    return result;
}

std::optional<BsdfSample> sample(const Bsdf& bsdf, glm::vec3 n, glm::vec3 ng_stored, glm::vec3 wo,
                                 float u_lobe, glm::vec2 u) {
    switch (bsdf.kind) {
        case Bsdf::Kind::mirror:
            return BsdfSample{reflect(wo, n), bsdf.ks, 0.0f, true};
        case Bsdf::Kind::dielectric: {
            // Entering when wo is on the side the stored normal points to.
            const bool entering = glm::dot(wo, ng_stored) > 0.0f;
            const float eta = entering ? bsdf.eta : 1.0f / bsdf.eta;
            const float cos_i = glm::dot(n, wo);
            const float reflectance = fresnel_dielectric(cos_i, eta);
            if (u_lobe < reflectance)
                return BsdfSample{reflect(wo, n), glm::vec3(1.0f), 0.0f, true};
            const float cos_t =
                std::sqrt(std::max(0.0f, 1.0f - (1.0f - cos_i * cos_i) / (eta * eta)));
            const glm::vec3 wi = glm::normalize(-wo / eta + (cos_i / eta - cos_t) * n);
            // Radiance is compressed by 1/eta^2 when it crosses into the denser medium.
            const glm::vec3 weight = (entering ? bsdf.tint : glm::vec3(1.0f)) / (eta * eta);
            return BsdfSample{wi, weight, 0.0f, true};
        }
        case Bsdf::Kind::diffuse_glossy:
            break;
    }
    glm::vec3 wi;
    if (u_lobe < bsdf.glossy_probability)
        wi = sample_phong_lobe(reflect(wo, n), bsdf.exponent, u);
    else
        wi = sample_cosine_hemisphere(n, u);
    const BsdfEval eval = evaluate(bsdf, n, wo, wi);
    if (eval.pdf <= 0.0f) return std::nullopt;
    return BsdfSample{wi, eval.f * (glm::dot(n, wi) / eval.pdf), eval.pdf, false};
}

}  // namespace edacrt
