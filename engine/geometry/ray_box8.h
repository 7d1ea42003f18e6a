#pragma once
// intersect_box (ray_box.h) on eight lanes of AVX2, bit for bit: the same operations in the
// same order, so a ray passes a box in the 8-wide kernels exactly when it passes the scalar
// test. A lane is any ray/box pair: the filter broadcasts one box over eight rays, the ray
// sampling one ray over eight candidate boxes.
#include <immintrin.h>

#include "geometry/ray_box.h"

namespace edacrt {

/// The lanes' rays and boxes, one register per coordinate.
struct SlabRay8 {
    __m256 org[3], inv_dir[3], tmin, t_far;
};
struct Aabb8 {
    __m256 lo[3], hi[3];
};

/// All-ones in the lanes whose ray passes its box; t_entry as in intersect_box.
/// max_ps(a, b) is `a > b ? a : b` and min_ps(a, b) `a < b ? a : b`, the scalar test's choices,
/// so a NaN distance never replaces a bound here either; blendv on the sign bit of 1/dir picks
/// the near and far planes as signbit() does.
[[gnu::always_inline]] inline __m256 intersect_box8(const SlabRay8& ray, const Aabb8& box,
                                                    __m256& t_entry) {
    const __m256 widen = _mm256_set1_ps(1.0f + 2.0f * gamma_bound(3));
    __m256 t0 = ray.tmin, t1 = ray.t_far;
    for (int axis = 0; axis < 3; ++axis) {
        const __m256 near_plane = _mm256_blendv_ps(box.lo[axis], box.hi[axis], ray.inv_dir[axis]);
        const __m256 far_plane = _mm256_blendv_ps(box.hi[axis], box.lo[axis], ray.inv_dir[axis]);
        const __m256 t_near_axis =
            _mm256_mul_ps(_mm256_sub_ps(near_plane, ray.org[axis]), ray.inv_dir[axis]);
        const __m256 t_far_axis = _mm256_mul_ps(
            _mm256_mul_ps(_mm256_sub_ps(far_plane, ray.org[axis]), ray.inv_dir[axis]), widen);
        t0 = _mm256_max_ps(t_near_axis, t0);
        t1 = _mm256_min_ps(t_far_axis, t1);
    }
    t_entry = t0;
    return _mm256_cmp_ps(t0, t1, _CMP_LE_OQ);
}

/// One box in every lane.
inline Aabb8 broadcast(const Aabb& box) {
    Aabb8 b;
    for (int k = 0; k < 3; ++k) {
        b.lo[k] = _mm256_set1_ps(box.lo[k]);
        b.hi[k] = _mm256_set1_ps(box.hi[k]);
    }
    return b;
}

/// One ray in every lane.
inline SlabRay8 broadcast(const SlabRay& ray, float t_far) {
    SlabRay8 r;
    for (int k = 0; k < 3; ++k) {
        r.org[k] = _mm256_set1_ps(ray.org[k]);
        r.inv_dir[k] = _mm256_set1_ps(ray.inv_dir[k]);
    }
    r.tmin = _mm256_set1_ps(ray.tmin);
    r.t_far = _mm256_set1_ps(t_far);
    return r;
}

}  // namespace edacrt
