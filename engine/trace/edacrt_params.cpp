#include "trace/edacrt_params.h"

#include <cmath>
#include <string>

#include "util/error.h"

namespace edacrt {
namespace {

void require(bool ok, const std::string& what) {
    if (!ok) throw InputError("EDACRT parameter " + what);
}

}  // namespace

void validate(const EdacrtParams& p) {
    require(p.bins >= 2 && p.bins <= 256, "bins (K) must be in [2, 256]");
    require(p.sample_threshold >= 1, "sample_threshold must be at least 1");
    require(p.sample_count >= 1, "sample_count must be at least 1");
    require(p.leaf_rays >= 1, "leaf_rays must be at least 1");
    require(p.leaf_tris >= 1, "leaf_tris must be at least 1");
    const auto cost = [&](float value, const char* name) {
        require(std::isfinite(value) && value >= 0.0f,
                std::string(name) + " must be finite and non-negative");
    };
    cost(p.cost_traversal, "C_T");
    cost(p.cost_intersect, "C_I");
    cost(p.cost_filter, "C_bv");
    cost(p.cost_child, "C_child");
    require(p.cost_intersect > 0.0f, "C_I must be positive");
    require(p.cost_child > 0.0f, "C_child must be positive");
}

}  // namespace edacrt
