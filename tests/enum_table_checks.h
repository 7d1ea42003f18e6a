#pragma once
// The properties every enum table (util/enum_table.h) must have, for tests of each binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <string>
#include <string_view>

#include "util/enum_table.h"

namespace edacrt::test {

/// Each name reads back as its value, each value's first name reads back as the value, names
/// are unique and non-empty, the values from 0 to the largest listed all have a name, and an
/// unknown name (or a name in other letter case) is refused with the known names listed.
template <typename E, std::size_t N>
void expect_enum_table(const EnumTable<E, N>& table) {
    SCOPED_TRACE(std::string(table.what));
    EXPECT_FALSE(table.what.empty());
    const std::string known = enum_names(table);
    std::set<std::string_view> names;
    int largest = 0;
    for (const EnumEntry<E>& entry : table) {
        EXPECT_FALSE(entry.name.empty());
        EXPECT_TRUE(names.insert(entry.name).second) << "named twice: " << entry.name;
        EXPECT_EQ(parse_enum(table, entry.name), entry.value) << entry.name;
        EXPECT_EQ(parse_enum_or_throw(table, enum_name(table, entry.value)), entry.value)
            << entry.name;
        EXPECT_NE(known.find(entry.name), std::string::npos) << entry.name;
        EXPECT_NE(enum_help(table).find(entry.name), std::string::npos) << entry.name;
        std::string upper(entry.name);
        std::transform(upper.begin(), upper.end(), upper.begin(),
                       [](unsigned char c) { return char(std::toupper(c)); });
        if (upper != entry.name) {
            EXPECT_FALSE(parse_enum(table, upper).has_value()) << upper;
        }
        largest = std::max(largest, int(entry.value));
    }
    for (int i = 0; i <= largest; ++i)
        EXPECT_NE(enum_name(table, static_cast<E>(i)), "?") << "value " << i << " has no name";
    EXPECT_EQ(enum_name(table, static_cast<E>(largest + 1)), "?");
    EXPECT_EQ(enum_name_list(table).size(), N);
    for (const char* unknown : {"", "no-such-name", " x"}) {
        EXPECT_FALSE(parse_enum(table, unknown).has_value()) << unknown;
        try {
            parse_enum_or_throw(table, unknown);
            ADD_FAILURE() << "'" << unknown << "' was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), "unknown " + std::string(table.what) + " '" + unknown +
                                                 "' (known: " + known + ")");
        }
    }
}

}  // namespace edacrt::test
