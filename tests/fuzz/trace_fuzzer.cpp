// libFuzzer target: a small triangle soup and a few rays decoded from the input, traced with
// every method for closest and any hit. Checked: every hit has a finite t in [tmin, tmax] and a
// valid prim; each method's closest hit agrees with naive's (hit or miss, and t, not prim: ties
// between triangles at the same t are allowed); any hit agrees with naive's closest hit or miss.
// A violation prints the case exactly (hex floats) and traps.
//
// Input format (every read past the end yields 0 bytes):
//   byte: triangle count - 1 (mod 16); per corner a byte: top bit set reuses an earlier vertex
//   (the byte picks which), so edges and vertices are shared, else a new vertex of 3 numbers;
//   byte: ray count - 1 (mod 16); per ray a byte: the kind (low 2 bits: free, aimed at a point of
//   a triangle, spawned from a point of a triangle with the renderer's offset), whether tmin and
//   tmax are given (bits 2, 3), then the kind's numbers and bytes.
//   A number is a tag byte: < 0x80 a multiple of 1/8 in [-8, 8) (0 for 0); < 0xC0 a special value
//   (zeros, extremes, denormals, inf, NaN); < 0xF0 a small multiple of 1/4 scaled by 2^(next byte
//   as int8); else the next 4 bytes as a float's bits.
// Scenes with non-finite coordinates (the OBJ loader rejects them) and rays validate_ray()
// rejects are skipped. Degenerate triangles are kept: a tracer must never hit them.
//
// Environment: EDACRT_FUZZ_PRINT=1 prints every decoded case (to read a reproducer).
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <vector>

#include "geometry/offset.h"
#include "scene/scene.h"
#include "trace/ray_file.h"
#include "trace/tracer.h"
#include "util/error.h"

namespace {

using namespace edacrt;

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

  private:
    const std::uint8_t* p_;
    const std::uint8_t* end_;
};

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Returns false when the scene has a non-finite coordinate.
bool decode_scene(Decoder& in, Scene& scene) {
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
    scene.triangle_materials.assign(scene.triangles.size(), 0);
    scene.materials.emplace_back();
    return true;
}

std::vector<Ray> decode_rays(Decoder& in, const Scene& scene) {
    std::vector<Ray> rays;
    const int count = 1 + in.byte() % 16;
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
                const Triangle tri = scene.corners(in.byte() % scene.triangle_count());
                const float u = in.barycentric(), v = in.barycentric();
                ray.dir = surface_point(tri, u, v).p - ray.org;
                break;
            }
            case 2: {  // spawned from a surface, as the renderer does
                const Triangle tri = scene.corners(in.byte() % scene.triangle_count());
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
        if (validate_ray(ray).empty()) rays.push_back(ray);
    }
    return rays;
}

struct Candidate {
    const char* name;
    std::unique_ptr<Tracer> tracer;
    bool own_kernel = true;  // uses intersect_triangle (else Embree: may also reject the input)
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
                       make_tracer(Method::edacrt, small_leaves(paper_params()))});
        EdacrtParams other;  // the options neither preset takes
        other.order = TraversalOrder::left_first;
        other.filter_skip = FilterSkip::triangles;
        other.small_nodes = SmallNodes::surface_area;
        out.push_back({"edacrt other switches", make_tracer(Method::edacrt, small_leaves(other))});
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

void print_case(const Scene& scene, const std::vector<Ray>& rays) {
    std::fprintf(stderr, "scene: %zu triangles\n", scene.triangle_count());
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
        const Triangle t = scene.corners(i);
        std::fprintf(stderr, "  tri %zu:", i);
        for (const glm::vec3& p : {t.p0, t.p1, t.p2})
            std::fprintf(stderr, " (%a %a %a)", p.x, p.y, p.z);
        std::fprintf(stderr, "\n");
    }
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Ray& r = rays[i];
        std::fprintf(stderr, "  ray %zu: org (%a %a %a) dir (%a %a %a) tmin %a tmax %a\n", i,
                     r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax);
    }
}

