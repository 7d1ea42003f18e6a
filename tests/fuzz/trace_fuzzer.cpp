// libFuzzer targets: trace_fuzzer decodes a small triangle soup, trace_fan_fuzzer (built with
// EDACRT_FUZZ_FANS) one polygon of up to 20,000 corners triangulated as a fan, and both a few
// rays, traced with every method for closest and any hit. Checked: every hit has a finite t in
// [tmin, tmax], a valid prim and barycentrics in the triangle (u, v >= 0, u + v <= 1, up to
// 1e-6); the ray's line does not certainly miss the triangle hit (edge signs in double,
// independent of the kernels: far rays once hit beside a triangle with every method, naive
// too); each method's closest hit agrees with naive's (hit or miss, and t, not prim: ties
// between triangles at the same t are allowed); any hit agrees with naive's closest hit or miss.
// A violation prints the case exactly (hex floats) and traps.
//
// Input format (every read past the end yields 0 bytes):
//   Soup: byte: triangle count - 1 (mod 16); per corner a byte: top bit set reuses an earlier
//   vertex (the byte picks which), so edges and vertices are shared, else a new vertex of 3
//   numbers. Fan (build_fan): 2 bytes of corner count (3 to 20,000, quadratic), a shape byte,
//   the centre (3 numbers), a radius byte, a jitter byte and a seed byte.
//   Then a byte: ray count - 1 (mod 16; mod 8 for fans); per ray a byte: the kind (low 2 bits:
//   free, aimed at a point of a triangle, spawned from a point of a triangle with the renderer's
//   offset), whether tmin and tmax are given (bits 2, 3), far (bit 4: moved back to 1e3..1e7
//   times a triangle's size, aimed near a point of it) and tiny (bit 5: the direction scaled to
//   2^-64..2^-33 by its longest component), then the kind's numbers and bytes, then the
//   modifiers'.
//   A number is a tag byte: < 0x80 a multiple of 1/8 in [-8, 8) (0 for 0); < 0xC0 a special value
//   (zeros, extremes, denormals, inf, NaN); < 0xF0 a small multiple of 1/4 scaled by 2^(next byte
//   as int8); else the next 4 bytes as a float's bits. A triangle is picked by one byte (mod the
//   count) in a soup, by two (a fraction of the count) in a fan.
// Scenes with non-finite coordinates (the OBJ loader rejects them) and rays validate_ray()
// rejects are skipped. Degenerate triangles are kept: a tracer must never hit them.
//
// Environment: EDACRT_FUZZ_PRINT=1 prints every decoded case and each method's time.
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/offset.h"
#include "scene/scene.h"
#include "trace/ray_file.h"
#include "trace/tracer.h"
#include "util/error.h"

namespace {

using namespace edacrt;

// trace_fan_fuzzer: the same checks on fans; built apart, since a fan takes seconds where a soup
// takes a millisecond.
#ifdef EDACRT_FUZZ_FANS
constexpr bool kFans = true;
#else
constexpr bool kFans = false;
#endif

constexpr float kSpecial[] = {0.0f,
                              -0.0f,
                              1.0f,
                              -1.0f,
                              0.5f,
                              1.0f / 3.0f,
                              0x1.000002p0f,   // 1 + ulp
                              0x1.fffffep-1f,  // 1 - ulp/2
                              0x1p-24f,
                              1e-8f,
                              1e8f,
                              1e-15f,
                              1e15f,
                              1.8e18f,
                              1e-20f,
                              1e20f,
                              1e38f,
                              -1e38f,
                              std::numeric_limits<float>::max(),
                              std::numeric_limits<float>::lowest(),
                              std::numeric_limits<float>::min(),
                              -std::numeric_limits<float>::min(),
                              std::numeric_limits<float>::denorm_min(),
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              std::numeric_limits<float>::quiet_NaN()};

class Decoder {
  public:
    Decoder(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}

    std::uint8_t byte() { return p_ < end_ ? *p_++ : 0; }

