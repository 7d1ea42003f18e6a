#pragma once
// The robust slab test (ray_box.h) on eight boxes at once with AVX2 (the build's baseline is
// x86-64-v3): the same operations in the same order, so each lane decides exactly as
// intersect_box() does for that box.
#include <immintrin.h>

#include "geometry/ray_box.h"

namespace edacrt {

/// Eight boxes, structure of arrays. An unused lane holds the empty box (lo = +inf, hi = -inf):
/// its near distance is +inf and its far distance -inf on every axis (never NaN, as the
/// origin is finite and 1/dir is not zero), so it is never hit.
struct alignas(32) Boxes8 {
    float lo[3][8];
    float hi[3][8];
};

/// A ray prepared for intersect_boxes8: per axis, which side is near (by the sign of 1/dir),
/// and the origin and 1/dir in all lanes.
struct SlabRay8 {
    __m256 org[3];
    __m256 inv_dir[3];
    bool negative[3];
    float tmin;
};

inline SlabRay8 make_slab_ray8(const SlabRay& ray) {
    SlabRay8 r;
    for (int axis = 0; axis < 3; ++axis) {
        r.org[axis] = _mm256_set1_ps(ray.org[axis]);
        r.inv_dir[axis] = _mm256_set1_ps(ray.inv_dir[axis]);
        r.negative[axis] = std::signbit(ray.inv_dir[axis]);
    }
    r.tmin = ray.tmin;
    return r;
}

/// intersect_box() for each lane over [ray.tmin, t_far]: bit i of the result is set when box i
/// is hit, and lane i of t_entry is its entry distance. MAXPS and MINPS return their second
/// operand when either is NaN, so a NaN distance (origin on the plane of an axis the ray is
/// parallel to) leaves the bound unchanged, as the scalar test's ordered comparisons do.
[[gnu::always_inline]] inline int intersect_boxes8(const SlabRay8& ray, const Boxes8& boxes,
                                                   float t_far, __m256& t_entry) {
    const __m256 scale = _mm256_set1_ps(1.0f + 2.0f * gamma_bound(3));
    __m256 t0 = _mm256_set1_ps(ray.tmin);
    __m256 t1 = _mm256_set1_ps(t_far);
    for (int axis = 0; axis < 3; ++axis) {
        const float* near_plane = ray.negative[axis] ? boxes.hi[axis] : boxes.lo[axis];
        const float* far_plane = ray.negative[axis] ? boxes.lo[axis] : boxes.hi[axis];
        const __m256 t_near_axis = _mm256_mul_ps(
            _mm256_sub_ps(_mm256_load_ps(near_plane), ray.org[axis]), ray.inv_dir[axis]);
        const __m256 t_far_axis =
            _mm256_mul_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(far_plane), ray.org[axis]),
                                        ray.inv_dir[axis]),
                          scale);
        t0 = _mm256_max_ps(t_near_axis, t0);
        t1 = _mm256_min_ps(t_far_axis, t1);
    }
    t_entry = t0;
    return _mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
}

}  // namespace edacrt
