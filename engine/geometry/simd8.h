#pragma once
// Eight-lane AVX2 helpers shared by the kernels (triangle8.h, ray_sampling.h, leaf_kernels.h),
// named after the scalar operations they stand for.
#include <immintrin.h>

namespace edacrt::simd8 {

inline __m256 set(float x) { return _mm256_set1_ps(x); }
inline __m256 abs(__m256 x) { return _mm256_andnot_ps(set(-0.0f), x); }
inline __m256 mul(__m256 a, __m256 b) { return _mm256_mul_ps(a, b); }
inline __m256 add(__m256 a, __m256 b) { return _mm256_add_ps(a, b); }
inline __m256 sub(__m256 a, __m256 b) { return _mm256_sub_ps(a, b); }
inline __m256 any(__m256 a, __m256 b) { return _mm256_or_ps(a, b); }
inline __m256 any(__m256 a, __m256 b, __m256 c) { return any(any(a, b), c); }
inline __m256 all(__m256 a, __m256 b) { return _mm256_and_ps(a, b); }
inline __m256 all(__m256 a, __m256 b, __m256 c) { return all(all(a, b), c); }
/// std::max(a, b), i.e. a < b ? b : a: a NaN in a is kept, as in the scalar code.
inline __m256 max(__m256 a, __m256 b) { return _mm256_max_ps(b, a); }
/// std::max({a, b, c}).
inline __m256 max(__m256 a, __m256 b, __m256 c) { return max(max(a, b), c); }
template <int Cmp>
inline __m256 cmp(__m256 a, __m256 b) {
    return _mm256_cmp_ps(a, b, Cmp);
}

/// Bit l of a mask to all-ones in lane l.
inline __m256 lane_mask(unsigned mask) {
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_castsi256_ps(
        _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(mask)), bits), bits));
}

}  // namespace edacrt::simd8
