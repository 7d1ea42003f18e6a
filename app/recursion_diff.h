#pragma once
// Two recursions of the same rays side by side (the Recursion tab's "against"): where their
// decisions first differ.
#include <cstdint>
#include <string>
#include <vector>

#include "trace/trace_stats.h"

namespace edacrt::app {

/// A pair of nodes, one in each recording, that got the same input (box, rays, triangles) and
/// decided differently: a leaf against a split, another split plane, the other child first, or
/// a filter skipped in one and run in the other. `what` says which, A's choice first.
struct DecisionDifference {
    std::int32_t node_a = -1, node_b = -1;  // into each TraceDetail::nodes
    std::uint16_t depth = 0;
    std::string what;
};

/// Walks both recorded trees from their roots, pairing each node's children (left, right and
/// the second child's early part) while the pair's decisions agree. Returns the pairs where
/// they first differ on each branch, in A's recursion order, at most `limit`: below such a pair
/// the inputs differ and nothing more is compared.
std::vector<DecisionDifference> first_differences(const TraceDetail& a, const TraceDetail& b,
                                                  std::size_t limit = 200);

}  // namespace edacrt::app