    float number() {
        const std::uint8_t tag = byte();
        if (tag < 0x80) return float(tag < 0x40 ? int(tag) : int(tag) - 0x80) * 0.125f;
        if (tag < 0xC0) return kSpecial[(tag - 0x80) % std::size(kSpecial)];
        if (tag < 0xF0) {
            const float mantissa = float(int(tag) - 0xC0 - 24) * 0.25f;
            return std::ldexp(mantissa, int(std::int8_t(byte())));
        }
        std::uint32_t bits = 0;
        for (int i = 0; i < 4; ++i) bits |= std::uint32_t(byte()) << (8 * i);
        return std::bit_cast<float>(bits);
    }

    glm::vec3 vec3() {
        const float x = number(), y = number();
        return {x, y, number()};
    }

    /// A barycentric coordinate: mostly the values of vertices, edges and centroids.
    float barycentric() {
        constexpr float kValues[] = {0.0f, 1.0f, 0.5f, 0.25f, 1.0f / 3.0f};
        const std::uint8_t b = byte();
        return b < 0xF0 ? kValues[b % std::size(kValues)] : number();
    }

    /// A triangle of `count`: one byte in a soup, a 16-bit fraction of the count in a fan.
    std::size_t pick(std::size_t count) {
        if (count <= 256) return byte() % count;
        const std::uint32_t fraction = byte() | std::uint32_t(byte()) << 8;
        return std::size_t((std::uint64_t(fraction) * count) >> 16);
    }

