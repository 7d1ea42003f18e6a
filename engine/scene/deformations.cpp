// Wave, twist and explode: positions moved in double from the mesh as loaded, shading normals
// turned by the inverse transpose of each deformation's Jacobian.
#include "scene/deformations.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "util/error.h"
#include "util/hash_random.h"
#include "util/spec_options.h"

namespace edacrt {
namespace {

constexpr double kTwoPi = 6.283185307179586;

/// Where time t is within a period, in [0, 1): the same t always gives the same value.
double cycle(double t, double period) {
    const double c = t / period;
    return c - std::floor(c);
}

/// A unit shading normal after a deformation whose Jacobian is I + u v^T with u . v = 0: the
/// inverse transpose of that Jacobian is I - v u^T (Sherman-Morrison), so n' ~ n - v (u . n).
/// Never zero for a non-zero n: its component along u is unchanged.
glm::dvec3 sheared_normal(const glm::dvec3& n, const glm::dvec3& u, const glm::dvec3& v) {
    return glm::normalize(n - v * glm::dot(u, n));
}

int take_axis(SpecOptions& options, std::string_view spec, const char* key, const char* fallback) {
    const std::string name = options.text(key, fallback);
    if (name == "x") return 0;
    if (name == "y") return 1;
    if (name == "z") return 2;
    throw InputError(std::string(spec) + ": " + key + " must be x, y or z, got '" + name + "'");
}

constexpr const char* kAxisNames[] = {"x", "y", "z"};

/// Gives every corner with a shading normal one of its own (triangle i, corner k: normal
/// 3i + k), so that a deformation can turn corners that shared a normal at different points
/// differently. A corner without one keeps -1.
void own_corner_normals(Scene& scene) {
    if (scene.triangle_normals.empty()) return;
    std::vector<glm::vec3> normals(3 * scene.triangle_count(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < scene.triangle_count(); ++i)
        for (int k = 0; k < 3; ++k) {
            std::int32_t& n = scene.triangle_normals[i][k];
            if (n < 0) continue;
            normals[3 * i + k] = scene.normals[std::size_t(n)];
            n = std::int32_t(3 * i + k);
        }
    scene.normals = std::move(normals);
}

/// The mesh as it was when the deformation was made, which every frame starts from.
class Deformation : public Animation {
  protected:
    Deformation(std::string spec, const Scene& scene, double period)
        : Animation(std::move(spec), scene),
          period_(period),
          base_(scene.positions),
          base_normals_(scene.normals),
          box_(scene.bounds()),
          diagonal_(glm::length(glm::dvec3(box_.extent()))) {}

  public:
    double duration() const override { return period_; }

  protected:
    /// Calls move(v) for every vertex in parallel, and turn(i, k) for every corner with a
    /// shading normal (after own_corner_normals, normal 3i + k).
    template <class Move, class Turn>
    void deform(Scene& scene, Move move, Turn turn) const {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, base_.size(), 4096),
                          [&](const auto& range) {
                              for (std::size_t v = range.begin(); v != range.end(); ++v)
                                  scene.positions[v] = move(glm::dvec3(base_[v]));
                          });
        if (scene.triangle_normals.empty()) return;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, scene.triangle_count(), 4096),
                          [&](const auto& range) {
                              for (std::size_t i = range.begin(); i != range.end(); ++i)
                                  for (int k = 0; k < 3; ++k) {
                                      if (scene.triangle_normals[i][k] < 0) continue;
                                      const std::size_t n = 3 * i + std::size_t(k);
                                      const glm::dvec3 p(base_[scene.triangles[i][k]]);
                                      scene.normals[n] =
                                          glm::vec3(turn(p, glm::dvec3(base_normals_[n])));
                                  }
                          });
    }

    double period_;
    std::vector<glm::vec3> base_, base_normals_;
    Aabb box_;
    double diagonal_;
};

/// A travelling sine wave: every point moves along `axis` by A sin(2 pi (s / L - t / P)),
/// s its coordinate along `direction` from the box's low side; crests travel one wavelength L
/// per period P.
class Wave final : public Deformation {
  public:
    Wave(SpecOptions& options, std::string_view spec, Scene& scene)
        : Wave(read(options, spec), scene) {}

