#pragma once
// The rays of one divide-and-conquer batch as a structure of arrays. The recursion partitions
// the stream in place, so every node's rays are one contiguous range that the kernels load
// eight at a time (gathers by ray index were slower than scalar code on AVX2 machines).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "geometry/ray.h"
#include "geometry/ray_box.h"

namespace edacrt {

/// Views of the stream's arrays: the ray and its current search distance, plus its index in
/// the batch, which travels with it. The direction itself, not its inverse, so that the leaves
/// need nothing else (the filter divides, which is hidden by its memory traffic).
struct RayStream {
    float* org[3];
    float* dir[3];
    float* tmin;
    float* t_far;  // tmax, then the t of the ray's hit (changed only with it: the leaves'
                   // kSkipsCurrentHit relies on that); -inf once an any-hit ray is done, which
                   // removes it from every later filter and leaf
    std::uint32_t* id;

    /// Bytes per ray: origin, direction, tmin, t_far and the id.
    static constexpr std::size_t kBytesPerRay = 9 * 4;

    /// The ray as traced, with tmax = its current t_far.
    Ray ray(std::size_t i) const {
        return {{org[0][i], org[1][i], org[2][i]},
                {dir[0][i], dir[1][i], dir[2][i]},
                tmin[i],
                t_far[i]};
    }
    SlabRay slab_ray(std::size_t i) const { return make_slab_ray(ray(i)); }
};

/// Copies rays [from_begin, + count) of `from` over `to`'s from to_begin, all nine arrays.
void copy_rays(const RayStream& from, std::size_t from_begin, const RayStream& to,
               std::size_t to_begin, std::size_t count);

/// One batch: the stream the recursion partitions, and the hits, indexed by the ray's number
/// (its id in the stream).
struct RayBatch {
    RayStream stream;
    Hit* hits;
};

/// The storage behind a RayStream, kept between batches so that a batch no larger than the
/// last one allocates nothing.
class RayStreamStorage {
  public:
    /// Fills the stream with `rays` in order (in parallel), t_far = tmax, and returns it.
    RayStream fill(std::span<const Ray> rays);
    /// Fills the stream with rays [begin, begin + count) of `from` as they are now (t_far and
    /// numbers included; sequential: for a part of a recursion), and returns it.
    RayStream fill(const RayStream& from, std::size_t begin, std::size_t count);
    std::size_t bytes() const { return capacity_ * RayStream::kBytesPerRay; }

  private:
    /// The stream's arrays for `n` rays, reallocated only to grow.
    RayStream reserve(std::size_t n);

    struct FreeAligned {
        void operator()(float* p) const;
    };
    std::unique_ptr<float[], FreeAligned> data_;
    std::size_t capacity_ = 0;
};

}  // namespace edacrt