  private:
    const std::uint8_t* p_;
    const std::uint8_t* end_;
};

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Returns false when the scene has a non-finite coordinate.
bool decode_soup(Decoder& in, Scene& scene) {
    const int count = 1 + in.byte() % 16;
    for (int i = 0; i < count; ++i) {
        std::array<std::uint32_t, 3> tri;
        for (std::uint32_t& corner : tri) {
            const std::uint8_t b = in.byte();
            if (b & 0x80 && !scene.positions.empty()) {
                corner = (b & 0x7f) % scene.positions.size();
            } else {
                corner = std::uint32_t(scene.positions.size());
                scene.positions.push_back(in.vec3());
                if (!finite(scene.positions.back())) return false;
            }
        }
        scene.triangles.push_back(tri);
    }
    return true;
}

/// Bounds that keep one fan's run within a few seconds under the sanitizers (8 rays at the
/// shared vertex of 20k corners: 2-4 s on a loaded machine). 1000 corners already reach the
/// recursion's depth bound.
constexpr std::size_t kMaxFanCorners = 20'000;
constexpr int kMaxFanRays = 8;

/// One polygon triangulated as the OBJ loader does a face, a fan (0, i, i + 1): thousands of
/// slivers sharing a vertex, which made the recursion go one level deeper per few triangles
/// until the stack overflowed (faces of 100k+ corners).
struct Fan {
    std::size_t corners;
    std::uint8_t shape;  // bits 0-1 apex, 2-3 arc, 4-5 height profile, 6 squash, 7 reverse
    glm::vec3 centre;
    float radius;
    std::uint8_t jitter, seed;
};

Fan decode_fan_parameters(Decoder& in) {
    Fan fan;
    const std::uint32_t raw = in.byte() | std::uint32_t(in.byte()) << 8;
    // Quadratic: most fans are small and fast, the largest still come up.
    fan.corners =
        3 + std::size_t(std::uint64_t(raw) * raw * (kMaxFanCorners - 3) / (0xFFFFull * 0xFFFF));
    fan.shape = in.byte();
    fan.centre = in.vec3();
    fan.radius = std::ldexp(1.0f, int(std::int8_t(in.byte())) / 4);  // 2^-32 to 2^31
    fan.jitter = in.byte();
    fan.seed = in.byte();
    return fan;
}

/// A number in [-1, 1] from (seed, i) (splitmix64's finaliser).
double jitter_value(std::uint64_t seed, std::uint64_t i) {
    std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + i + 1;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1p-52 - 1.0;
}

/// Returns false when a corner is not finite.
bool build_fan(const Fan& fan, Scene& scene) {
    constexpr double kPi = 3.14159265358979323846;
    constexpr double kArcs[] = {2.0 * kPi, kPi, 1e-2, 1e-5};  // the last: nearly collinear
    const int apex = fan.shape & 3;
    const double arc = kArcs[(fan.shape >> 2) & 3];
    const int profile = (fan.shape >> 4) & 3;
    const double squash = fan.shape & 0x40 ? 0x1p-10 : 1.0;
    const double r = fan.radius;
    const double amplitude = fan.jitter == 0 ? 0.0 : r * std::ldexp(1.0, -int(fan.jitter % 40));
    const glm::dvec3 centre(fan.centre);
    // Apex 0: every corner on the arc (a convex polygon as an OBJ face); else corner 0 is the
    // centre, a cone's tip above it, or a point outside the circle (long slivers).
    const std::size_t on_arc = apex == 0 ? fan.corners : fan.corners - 1;
    scene.positions.reserve(fan.corners);
    if (apex != 0) {
        const glm::dvec3 tip = apex == 1   ? glm::dvec3(0.0)
                               : apex == 2 ? glm::dvec3(0.0, 0.0, r)
                                           : glm::dvec3(-3.0 * r, 0.0, 0.0);
        scene.positions.emplace_back(centre + tip);
    }
    for (std::size_t i = 0; i < on_arc; ++i) {
        const std::size_t k = fan.shape & 0x80 ? on_arc - 1 - i : i;
        const double angle = arc * double(k) / double(on_arc);
        double z = 0.0;
        if (profile == 1) z = 0.1 * r * std::sin(7.0 * angle);
        if (profile == 2) z = 0.1 * r * angle;  // a helix: not planar
        if (profile == 3) z = 0.2 * r * std::cos(2.0 * angle);
        glm::dvec3 p(r * std::cos(angle), squash * r * std::sin(angle), z);
        if (amplitude > 0.0)
            p += amplitude * glm::dvec3(jitter_value(fan.seed, 3 * i),
                                        jitter_value(fan.seed, 3 * i + 1),
                                        jitter_value(fan.seed, 3 * i + 2));
        scene.positions.emplace_back(centre + p);
        if (!finite(scene.positions.back())) return false;
    }
    scene.triangles.reserve(fan.corners - 2);
    for (std::uint32_t i = 1; i + 1 < fan.corners; ++i) scene.triangles.push_back({0, i, i + 1});
    return finite(scene.positions.front());
}

/// Returns false when the scene has a non-finite coordinate.
bool decode_scene(Decoder& in, Scene& scene, std::optional<Fan>& fan) {
    if (kFans) {
        fan = decode_fan_parameters(in);
        if (!build_fan(*fan, scene)) return false;
    } else if (!decode_soup(in, scene)) {
        return false;
    }
    scene.triangle_materials.assign(scene.triangles.size(), 0);
    scene.materials.emplace_back();
    return true;
}

double max_abs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

/// Far rays (issue: a ray from 1e6 away hit 60 units beside a unit triangle): the origin moved
/// back along the direction to 1e3..1e7 times the triangle's size from a point near the
/// triangle: on it, or pushed past an edge or a vertex by 2^-k of the barycentrics.
void make_far(Decoder& in, const Scene& scene, Ray& ray) {
    const Triangle tri = scene.corners(in.pick(scene.triangle_count()));
    float u = in.barycentric(), v = in.barycentric();
    const std::uint8_t nudge = in.byte();
    const float step = std::ldexp(1.0f, -int(nudge % 32));
    // Past the edge u = 0 or v = 0 (when on it), past u + v = 1, or inside near a vertex or edge.
    if ((nudge >> 5 & 3) == 0) u -= step;
    if ((nudge >> 5 & 3) == 1) v -= step;
    if ((nudge >> 5 & 3) == 2) u += step, v += step;
    if ((nudge >> 5 & 3) == 3) u += 0.5f * step;
    const glm::dvec3 target(surface_point(tri, u, v).p);
    const std::uint8_t distance = in.byte();
    const glm::dvec3 p[3] = {glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)};
    const double size =
        std::max({max_abs(p[1] - p[0]), max_abs(p[2] - p[1]), max_abs(p[0] - p[2])});
    const double length = glm::length(glm::dvec3(ray.dir));
    if (!(size > 0.0) || !(length > 0.0) || !std::isfinite(length)) return;
    const double away = std::pow(10.0, 3 + distance % 5) * (1.0 + double(distance / 5) / 64.0);
    ray.org = glm::vec3(target - glm::dvec3(ray.dir) * (away * size / length));
}