[[noreturn]] void violation(const Scene& scene, const std::vector<Ray>& rays, const char* method,
                            const char* query, std::size_t ray, const Hit& got, const Hit& expected,
                            const char* what) {
    std::fprintf(stderr, "trace_fuzzer: %s, %s, ray %zu: %s\n", method, query, ray, what);
    std::fprintf(stderr, "  got t %a (%.9g) prim %d u %g v %g; naive closest t %a (%.9g) prim %d\n",
                 got.t, got.t, got.prim, got.u, got.v, expected.t, expected.t, expected.prim);
    print_case(scene, rays);
    __builtin_trap();
}

/// Why a hit record is invalid for `ray`; null when it is fine.
const char* invalid_record(const Hit& hit, const Ray& ray, std::size_t triangles) {
    if (hit.prim < -1 || hit.prim >= std::int64_t(triangles)) return "prim out of range";
    if (!hit.hit()) return nullptr;
    if (!std::isfinite(hit.t)) return "non-finite t";
    if (!(hit.t >= ray.tmin && hit.t <= ray.tmax)) return "t outside [tmin, tmax]";
    return nullptr;
}

double max_abs(const glm::dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
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
    Scene scene;
    if (!decode_scene(in, scene)) return 0;
    const std::vector<Ray> rays = decode_rays(in, scene);
    if (rays.empty()) return 0;
    if (print_cases) print_case(scene, rays);

    static const auto naive = make_tracer(Method::naive);
    naive->set_scene(scene);
    std::vector<Hit> expected(rays.size()), got(rays.size());
    naive->trace(rays, expected, Query::closest);
    naive->trace(rays, got, Query::any);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (const char* why = invalid_record(expected[i], rays[i], scene.triangle_count()))
            violation(scene, rays, "naive", "closest hit", i, expected[i], expected[i], why);
        if (const char* why = invalid_record(got[i], rays[i], scene.triangle_count()))
            violation(scene, rays, "naive", "any hit", i, got[i], expected[i], why);
        if (got[i].hit() != expected[i].hit())
            violation(scene, rays, "naive", "any hit", i, got[i], expected[i],
                      "hit/miss differs from closest hit");
    }

    for (Candidate& c : candidates()) {
        try {
            c.tracer->set_scene(scene);
        } catch (const InputError& e) {
            if (!c.own_kernel) continue;
            violation(scene, rays, c.name, "set_scene", 0, Hit{}, Hit{}, e.what());
        }
        for (const Query query : {Query::closest, Query::any}) {
            const char* query_name = query == Query::closest ? "closest hit" : "any hit";
            try {
                c.tracer->trace(rays, got, query);
            } catch (const InputError& e) {
                if (!c.own_kernel) break;
                violation(scene, rays, c.name, query_name, 0, Hit{}, Hit{}, e.what());
            }
            for (std::size_t i = 0; i < rays.size(); ++i) {
                if (const char* why = invalid_record(got[i], rays[i], scene.triangle_count()))
                    violation(scene, rays, c.name, query_name, i, got[i], expected[i], why);
                const bool differs =
                    got[i].hit() != expected[i].hit() ||
                    (query == Query::closest && got[i].hit() &&
                     !(std::abs(got[i].t - expected[i].t) <= 1e-6f * std::abs(expected[i].t)));
                if (differs && !at_segment_end(rays[i], got[i], expected[i]) &&
                    (c.own_kernel ||
                     !rounding_may_differ(scene, rays[i], got[i], expected[i], query)))
                    violation(scene, rays, c.name, query_name, i, got[i], expected[i],
                              got[i].hit() != expected[i].hit()
                                  ? "hit/miss differs from naive closest hit"
                                  : "t differs from naive");
            }
        }
    }
    return 0;
}
