#pragma once
// An 8-wide BVH collapsed from the binary one, so that one AVX2 slab test (ray_box8.h) decides
// a node's children: the layout of Embree's BVH8 (Wald et al., "Embree: A Kernel Framework for
// Efficient CPU Ray Tracing", 2014) without its compression.
#include <cstdint>
#include <vector>

#include "geometry/ray_box8.h"
#include "trace/bvh_build.h"

namespace edacrt {

/// 256 bytes. Lane i is an inner child (node child[i]) when count[i] == 0 and its box is not
/// empty, a leaf (references child[i] .. child[i] + count[i] - 1 of Bvh::prims) otherwise;
/// children fill lanes 0, 1, ... and the rest hold empty boxes.
struct Bvh8Node {
    Boxes8 boxes;
    std::uint32_t child[8];
    std::uint32_t count[8];
};
static_assert(sizeof(Bvh8Node) == 256);

/// Collapses `binary` (nodes[0] the root): each wide node takes the children of a binary inner
/// node and keeps opening its inner child of largest surface area until it has eight. The root
/// of the result is element 0; a binary tree that is a single leaf gives one node with that
/// leaf in lane 0. Empty for an empty tree. No wide node is deeper than its binary origin.
std::vector<Bvh8Node> collapse_bvh8(const std::vector<BvhNode>& binary);

}  // namespace edacrt