/// Directions near the shortest validate_ray() accepts (2^-64 by the longest component), up to
/// 2^-33: every distance is then a huge t. The mantissa byte 255 puts it one ulp below (refused).
void make_tiny(Decoder& in, Ray& ray) {
    const std::uint8_t exponent = in.byte(), mantissa = in.byte();
    const double longest = max_abs(glm::dvec3(ray.dir));
    if (!(longest > 0.0) || !std::isfinite(longest)) return;
    const double target = mantissa == 255 ? double(kShortestDirection) * (1.0 - 0x1p-24)
                                          : std::ldexp(1.0 + mantissa / 256.0, -64 + exponent % 32);
    ray.dir = glm::vec3(glm::dvec3(ray.dir) * (target / longest));
}

/// Up to `max_count` rays.
std::vector<Ray> decode_rays(Decoder& in, const Scene& scene, int max_count) {
    std::vector<Ray> rays;
    const int count = 1 + in.byte() % max_count;
    for (int i = 0; i < count; ++i) {
        const std::uint8_t flags = in.byte();
        Ray ray;
        switch (flags & 3) {
            case 0:
            case 3:
                ray.org = in.vec3();
                ray.dir = in.vec3();
                break;
            case 1: {  // through a point of a triangle: an edge, a vertex, the centroid
                ray.org = in.vec3();
                const Triangle tri = scene.corners(in.pick(scene.triangle_count()));
                const float u = in.barycentric(), v = in.barycentric();
                ray.dir = surface_point(tri, u, v).p - ray.org;
                break;
            }
            case 2: {  // spawned from a surface, as the renderer does
                const Triangle tri = scene.corners(in.pick(scene.triangle_count()));
                const float u = in.barycentric(), v = in.barycentric();
                ray.dir = in.vec3();
                const glm::vec3 n = unit_normal(tri);
                ray.org = offset_ray_origin(surface_point(tri, u, v), n, ray.dir);
                ray.tmin = kSpawnTmin;
                break;
            }
        }
        if (flags & 4) ray.tmin = in.number();
        if (flags & 8) ray.tmax = in.number();
        if (flags & 0x10) make_far(in, scene, ray);
        if (flags & 0x20) make_tiny(in, ray);
        const std::string problem = validate_ray(ray);
        if (problem.empty() && max_abs(glm::dvec3(ray.dir)) < double(kShortestDirection)) {
            std::fprintf(stderr, "trace_fuzzer: validate_ray accepts direction (%a %a %a)\n",
                         ray.dir.x, ray.dir.y, ray.dir.z);
            __builtin_trap();
        }
        if (problem.empty()) rays.push_back(ray);
    }
    return rays;
}

struct Candidate {
    const char* name;
    std::unique_ptr<Tracer> tracer;
    bool own_kernel = true;  // uses intersect_triangle (else Embree: may also reject the input)
    bool on_fans = true;     // false: a variant of another candidate, left out on fans (time)
};

/// Parameters that make the divide-and-conquer methods recurse even on a handful of rays and
/// triangles (the defaults brute-force anything this small).
EdacrtParams small_leaves(EdacrtParams p = {}) {
    p.leaf_rays = p.leaf_tris = p.cost_leaf_max_tris = 1;
    p.sample_threshold = 4;
    p.sample_count = 2;
    return p;
}

std::vector<Candidate>& candidates() {
    static std::vector<Candidate> list = [] {
        std::vector<Candidate> out;
        out.push_back({"edacrt", make_tracer(Method::edacrt)});
        out.push_back({"edacrt small leaves", make_tracer(Method::edacrt, small_leaves())});
        out.push_back({"dacrt small leaves", make_tracer(Method::dacrt, small_leaves())});
        out.push_back({"edacrt paper small leaves",
                       make_tracer(Method::edacrt, small_leaves(paper_params())), true, false});
        EdacrtParams other;  // the options neither preset takes
        other.order = TraversalOrder::left_first;
        other.filter_skip = FilterSkip::triangles;
        other.small_nodes = SmallNodes::surface_area;
        out.push_back({"edacrt other switches", make_tracer(Method::edacrt, small_leaves(other)),
                       true, false});
        out.push_back({"bvh", make_tracer(Method::bvh)});
#ifdef EDACRT_HAS_EMBREE
        for (const EmbreeMode mode : {EmbreeMode::single, EmbreeMode::packet8})
            out.push_back({mode == EmbreeMode::single ? "embree single" : "embree packet8",
                           make_tracer(Method::embree, {}, mode), false});
#endif
        return out;
    }();
    return list;
}

