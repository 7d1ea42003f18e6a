#pragma once
// Top-down binned-SAH BVH construction (Wald, "On fast Construction of SAH-based Bounding
// Volume Hierarchies", 2007) over references: a box and the triangle it stands for.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/aabb.h"

namespace edacrt {

/// 32 bytes. A leaf when count > 0 (references first .. first + count - 1 of Bvh::prims);
/// otherwise its children are nodes first and first + 1, stored side by side.
struct BvhNode {
    Aabb box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};
static_assert(sizeof(BvhNode) == 32);

/// A triangle's box (conservative_bounds) and number.
struct BvhReference {
    Aabb box;
    std::uint32_t prim = 0;
};

/// Costs in units of one ray-triangle test, per ray reaching a node.
struct BvhBuildOptions {
    int bins = 4;                    // per axis; all three axes are binned (the sweep's best)
    std::uint32_t max_leaf = 8;      // larger nodes are always split
    float traversal_cost = 1.0f;     // visiting an inner node: its two box tests
    float intersection_cost = 1.0f;  // one ray-triangle test
};

/// Sets one option from `key=value` text, for variants of the baseline (edacrt bench --methods
/// bvh:bins=8:max-leaf=4): bins, max-leaf, c-t (traversal_cost; C_I = 1 is the unit). Throws
/// InputError naming the option and its range.
void set_bvh_option(BvhBuildOptions& options, std::string_view key, std::string_view text);

struct Bvh {
    std::vector<BvhNode> nodes;        // nodes[0] is the root; depth-first, left child first
    std::vector<std::uint32_t> prims;  // the references' triangles, grouped by leaf
};

/// Deepest node of a built BVH is at this depth - 1 (the traversal stack is sized for it).
inline constexpr int kBvhMaxDepth = 64;

/// Builds the BVH in parallel (oneTBB); the result is the same for any thread count. Nodes that
/// cannot be split by the SAH (all centroids in one point, areas that overflow) or lie deep
/// are split at the median centroid, so a node larger than max_leaf is a leaf only at the
/// maximum depth.
Bvh build_bvh(std::span<const BvhReference> references, const BvhBuildOptions& options = {});

}  // namespace edacrt
