#include "columns.h"

#include <array>

namespace edacrt::app {
namespace {

constexpr Column kLevels[] = {
    {"level",
     "Recursion depth: 0 is the root node; the first row is the batch against the "
     "scene box, the last the total."},
    {"nodes", "Nodes the level's rays entered (count)."},
    {"leaves",
     "Of those, nodes solved by brute force: every ray against every triangle "
     "(count).",
     true},
    {"rays in", "Rays entering the level's nodes, summed over its nodes (ray-node pairs)."},
    {"rays down",
     "Rays handed to the children, after filtering or unfiltered (ray-node "
     "pairs).",
     true},
    {"filtered", "Child ray sets filtered against the child's box (count).", true},
    {"skipped",
     "Child ray sets passed down unfiltered, where alpha > 1 - C_bv / (n_child "
     "C_child) (Section 3.4; count)."},
    {"2nd split",
     "Nodes whose second child got its rays in two parts (second-child split): at "
     "once, the rays that missed the first child's box; after it, the rest. Each "
     "is one more child ray set, filtered or skipped (count).",
     true},
    {"tris", "Triangles (pre-split pieces count one each) summed over the level's nodes."},
    {"sample box",
     "Ray-box tests of the sampled rays against the 2(K-1) candidate child "
     "boxes (Section 3.2; count)."},
    {"filter box", "Ray-box tests filtering rays into the chosen children's boxes (count)."},
    {"tri tests", "Ray-triangle tests in the level's leaves (count)."},
    {"order 1st",
     "Of the rays that hit both children's boxes and found their hit below, the "
     "share whose hit was in the child visited first (percent; Section 3.3).",
     true},
    {"culled",
     "Rays the second child's filter dropped only because their hit so far is nearer "
     "than its box: what visiting the near child first bought (count).",
     true},
    {"alpha est",
     "Mean estimated hit ratio of the chosen splits' children, from the source "
     "the node used (sampled rays, area ratio or every ray; 0-1)."},
    {"alpha true",
     "Mean share of the node's rays that hit the chosen children's boxes "
     "(0-1)."},
    {"ms",
     "Wall time of the level's own work on the recursion's thread (sampling, binning, "
     "filtering, leaves), in milliseconds, from the untimed detail pass."},
};

constexpr Column kAlphaErrors[] = {
    {"level", "Recursion depth; click a row for its histogram."},
    {"sampled", "Split nodes whose alpha came from sampled rays (count)."},
    {"area", "Split nodes whose alpha came from area ratios (count)."},
    {"every ray", "Split nodes whose alpha came from every one of their rays: exact (count)."},
    {"samples/node", "Mean rays drawn per node that sampled (rays)."},
    {"mean", "Mean |estimated - true| alpha over the chosen splits' children (0-1)."},
    {"p50", "Median alpha error: half the children are at most this far off (0-1, to 0.01)."},
    {"p90", "90th percentile of the alpha error (0-1, to 0.01)."},
    {"max", "Largest alpha error of any child at this level (0-1)."},
};

constexpr Column kComparison[] = {
    {"method", "Tracing method."},
    {"update",
     "How the method takes a changed scene: rebuild, refit or dynamic; none for the "
     "methods that keep no structure."},
    {"update ms",
     "Time to take the frame's geometry: the per-frame structures, or the tree's "
     "build or refit (milliseconds, median of 3)."},
    {"ms", "Time to trace the rays (milliseconds, median of 3)."},
    {"Mrays/s", "Rays per second of the trace, in millions."},
    {"/ embree", "Update plus trace time over Embree's (rebuild): below 1 is faster."},
    {"box tests/ray", "Ray-box tests per ray (mean); Embree does not report them."},
    {"tri tests/ray", "Ray-triangle tests per ray (mean); Embree does not report them."},
};

constexpr Column kCandidates[] = {
    {"j", "Candidate split: bins 0..j go left (Section 3.1)."},
    {"N_L", "Triangles in the left child (count)."},
    {"N_R", "Triangles in the right child (count)."},
    {"a_L", "Hit ratio of the left child's box, from the node's alpha source (0-1)."},
    {"a_R", "Hit ratio of the right child's box (0-1)."},
    {"cost",
     "C_T + C_I (a_L N_L + a_R N_R): expected cost per ray, in ray-triangle tests; * "
     "marks the chosen split."},
};

constexpr Column kNodes[] = {
    {"node", "The node's number in the recording (click: select it)."},
    {"rays", "Rays that entered the node (count)."},
    {"tris", "Triangles in the node (count)."},
    {"kind", "Leaf (brute force), or split and which child it visits first (L or R)."},
    {"filter",
     "Left/right child: its rays filtered against its box (filt) or passed down "
     "unfiltered (skip, Section 3.4)."},
    {"alpha",
     "Where the node's hit ratios came from (sampled, area, every ray) and how many "
     "rays it drew."},
    {"error", "The larger |estimated - true| alpha of its two chosen children (0-1)."},
};

constexpr Column kVisits[] = {
    {"depth", "Recursion depth of the node the ray entered."},
    {"node", "The node's number in the recording."},
    {"rays in/out",
     "Rays that entered the node / handed to its left + right child (counts; a "
     "leaf shows its rays only)."},
    {"tris", "Triangles in the node (count)."},
    {"true a_L/a_R", "Share of the node's rays that hit the left / right child's box (0-1)."},
    {"first", "The child visited first (left or right)."},
    {"order",
     "On the path to the hit: whether the hit was in the child visited first (right "
     "choice) or the second (order miss). In a leaf, the tests it made."},
    {"left",
     "What became of this ray at the left child: kept by its filter, passed "
     "unfiltered, filtered out (it misses the box) or culled by distance (it meets the "
     "box beyond the hit found so far). In a leaf, whether the hit was found there."},
    {"right", "The same, at the right child."},
};

constexpr Column kAgainst[] = {
    {"level", "Recursion depth (0: the root); the last row is the total."},
    {"nodes A", "Nodes of the level in the recording (A: the method and parameters in force)."},
    {"nodes B", "Nodes of the level in the recursion it is compared with (B: the preset chosen)."},
    {"box A", "Ray-box tests per ray of the batch at this level, A (sampling and filtering)."},
    {"box B", "Ray-box tests per ray of the batch at this level, B."},
    {"tri A", "Ray-triangle tests per ray of the batch at this level, A (leaves)."},
    {"tri B", "Ray-triangle tests per ray of the batch at this level, B."},
};

constexpr std::array<std::span<const Column>, 7> kTables = {
    kLevels, kAlphaErrors, kComparison, kCandidates, kNodes, kVisits, kAgainst};

}  // namespace

std::span<const Column> level_columns() { return kLevels; }
std::span<const Column> alpha_error_columns() { return kAlphaErrors; }
std::span<const Column> comparison_columns() { return kComparison; }
std::span<const Column> candidate_columns() { return kCandidates; }
std::span<const Column> node_columns() { return kNodes; }
std::span<const Column> visit_columns() { return kVisits; }
std::span<const Column> against_columns() { return kAgainst; }
std::span<const std::span<const Column>> all_table_columns() { return kTables; }

}  // namespace edacrt::app