/// A decoded input.
struct Case {
    Scene scene;
    std::optional<Fan> fan;
    std::vector<Ray> rays;
};

/// The case, exactly; of a fan its parameters and the triangles `prims` (thousands of
/// triangles would drown the rays).
void print_case(const Case& c, std::initializer_list<std::int32_t> prims = {}) {
    const Scene& scene = c.scene;
    std::fprintf(stderr, "scene: %zu triangles\n", scene.triangle_count());
    const auto print_triangle = [&](std::size_t i) {
        const Triangle t = scene.corners(i);
        std::fprintf(stderr, "  tri %zu:", i);
        for (const glm::vec3& p : {t.p0, t.p1, t.p2})
            std::fprintf(stderr, " (%a %a %a)", p.x, p.y, p.z);
        std::fprintf(stderr, "\n");
    };
    if (c.fan) {
        const Fan& f = *c.fan;
        std::fprintf(stderr,
                     "  fan: %zu corners, shape 0x%02x, centre (%a %a %a), radius %a, jitter %d, "
                     "seed %d\n",
                     f.corners, f.shape, f.centre.x, f.centre.y, f.centre.z, f.radius, f.jitter,
                     f.seed);
        for (const std::int32_t prim : prims)
            if (prim >= 0) print_triangle(std::size_t(prim));
    } else {
        for (std::size_t i = 0; i < scene.triangle_count(); ++i) print_triangle(i);
    }
    for (std::size_t i = 0; i < c.rays.size(); ++i) {
        const Ray& r = c.rays[i];
        std::fprintf(stderr, "  ray %zu: org (%a %a %a) dir (%a %a %a) tmin %a tmax %a\n", i,
                     r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax);
    }
}

[[noreturn]] void violation(const Case& c, const char* method, const char* query, std::size_t ray,
                            const Hit& got, const Hit& expected, const char* what) {
    std::fprintf(stderr, "trace_fuzzer: %s, %s, ray %zu: %s\n", method, query, ray, what);
    std::fprintf(stderr, "  got t %a (%.9g) prim %d u %g v %g; naive closest t %a (%.9g) prim %d\n",
                 got.t, got.t, got.prim, got.u, got.v, expected.t, expected.t, expected.prim);
    print_case(c, {got.prim, expected.prim});
    __builtin_trap();
}

/// Whether the ray's line certainly passes outside triangle `prim`: two edge functions have
/// opposite signs beyond their bounds. An edge function is the Pluecker product
/// d . ((p - o) x (q - p)), in double from the float inputs, so the large difference from the
/// origin meets only the edge, not another large difference (d . ((p - o) x (q - o)) would
/// cancel for a small triangle far away). Its bound lets the line pass 2^-20 of the largest
/// coordinate outside the edge (the kernel's float rounding, then some) and covers double's
/// rounding of the differences. Independent of the kernels: every method, naive too, once
/// reported far rays' hits 60 units beside a unit triangle.
bool certainly_outside(const Scene& scene, const Ray& ray, std::int32_t prim) {
    const Triangle tri = scene.corners(std::size_t(prim));
    const glm::dvec3 org(ray.org), dir(ray.dir);
    const glm::dvec3 corners[3] = {glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)};
    bool positive = false, negative = false;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 &p = corners[k], &q = corners[(k + 1) % 3];
        const glm::dvec3 edge = q - p;
        const double e = glm::dot(dir, glm::cross(p - org, edge));
        const double scale = std::max({max_abs(p), max_abs(q), max_abs(org)});
        const double from_origin = max_abs(p) + max_abs(org), edge_size = max_abs(edge);
        const double bound =
            max_abs(dir) * (0x1p-20 * scale * edge_size +
                            0x1p-48 * from_origin * (edge_size + max_abs(p) + max_abs(q)));
        positive |= e > bound;
        negative |= e < -bound;
    }
    return positive && negative;
}

