#pragma once
// An enum's names, written once: one table of {value, name, help} per enum gives its name (for
// messages, JSON, command lines), its parsing, the list of known names in help texts and errors,
// and the entries of the viewer's combo boxes.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "util/error.h"

namespace edacrt {

template <typename E>
struct EnumEntry {
    E value;
    std::string_view name;       // as command lines, scripts and JSON spell it
    std::string_view help = {};  // a short description for help texts and tooltips (optional)
};

/// The names of an enum, in the order they are listed. `what` names the enum in messages
/// ("unknown WHAT 'x' (known: ...)"). A value may have several names (aliases, after its first
/// name); enum_name() gives the first.
template <typename E, std::size_t N>
struct EnumTable {
    std::string_view what;
    std::array<EnumEntry<E>, N> entries;

    constexpr const EnumEntry<E>* begin() const { return entries.data(); }
    constexpr const EnumEntry<E>* end() const { return entries.data() + N; }
    static constexpr std::size_t size() { return N; }
};

/// An EnumTable with its size counted: enum_table<Mode>("mode", {{Mode::a, "a"}, ...}).
template <typename E, std::size_t N>
constexpr EnumTable<E, N> enum_table(std::string_view what, const EnumEntry<E> (&entries)[N]) {
    EnumTable<E, N> table{what, {}};
    for (std::size_t i = 0; i < N; ++i) table.entries[i] = entries[i];
    return table;
}

/// The first name of `value`, or "?" for a value the table does not list.
template <typename E, std::size_t N>
constexpr std::string_view enum_name(const EnumTable<E, N>& table, E value) {
    for (const EnumEntry<E>& entry : table)
        if (entry.value == value) return entry.name;
    return "?";
}

/// The value named `text` (exactly, letter case included), or nullopt.
template <typename E, std::size_t N>
constexpr std::optional<E> parse_enum(const EnumTable<E, N>& table, std::string_view text) {
    for (const EnumEntry<E>& entry : table)
        if (entry.name == text) return entry.value;
    return std::nullopt;
}

/// Every name, joined by `separator`: "a, b, c" for messages, "a|b|c" for help texts.
template <typename E, std::size_t N>
std::string enum_names(const EnumTable<E, N>& table, std::string_view separator = ", ") {
    std::string names;
    for (const EnumEntry<E>& entry : table)
        names.append(names.empty() ? "" : separator).append(entry.name);
    return names;
}

/// Every name, one string each (the default of a flag that takes a list of names).
template <typename E, std::size_t N>
std::vector<std::string> enum_name_list(const EnumTable<E, N>& table) {
    std::vector<std::string> names;
    for (const EnumEntry<E>& entry : table) names.emplace_back(entry.name);
    return names;
}

/// Every name with its help in parentheses where it has one: "a (what a does), b".
template <typename E, std::size_t N>
std::string enum_help(const EnumTable<E, N>& table) {
    std::string help;
    for (const EnumEntry<E>& entry : table) {
        help.append(help.empty() ? "" : ", ").append(entry.name);
        if (!entry.help.empty()) help.append(" (").append(entry.help).append(")");
    }
    return help;
}

/// "unknown WHAT 'TEXT' (known: a, b, c)".
template <typename E, std::size_t N>
std::string unknown_enum_message(const EnumTable<E, N>& table, std::string_view text) {
    return "unknown " + std::string(table.what) + " '" + std::string(text) +
           "' (known: " + enum_names(table) + ")";
}

/// parse_enum(), or throws InputError with unknown_enum_message().
template <typename E, std::size_t N>
E parse_enum_or_throw(const EnumTable<E, N>& table, std::string_view text) {
    if (const std::optional<E> value = parse_enum(table, text)) return *value;
    throw InputError(unknown_enum_message(table, text));
}

/// True when entry i holds the value E(i), one name each: the table can index by value.
template <typename E, std::size_t N>
constexpr bool in_enum_order(const EnumTable<E, N>& table) {
    for (std::size_t i = 0; i < N; ++i)
        if (table.entries[i].value != static_cast<E>(i)) return false;
    return true;
}

/// The names alone, in table order (for the EDACRT parameter table's choices).
template <typename E, std::size_t N>
constexpr std::array<std::string_view, N> enum_name_array(const EnumTable<E, N>& table) {
    std::array<std::string_view, N> names{};
    for (std::size_t i = 0; i < N; ++i) names[i] = table.entries[i].name;
    return names;
}

}  // namespace edacrt
