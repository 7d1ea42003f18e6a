#include "trace/ray_stream.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "util/frame_memory.h"

namespace edacrt {

void RayStreamStorage::FreeAligned::operator()(float* p) const { free_frame_memory(p); }

RayStream RayStreamStorage::reserve(std::size_t n) {
    if (n > capacity_) {
        // Each array starts on a 64-byte line, and the nine start 448 bytes apart modulo 4 KiB:
        // arrays a multiple of 4 KiB apart make the kernels' loads wait on unrelated stores to
        // the same offset of another array (4K aliasing), which doubled the filter's time.
        const std::size_t capacity = (n + 1023) / 1024 * 1024 + 112;
        // On 2 MiB pages when large: a fresh stream's 4 KiB page faults were a tenth of a bunny
        // frame.
        data_.reset(
            static_cast<float*>(allocate_frame_memory(capacity * RayStream::kBytesPerRay, 64)));
        capacity_ = capacity;
    }
    float* base = data_.get();
    const auto array = [&](int k) { return base + std::size_t(k) * capacity_; };
    const RayStream s{{array(0), array(1), array(2)},
                      {array(3), array(4), array(5)},
                      array(6),
                      array(7),
                      reinterpret_cast<std::uint32_t*>(array(8))};
    return s;
}

RayStream RayStreamStorage::fill(std::span<const Ray> rays) {
    const std::size_t n = rays.size();
    const RayStream s = reserve(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Ray& ray = rays[i];
            for (int k = 0; k < 3; ++k) {
                s.org[k][i] = ray.org[k];
                s.dir[k][i] = ray.dir[k];
            }
            s.tmin[i] = ray.tmin;
            s.t_far[i] = ray.tmax;
            s.id[i] = std::uint32_t(i);
        }
    });
    return s;
}

RayStream RayStreamStorage::fill(const RayStream& from, std::size_t begin, std::size_t count) {
    const RayStream s = reserve(count);
    copy_rays(from, begin, s, 0, count);
    return s;
}

void copy_rays(const RayStream& from, std::size_t from_begin, const RayStream& to,
               std::size_t to_begin, std::size_t count) {
    const auto copy = [&](const auto* a, auto* b) {
        std::copy_n(a + from_begin, count, b + to_begin);
    };
    for (int k = 0; k < 3; ++k) {
        copy(from.org[k], to.org[k]);
        copy(from.dir[k], to.dir[k]);
    }
    copy(from.tmin, to.tmin);
    copy(from.t_far, to.t_far);
    copy(from.id, to.id);
}

}  // namespace edacrt