/// Why a hit record is invalid for `ray`; null when it is fine.
const char* invalid_record(const Scene& scene, const Hit& hit, const Ray& ray, bool own_kernel) {
    if (hit.prim < -1 || hit.prim >= std::int64_t(scene.triangle_count()))
        return "prim out of range";
    if (!hit.hit()) return nullptr;
    if (!std::isfinite(hit.t)) return "non-finite t";
    if (!(hit.t >= ray.tmin && hit.t <= ray.tmax)) return "t outside [tmin, tmax]";
    // Every method, Embree's clamped hits too (a far ray's hit once came with u = 1008).
    constexpr float kSlack = 1e-6f;
    if (!(hit.u >= -kSlack && hit.v >= -kSlack && hit.u + hit.v <= 1.0f + kSlack))
        return "barycentrics outside the triangle";
    // Embree's inside test is its own (its hit is only clamped into the triangle).
    if (own_kernel && certainly_outside(scene, ray, hit.prim))
        return "hit on a triangle the ray's line certainly misses";
    return nullptr;
}

/// Where the ray meets triangle `prim`'s plane, in double: the distance t, and the scale of
/// single-precision rounding there (1e-5 of the largest coordinate involved, along the normal).
struct PlaneHit {
    double t;
    double tolerance;      // of t
    bool ill_conditioned;  // grazing, or within `tolerance` of an edge, the origin, tmin or tmax
};

PlaneHit plane_hit(const Scene& scene, const Ray& ray, std::int32_t prim) {
    const Triangle tri = scene.corners(std::size_t(prim));
    const glm::dvec3 p[3] = {glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)};
    const glm::dvec3 org(ray.org), dir(ray.dir);
    // The normal from the two shorter edges, at the vertex they share: the long edge's
    // difference may round (a tiny corner beside a large one) and cancel in the cross product.
    int longest = 0;
    double edge_length[3];
    for (int k = 0; k < 3; ++k) {
        edge_length[k] = glm::length(p[(k + 1) % 3] - p[k]);
        if (edge_length[k] > edge_length[longest]) longest = k;
    }
    const glm::dvec3 apex = p[(longest + 2) % 3];
    const glm::dvec3 n = glm::cross(p[longest] - apex, p[(longest + 1) % 3] - apex);
    const double length = glm::length(dir);
    const double t = glm::dot(n, apex - org) / glm::dot(n, dir);
    const glm::dvec3 q = org + t * dir;
    const double reach =
        1e-5 * std::max({max_abs(p[0]), max_abs(p[1]), max_abs(p[2]), max_abs(org), max_abs(q)});
    const double cosine = std::abs(glm::dot(n, dir)) / (glm::length(n) * length);
    PlaneHit out{t, reach / (length * cosine), false};
    // Thinner than the rounding (or degenerate: NaN), or grazing.
    if (!(glm::length(n) > reach * edge_length[longest])) out.ill_conditioned = true;
    if (!(cosine > 1e-3)) out.ill_conditioned = true;
    for (const double bound : {0.0, double(ray.tmin), double(ray.tmax)})
        if (std::abs(t - bound) <= out.tolerance) out.ill_conditioned = true;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 a = p[k], edge = p[(k + 1) % 3] - a;
        if (!(glm::length(glm::cross(edge, q - a)) > reach * edge_length[k]))
            out.ill_conditioned = true;
    }
    return out;
}

/// Whether a kernel with its own rounding (Embree's) may legitimately disagree with ours: one of
/// the two hits is ill-conditioned for the ray, or both hit within rounding of each other.
/// Embree also reports hits at t = 0 from an origin on a triangle when tmin = 0 (our kernel
/// rejects t within its rounding bound of 0): covered by the origin clause.
bool rounding_may_differ(const Scene& scene, const Ray& ray, const Hit& got, const Hit& expected,
                         Query query) {
    if (got.hit() && plane_hit(scene, ray, got.prim).ill_conditioned) return true;
    if (!expected.hit()) return false;
    const PlaneHit reference = plane_hit(scene, ray, expected.prim);
    if (reference.ill_conditioned) return true;
    return query == Query::closest && got.hit() &&
           std::abs(double(got.t) - double(expected.t)) <= reference.tolerance;
}

