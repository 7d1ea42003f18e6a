#include "trace/bvh_wide.h"

#include <algorithm>
#include <cassert>

namespace edacrt {
namespace {

class Collapser {
  public:
    Collapser(const std::vector<BvhNode>& binary, std::vector<Bvh8Node>& wide)
        : binary_(binary), wide_(wide) {}

    /// Appends the wide node for binary node `index`'s children (or for `index` itself when it
    /// is a leaf, only at the root), then those of its inner children; returns its position.
    std::uint32_t collapse(std::uint32_t index) {
        std::uint32_t children[8];
        int size = 0;
        const BvhNode& node = binary_[index];
        if (node.count > 0) {
            children[size++] = index;
        } else {
            children[size++] = node.first;
            children[size++] = node.first + 1;
        }
        while (size < 8) {  // open the largest inner child
            int largest = -1;
            float largest_area = -1.0f;
            for (int i = 0; i < size; ++i) {
                const BvhNode& child = binary_[children[i]];
                if (child.count == 0 && child.box.surface_area() > largest_area) {
                    largest = i;
                    largest_area = child.box.surface_area();
                }
            }
            if (largest < 0) break;
            const std::uint32_t opened = binary_[children[largest]].first;
            children[largest] = opened;
            children[size++] = opened + 1;
        }
        const std::uint32_t position = std::uint32_t(wide_.size());
        wide_.emplace_back();
        Bvh8Node& out = wide_.back();
        out.boxes = pack_boxes8(size, [&](int i) { return binary_[children[i]].box; });
        std::fill_n(out.child, 8, 0u);
        std::fill_n(out.count, 8, 0u);
        for (int i = 0; i < size; ++i) {
            const BvhNode& child = binary_[children[i]];
            assert(!child.box.empty());  // an empty box would read as an unused lane
            out.child[i] = child.first;
            out.count[i] = child.count;
        }
        for (int i = 0; i < size; ++i) {  // after filling: collapse() appends to wide_
            if (binary_[children[i]].count == 0) wide_[position].child[i] = collapse(children[i]);
        }
        return position;
    }

  private:
    const std::vector<BvhNode>& binary_;
    std::vector<Bvh8Node>& wide_;
};

}  // namespace

std::vector<Bvh8Node> collapse_bvh8(const std::vector<BvhNode>& binary) {
    std::vector<Bvh8Node> wide;
    if (binary.empty()) return wide;
    wide.reserve(binary.size() / 4 + 1);
    Collapser(binary, wide).collapse(0);
    return wide;
}

}  // namespace edacrt
