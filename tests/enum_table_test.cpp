// Every enum's table (util/enum_table.h) round-trips and refuses unknown names with the known
// ones; the generic helpers format as the messages and help texts expect.
#include "util/enum_table.h"

#include <gtest/gtest.h>

#include "../cli/bench_rays.h"  // the edacrt tool's ray sets: only the table, defined inline
#include "enum_table_checks.h"
#include "render/exr_image.h"
#include "render/film.h"
#include "render/image_format.h"
#include "render/render_settings.h"
#include "trace/edacrt_params.h"
#include "trace/tracer.h"

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

TEST(EnumTable, AliasesReadBackAsTheirValueAndPrintAsTheFirstName) {
    EXPECT_EQ(parse_enum(kImageFormats, ".jpeg"), ImageFormat::jpg);
    EXPECT_EQ(enum_name(kImageFormats, ImageFormat::jpg), ".jpg");
    EXPECT_FALSE(in_enum_order(kImageFormats));
}

TEST(EnumTable, EveryTableRoundTripsAndRefusesUnknownNames) {
    test::expect_enum_table(kMethods);
    test::expect_enum_table(kEmbreeModes);
    test::expect_enum_table(kQueries);
    test::expect_enum_table(kSceneUpdates);
    test::expect_enum_table(kUpdateWorks);
    test::expect_enum_table(kIntegrators);
    test::expect_enum_table(kPrimaryShadings);
    test::expect_enum_table(kToneMaps);
    test::expect_enum_table(kExrPixels);
    test::expect_enum_table(kImageFormats);
    test::expect_enum_table(kHitRatios);
    test::expect_enum_table(kTraversalOrders);
    test::expect_enum_table(kFilterSkips);
    test::expect_enum_table(kSmallNodes);
    test::expect_enum_table(kBinnings);
    test::expect_enum_table(kSecondChildren);
    test::expect_enum_table(kAlphaSources);
    test::expect_enum_table(kFarChildren);
    test::expect_enum_table(cli::kRaySetKinds);
}

TEST(EnumTable, MessagesAreTheOnesTheToolsPrint) {
    EXPECT_EQ(unknown_enum_message(kMethods, "magic"),
              "unknown method 'magic' (known: edacrt, dacrt, bvh, embree, naive)");
    EXPECT_EQ(unknown_enum_message(kSceneUpdates, "sideways"),
              "unknown scene update 'sideways' (known: rebuild, dynamic, refit)");
    EXPECT_EQ(unknown_enum_message(kIntegrators, "magic"),
              "unknown integrator 'magic' (known: primary, ao, path)");
}

/// The EDACRT parameter table's choices are the enum tables' names, in enum order.
TEST(EnumTable, ParameterChoicesComeFromTheTables) {
    const auto choices = [](std::string_view key) {
        const ParamInfo* info = find_param(key);
        EXPECT_NE(info, nullptr) << key;
        return std::vector<std::string>(info->choices.begin(), info->choices.end());
    };
    EXPECT_EQ(choices("hit-ratio"), enum_name_list(kHitRatios));
    EXPECT_EQ(choices("order"), enum_name_list(kTraversalOrders));
    EXPECT_EQ(choices("filter-skip"), enum_name_list(kFilterSkips));
    EXPECT_EQ(choices("small-nodes"), enum_name_list(kSmallNodes));
    EXPECT_EQ(choices("binning"), enum_name_list(kBinnings));
    EXPECT_EQ(choices("second-child"), enum_name_list(kSecondChildren));
    EXPECT_EQ(choices("far-child"), enum_name_list(kFarChildren));
    for (const auto& entry : kSecondChildren) {
        EdacrtParams params;
        set_param(params, *find_param("second-child"), entry.name);
        EXPECT_EQ(params.second_child, entry.value);
        EXPECT_EQ(param_text(params, *find_param("second-child")), entry.name);
    }
    for (const auto& entry : kFarChildren) {
        EdacrtParams params;
        set_param(params, *find_param("far-child"), entry.name);
        EXPECT_EQ(params.far_child, entry.value);
        EXPECT_EQ(param_text(params, *find_param("far-child")), entry.name);
    }
}

}  // namespace
}  // namespace edacrt