  private:
    struct Params {
        double amplitude, wavelength, period;
        int axis, direction;
    };

    static Params read(SpecOptions& options, std::string_view spec) {
        Params p;
        p.amplitude = options.number("amplitude", 0.02, 0.0, 10.0);
        p.wavelength = options.number("wavelength", 0.25, 1e-3, 1e3);
        p.period = options.number("period", 1.0, 1e-3, 1e6);
        p.axis = take_axis(options, spec, "axis", "y");
        p.direction = take_axis(options, spec, "direction", "x");
        if (p.axis == p.direction)
            throw InputError(std::string(spec) +
                             ": axis and direction must differ (the wave "
                             "moves points across its direction of travel)");
        options.finish();
        return p;
    }

    Wave(const Params& p, Scene& scene)
        : Deformation("wave:amplitude=" + shortest_text(p.amplitude) + ",wavelength=" +
                          shortest_text(p.wavelength) + ",period=" + shortest_text(p.period) +
                          ",axis=" + kAxisNames[p.axis] + ",direction=" + kAxisNames[p.direction],
                      (own_corner_normals(scene), scene), p.period),
          p_(p) {}

    void write_frame(double t, Scene& scene) override {
        const double amplitude = p_.amplitude * diagonal_;
        // Radians per unit length; a mesh without extent does not move.
        const double k = diagonal_ > 0.0 ? kTwoPi / (p_.wavelength * diagonal_) : 0.0;
        const double phase = kTwoPi * cycle(t, p_.period);
        const double lo = box_.lo[p_.direction];
        glm::dvec3 axis(0.0), direction(0.0);
        axis[p_.axis] = 1.0;
        direction[p_.direction] = 1.0;
        deform(
            scene,
            [&](glm::dvec3 p) {
                p[p_.axis] += amplitude * std::sin(k * (p[p_.direction] - lo) - phase);
                return glm::vec3(p);
            },
            [&](const glm::dvec3& p, const glm::dvec3& n) {
                // Jacobian I + axis grad(d)^T, grad(d) along `direction`, across `axis`.
                const double slope = amplitude * k * std::cos(k * (p[p_.direction] - lo) - phase);
                return sheared_normal(n, axis, slope * direction);
            });
    }

    Params p_;
};

/// A twist about the line through the box centre along `axis`: a point at height h (from -1/2
/// at one end of the box to 1/2 at the other) turns by theta = DEG h sin(2 pi t / P), so the
/// ends swing between +-DEG/2, DEG apart at most.
class Twist final : public Deformation {
  public:
    Twist(SpecOptions& options, std::string_view spec, Scene& scene)
        : Twist(read(options, spec), scene) {}

  private:
    struct Params {
        double angle, period;
        int axis;
    };

    static Params read(SpecOptions& options, std::string_view spec) {
        Params p;
        p.angle = options.number("angle", 90.0, -36000.0, 36000.0);
        p.period = options.number("period", 2.0, 1e-3, 1e6);
        p.axis = take_axis(options, spec, "axis", "y");
        options.finish();
        return p;
    }

    Twist(const Params& p, Scene& scene)
        : Deformation("twist:angle=" + shortest_text(p.angle) +
                          ",period=" + shortest_text(p.period) + ",axis=" + kAxisNames[p.axis],
                      (own_corner_normals(scene), scene), p.period),
          p_(p) {}

    void write_frame(double t, Scene& scene) override {
        const int a = p_.axis, b = (a + 1) % 3, c = (a + 2) % 3;  // (b, c, a) right-handed
        const glm::dvec3 centre(box_.center());
        const double height = box_.extent()[a];
        // d theta / d p_a: the twist rate along the axis at this time.
        const double rate = height > 0.0 ? p_.angle * (kTwoPi / 360.0) *
                                               std::sin(kTwoPi * cycle(t, p_.period)) / height
                                         : 0.0;
        const auto rotate = [&](glm::dvec3 q, double theta) {
            const double cos_t = std::cos(theta), sin_t = std::sin(theta);
            const double qb = q[b], qc = q[c];
            q[b] = qb * cos_t - qc * sin_t;
            q[c] = qb * sin_t + qc * cos_t;
            return q;
        };
        deform(
            scene,
            [&](const glm::dvec3& p) {
                const glm::dvec3 q = p - centre;
                return glm::vec3(centre + rotate(q, rate * q[a]));
            },
            [&](const glm::dvec3& p, const glm::dvec3& n) {
                // Jacobian R(theta) (I + u axis^T) with u = rate (axis x q), so the inverse
                // transpose is R(theta) (I - axis u^T).
                const glm::dvec3 q = p - centre;
                glm::dvec3 u(0.0), axis(0.0);
                u[b] = -rate * q[c];
                u[c] = rate * q[b];
                axis[a] = 1.0;
                return rotate(sheared_normal(n, u, axis), rate * q[a]);
            });
    }

