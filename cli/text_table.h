#pragma once
// The benchmark reports' tables: columns described once, printed as a padded stdout table
// and as markdown.
#include <algorithm>
#include <span>
#include <string>

namespace edacrt::cli {

template <typename Row>
struct Column {
    const char* title;
    int width;  // in the stdout table; text columns are left-aligned, numbers right-aligned
    bool text_column;
    std::string (*text)(const Row&);
};

inline std::string pad(std::string text, int width, bool left) {
    const std::string fill(std::size_t(std::max(0, width - int(text.size()))), ' ');
    return left ? text + fill : fill + text;
}

template <typename Row>
std::string text_table_header(std::span<const Column<Row>> columns) {
    std::string text;
    for (const Column<Row>& c : columns) text += pad(c.title, c.width, c.text_column) + " ";
    return text + "\n";
}

template <typename Row>
std::string text_table_row(std::span<const Column<Row>> columns, const Row& row) {
    std::string text;
    for (const Column<Row>& c : columns) text += pad(c.text(row), c.width, c.text_column) + " ";
    return text + "\n";
}

/// The rows for which `shown(row)` holds.
template <typename Row, typename Rows, typename Shown>
std::string markdown_table(std::span<const Column<Row>> columns, const Rows& rows, Shown shown) {
    std::string text = "|", rule = "|";
    for (const Column<Row>& c : columns) {
        text += std::string(" ") + c.title + " |";
        rule += c.text_column ? "---|" : "---:|";
    }
    text += "\n" + rule + "\n";
    for (const Row& row : rows) {
        if (!shown(row)) continue;
        text += "|";
        for (const Column<Row>& c : columns) text.append(" ").append(c.text(row)).append(" |");
        text += "\n";
    }
    return text;
}

}  // namespace edacrt::cli
