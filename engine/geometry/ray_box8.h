#pragma once
// The robust slab test (ray_box.h) on eight lanes with AVX2 (the build's baseline is
// x86-64-v3), bit for bit: the same operations in the same order, so each lane decides exactly
// as intersect_box() does. Two shapes: one ray against eight boxes (the BVH's children, the
// sampling's candidate boxes), and eight rays against one box each (the filter).
// MAXPS and MINPS return their second operand when either is NaN and are otherwise
// `a > b ? a : b`, `a < b ? a : b`: the scalar test's choices, so a NaN distance (origin on the
// plane of an axis the ray is parallel to) leaves the bound unchanged here too.
#include <immintrin.h>

#include <cmath>

#include "geometry/ray_box.h"

namespace edacrt {

/// Eight boxes, structure of arrays. An unused lane holds the empty box (lo = +inf, hi = -inf):
/// its near distance is +inf and its far distance -inf on every axis (never NaN, as the
/// origin is finite and 1/dir is not zero), so it is never hit.
struct alignas(32) Boxes8 {
    float lo[3][8];
    float hi[3][8];
};

inline void set_lane(Boxes8& boxes, int lane, const Aabb& box) {
    for (int axis = 0; axis < 3; ++axis) {
        boxes.lo[axis][lane] = box.lo[axis];
        boxes.hi[axis][lane] = box.hi[axis];
    }
}

inline Aabb lane_box(const Boxes8& boxes, int lane) {
    Aabb box;
    for (int axis = 0; axis < 3; ++axis) {
        box.lo[axis] = boxes.lo[axis][lane];
        box.hi[axis] = boxes.hi[axis][lane];
    }
    return box;
}

/// box(0) .. box(count - 1) (count <= 8) in lanes 0, 1, ..., the empty box in the others.
template <class BoxAt>
Boxes8 pack_boxes8(int count, const BoxAt& box) {
    Boxes8 boxes;
    for (int lane = 0; lane < 8; ++lane) set_lane(boxes, lane, lane < count ? box(lane) : Aabb{});
    return boxes;
}

/// One ray prepared for intersect_boxes8: per axis, which side is near (by the sign of 1/dir),
/// and the origin and 1/dir in all lanes.
struct SlabRay1x8 {
    __m256 org[3];
    __m256 inv_dir[3];
    bool negative[3];
    float tmin;
};

inline SlabRay1x8 make_slab_ray1x8(const SlabRay& ray) {
    SlabRay1x8 r;
    for (int axis = 0; axis < 3; ++axis) {
        r.org[axis] = _mm256_set1_ps(ray.org[axis]);
        r.inv_dir[axis] = _mm256_set1_ps(ray.inv_dir[axis]);
        r.negative[axis] = std::signbit(ray.inv_dir[axis]);
    }
    r.tmin = ray.tmin;
    return r;
}

/// intersect_box() for each box over [ray.tmin, t_far]: bit i of the result is set when box i
/// is hit, and lane i of t_entry is its entry distance.
[[gnu::always_inline]] inline int intersect_boxes8(const SlabRay1x8& ray, const Boxes8& boxes,
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

/// Eight rays, one register per coordinate.
struct SlabRay8 {
    __m256 org[3], inv_dir[3], tmin, t_far;
};

/// Eight boxes in registers (one box broadcast, for the filter).
struct Aabb8 {
    __m256 lo[3], hi[3];
};

inline Aabb8 broadcast(const Aabb& box) {
    Aabb8 b;
    for (int k = 0; k < 3; ++k) {
        b.lo[k] = _mm256_set1_ps(box.lo[k]);
        b.hi[k] = _mm256_set1_ps(box.hi[k]);
    }
    return b;
}

/// intersect_box() for lane i's ray and box over [tmin, t_far]: all-ones in the lanes that
/// hit, t_entry as in intersect_box. Blendv on the sign bit of 1/dir picks each lane's near and
/// far planes as signbit() does.
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

}  // namespace edacrt