/// A hit within its float rounding of tmin or tmax may be decided either way: the triangle test
/// decides on its float t, a box test (conservative against the exact segment) on the exact t
/// (found by this fuzzer: origin at z = 1e38, tmin = tmax = naive's t, the exact t 1 ulp beyond).
bool at_segment_end(const Ray& ray, const Hit& got, const Hit& expected) {
    for (const Hit* hit : {&got, &expected})
        if (hit->hit() && std::min(std::abs(hit->t - ray.tmin), std::abs(hit->t - ray.tmax)) <=
                              kTrustedDistanceError * hit->t)
            return true;
    return false;
}

bool print_cases = false;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // One thread: reproducible runs, and the batches are far too small to split anyway.
    static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    print_cases = std::getenv("EDACRT_FUZZ_PRINT") != nullptr;
    candidates();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Decoder in(data, size);
    Case c;
    if (!decode_scene(in, c.scene, c.fan)) return 0;
    // A fan costs up to 160 recursion levels over all its triangles per ray and method.
    c.rays = decode_rays(in, c.scene, c.fan ? kMaxFanRays : 16);
    if (c.rays.empty()) return 0;
    if (print_cases) print_case(c);
    const Scene& scene = c.scene;
    const std::vector<Ray>& rays = c.rays;

    static const auto naive = make_tracer(Method::naive);
    naive->set_scene(scene);
    std::vector<Hit> expected(rays.size()), got(rays.size());
    naive->trace(rays, expected, Query::closest);
    naive->trace(rays, got, Query::any);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (const char* why = invalid_record(scene, expected[i], rays[i], true))
            violation(c, "naive", "closest hit", i, expected[i], expected[i], why);
        if (const char* why = invalid_record(scene, got[i], rays[i], true))
            violation(c, "naive", "any hit", i, got[i], expected[i], why);
        if (got[i].hit() != expected[i].hit())
            violation(c, "naive", "any hit", i, got[i], expected[i],
                      "hit/miss differs from closest hit");
    }

    for (Candidate& candidate : candidates()) {
        if (c.fan && !candidate.on_fans) continue;
        const char* name = candidate.name;
        const auto start = std::chrono::steady_clock::now();
        try {
            candidate.tracer->set_scene(scene);
        } catch (const InputError& e) {
            if (!candidate.own_kernel) continue;
            violation(c, name, "set_scene", 0, Hit{}, Hit{}, e.what());
        }
        for (const Query query : {Query::closest, Query::any}) {
            const char* query_name = query == Query::closest ? "closest hit" : "any hit";
            try {
                candidate.tracer->trace(rays, got, query);
            } catch (const InputError& e) {
                if (!candidate.own_kernel) break;
                violation(c, name, query_name, 0, Hit{}, Hit{}, e.what());
            }
            for (std::size_t i = 0; i < rays.size(); ++i) {
                if (const char* why = invalid_record(scene, got[i], rays[i], candidate.own_kernel))
                    violation(c, name, query_name, i, got[i], expected[i], why);
                const bool differs =
                    got[i].hit() != expected[i].hit() ||
                    (query == Query::closest && got[i].hit() &&
                     !(std::abs(got[i].t - expected[i].t) <= 1e-6f * std::abs(expected[i].t)));
                if (differs && !at_segment_end(rays[i], got[i], expected[i]) &&
                    (candidate.own_kernel ||
                     !rounding_may_differ(scene, rays[i], got[i], expected[i], query)))
                    violation(c, name, query_name, i, got[i], expected[i],
                              got[i].hit() != expected[i].hit()
                                  ? "hit/miss differs from naive closest hit"
                                  : "t differs from naive");
            }
        }
        if (print_cases)
            std::fprintf(
                stderr, "  %s: %.3f s\n", name,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return 0;
}
