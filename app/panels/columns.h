#pragma once
// The columns of the viewer's analysis tables, each with what its header's tooltip says:
// the meaning and the unit. One list per table, so the tables and their test share it.
#include <span>

namespace edacrt::app {

struct Column {
    const char* name;
    const char* help;     // meaning and unit
    bool detail = false;  // left out of the compact set (ViewerState::all_columns off)
};

/// Statistics: one row per recursion level.
std::span<const Column> level_columns();
/// Statistics: the estimated hit ratios' error per level.
std::span<const Column> alpha_error_columns();
/// Statistics: every method on the same rays.
std::span<const Column> comparison_columns();
/// Recursion: one node's candidate splits.
std::span<const Column> candidate_columns();
/// Recursion: the nodes of one level.
std::span<const Column> node_columns();
/// Traversal: the nodes one ray entered.
std::span<const Column> visit_columns();
/// Recursion: two recursions of the same rays, level by level.
std::span<const Column> against_columns();

/// Every table above, for the test that each column explains itself.
std::span<const std::span<const Column>> all_table_columns();

}  // namespace edacrt::app