    Params p_;
};

/// Every triangle moves as a whole along its geometric normal, by D s_i (1 - cos(2 pi t / P))
/// / 2: out to at most D s_i and back, s_i in [0.5, 1.5) a hash of the triangle's number so
/// that neighbours part. Degenerate triangles (no normal) stay. Shading normals are unchanged.
class Explode final : public Deformation {
  public:
    Explode(SpecOptions& options, Scene& scene) : Explode(read(options), scene) {}

  private:
    struct Params {
        double distance, period;
    };

    static Params read(SpecOptions& options) {
        Params p;
        p.distance = options.number("distance", 0.1, 0.0, 100.0);
        p.period = options.number("period", 2.0, 1e-3, 1e6);
        options.finish();
        return p;
    }

    /// Three corners of its own per triangle (triangle i: 3i, 3i + 1, 3i + 2), so triangles can
    /// part.
    static void split_corners(Scene& scene) {
        std::vector<glm::vec3> positions(3 * scene.triangle_count());
        for (std::size_t i = 0; i < scene.triangle_count(); ++i)
            for (int k = 0; k < 3; ++k) {
                positions[3 * i + k] = scene.positions[scene.triangles[i][k]];
                scene.triangles[i][k] = std::uint32_t(3 * i + k);
            }
        scene.positions = std::move(positions);
    }

    Explode(const Params& p, Scene& scene)
        : Deformation("explode:distance=" + shortest_text(p.distance) +
                          ",period=" + shortest_text(p.period),
                      (split_corners(scene), scene), p.period),
          p_(p),
          offsets_(scene.triangle_count()) {
        for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
            const double spread = 0.5 + hash_to_unit_float(pcg_hash(std::uint32_t(i)));
            offsets_[i] = glm::dvec3(unit_normal(scene.corners(i))) * spread;
        }
    }

    void write_frame(double t, Scene& scene) override {
        const double reach =
            p_.distance * diagonal_ * 0.5 * (1.0 - std::cos(kTwoPi * cycle(t, p_.period)));
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, offsets_.size(), 4096),
                          [&](const auto& range) {
                              for (std::size_t i = range.begin(); i != range.end(); ++i) {
                                  const glm::dvec3 offset = reach * offsets_[i];
                                  for (std::size_t v = 3 * i; v < 3 * i + 3; ++v)
                                      scene.positions[v] = glm::vec3(glm::dvec3(base_[v]) + offset);
                              }
                          });
    }

    Params p_;
    std::vector<glm::dvec3> offsets_;  // unit normal times spread, per triangle
};

}  // namespace

std::unique_ptr<Animation> make_deformation(std::string_view spec, Scene& scene) {
    const std::size_t colon = spec.find(':');
    const std::string_view kind = spec.substr(0, colon);
    SpecOptions options(spec, colon == std::string_view::npos ? "" : spec.substr(colon + 1));
    if (kind == "wave") return std::make_unique<Wave>(options, spec, scene);
    if (kind == "twist") return std::make_unique<Twist>(options, spec, scene);
    if (kind == "explode") return std::make_unique<Explode>(options, scene);
    // One line (messages reach the terminal escaped, a newline as \x0A): the kinds alone,
    // the first line of each in animation_help().
    std::string kinds;
    std::istringstream help(animation_help());
    for (std::string line; std::getline(help, line);)
        if (line.starts_with("  ") && line.size() > 2 && line[2] != ' ')
            kinds += (kinds.empty() ? "" : ", ") + line.substr(2);
    throw InputError("unknown animation '" + std::string(spec) + "'; available: " + kinds +
                     " (--help describes them)");
}

}  // namespace edacrt
