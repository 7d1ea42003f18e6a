#pragma once
#include <cstdint>

namespace edacrt {

/// Parameters of EDACRT (Nabata, Iwasaki, Dobashi, Nishita, HPG 2013). With sampling off the
/// same recursion is object-partitioning DACRT (Afra 2012): surface-area ratios instead of
/// sampled hit ratios, rays always filtered, near child chosen by the rays' direction sign.
struct EdacrtParams {
    int bins = 8;  // K: K - 1 candidate splits per node (Wald 2007); 8 measured faster than 16
    std::uint32_t sample_threshold = 1000;  // nodes with more rays than this sample them...
    std::uint32_t sample_count = 100;       // ...drawing this many; smaller nodes use all rays
    std::uint32_t leaf_rays = 16;           // brute force when rays <= leaf_rays...
    std::uint32_t leaf_tris = 16;           // ...or triangles <= leaf_tris
    // The cost test may end the recursion only in nodes with at most this many triangles: it
    // prices both children as leaves, so when the rays start inside overlapping child boxes
    // (alpha ~ 1 for both) it would otherwise make leaves of the whole scene.
    std::uint32_t cost_leaf_max_tris = 64;
    float cost_traversal = 2.0f;  // C_T: per-ray cost of a split (two box tests)
    float cost_intersect = 1.0f;  // C_I: one ray-triangle test
    float cost_filter = 1.0f;     // C_bv: filtering one ray against a child box
    float cost_child = 1.0f;      // C_child: per-triangle cost of an unfiltered ray
    bool filter_skip = true;      // skip filtering when alpha > 1 - C_bv/(n C_child)
    bool sampling = true;         // off: DACRT's surface-area ratios
    std::uint32_t seed = 1;       // of the per-node ray sampling

    bool operator==(const EdacrtParams&) const = default;
};

/// Parameters of the DACRT baseline: `params` with sampling and filter skipping off.
inline EdacrtParams dacrt_params(EdacrtParams params = {}) {
    params.sampling = false;
    params.filter_skip = false;
    return params;
}

/// Throws InputError naming the first parameter out of range.
void validate(const EdacrtParams& params);

}  // namespace edacrt
