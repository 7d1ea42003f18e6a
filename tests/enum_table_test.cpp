// The generic enum table helpers (util/enum_table.h) format as the messages and help texts
// expect.
#include "util/enum_table.h"

#include <gtest/gtest.h>

#include "enum_table_checks.h"

namespace edacrt {
namespace {

enum class Colour { red, green, blue };
constexpr auto kColours = enum_table<Colour>(
    "colour", {{Colour::red, "red", "warm"}, {Colour::green, "green"}, {Colour::blue, "blue"}});

TEST(EnumTable, HelpersFormatAsMessagesAndHelpTextsExpect) {
    static_assert(kColours.size() == 3);
    static_assert(enum_name(kColours, Colour::green) == "green");
    static_assert(parse_enum(kColours, "blue") == Colour::blue);
    static_assert(!parse_enum(kColours, "Blue"));
    static_assert(in_enum_order(kColours));
    EXPECT_EQ(enum_names(kColours), "red, green, blue");
    EXPECT_EQ(enum_names(kColours, "|"), "red|green|blue");
    EXPECT_EQ(enum_help(kColours), "red (warm), green, blue");
    EXPECT_EQ(unknown_enum_message(kColours, "pink"),
              "unknown colour 'pink' (known: red, green, blue)");
    EXPECT_EQ(enum_name_list(kColours), (std::vector<std::string>{"red", "green", "blue"}));
    EXPECT_EQ(enum_name_array(kColours)[2], "blue");
    test::expect_enum_table(kColours);
}

}  // namespace
}  // namespace edacrt
