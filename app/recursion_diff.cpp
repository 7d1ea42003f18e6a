#include "recursion_diff.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace edacrt::app {
namespace {

const char* side(int s) { return s == 0 ? "left" : "right"; }

/// What differs in the decisions of two nodes with the same input, or "" (A's first).
std::string decision_difference(const NodeRecord& a, const NodeRecord& b) {
    char text[160];
    if (a.leaf != b.leaf) return a.leaf ? "a leaf against a split" : "a split against a leaf";
    if (a.leaf) return "";
    const float pa = a.candidates[std::size_t(a.chosen)].plane,
                pb = b.candidates[std::size_t(b.chosen)].plane;
    if (a.axis != b.axis || pa != pb) {
        std::snprintf(text, sizeof text, "split plane %c = %.4g against %c = %.4g",
                      "xyz"[std::clamp(a.axis, 0, 2)], pa, "xyz"[std::clamp(b.axis, 0, 2)], pb);
        return text;
    }
    if (a.left_first != b.left_first)
        return a.left_first ? "left child first against right first"
                            : "right child first against left first";
    for (int s = 0; s < 2; ++s)
        if (a.filter_skipped[s] != b.filter_skipped[s])
            return std::string("the ") + side(s) + " child's filter " +
                   (a.filter_skipped[s] ? "skipped against run" : "run against skipped");
    return "";
}

bool same_input(const NodeRecord& a, const NodeRecord& b) {
    return a.rays == b.rays && a.triangles == b.triangles && a.box.lo == b.box.lo &&
           a.box.hi == b.box.hi;
}

}  // namespace

std::vector<DecisionDifference> first_differences(const TraceDetail& a, const TraceDetail& b,
                                                  std::size_t limit) {
    std::vector<DecisionDifference> out;
    if (a.nodes.empty() || b.nodes.empty()) return out;
    // Depth first, A's children in the order A entered them: the list reads in A's order.
    std::vector<std::pair<std::int32_t, std::int32_t>> stack = {{0, 0}};
    while (!stack.empty() && out.size() < limit) {
        const auto [ia, ib] = stack.back();
        stack.pop_back();
        if (ia < 0 || ib < 0 || std::size_t(ia) >= a.nodes.size() ||
            std::size_t(ib) >= b.nodes.size())
            continue;  // not entered, or past a recording's budget
        const NodeRecord &na = a.nodes[std::size_t(ia)], &nb = b.nodes[std::size_t(ib)];
        std::string what;
        if (!same_input(na, nb)) {
            char text[128];
            std::snprintf(text, sizeof text, "input: %u rays x %u triangles against %u x %u",
                          na.rays, na.triangles, nb.rays, nb.triangles);
            what = text;
        } else {
            what = decision_difference(na, nb);
        }
        if (!what.empty()) {
            out.push_back({ia, ib, na.depth, std::move(what)});
            continue;
        }
        const int first = na.left_first ? 0 : 1;
        // Pushed in reverse: the first child's pair is compared next.
        stack.emplace_back(na.second_early, nb.second_early);
        stack.emplace_back(na.children[1 - first], nb.children[1 - first]);
        stack.emplace_back(na.children[first], nb.children[first]);
    }
    return out;
}

}  // namespace edacrt::app
