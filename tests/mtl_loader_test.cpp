#include "scene/mtl_loader.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "util/error.h"

namespace edacrt {
namespace {

std::vector<Material> parse(std::string_view text, std::vector<std::string>* warnings = nullptr) {
    std::vector<std::string> ignored;
    return parse_mtl(text, "m.mtl", warnings ? *warnings : ignored);
}

std::string error_of(std::string_view text) {
    try {
        parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError for:\n" << text;
    return {};
}

::testing::AssertionResult contains(const std::string& text, std::string_view part) {
    if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

TEST(MtlLoader, ParsesModelledKeywords) {
    std::vector<std::string> warnings;
    const std::vector<Material> materials = parse(
        "newmtl shiny\n"
        "Kd 0.1 0.2 0.3\n"
        "Ks 0.4 0.5 0.6\n"
        "Ke 17 12 4\n"
        "Ns 96.5\n"
        "Ni 1.45\n"
        "Tf 0.7 0.8 0.9\n"
        "illum 3\n",
        &warnings);
    ASSERT_EQ(materials.size(), 1u);
    const Material& m = materials[0];
    EXPECT_EQ(m.name, "shiny");
    EXPECT_EQ(m.kd, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(m.ks, glm::vec3(0.4f, 0.5f, 0.6f));
    EXPECT_EQ(m.ke, glm::vec3(17, 12, 4));
    EXPECT_EQ(m.ns, 96.5f);
    EXPECT_EQ(m.ni, 1.45f);
    EXPECT_EQ(m.tf, glm::vec3(0.7f, 0.8f, 0.9f));
    EXPECT_EQ(m.illum, 3);
    EXPECT_TRUE(m.emissive());
    EXPECT_TRUE(warnings.empty());
}

TEST(MtlLoader, UnsetValuesKeepTheDefaults) {
    const std::vector<Material> materials = parse("newmtl plain\n");
    ASSERT_EQ(materials.size(), 1u);
    EXPECT_EQ(materials[0].kd, glm::vec3(0.8f));
    EXPECT_EQ(materials[0].ke, glm::vec3(0.0f));
    EXPECT_EQ(materials[0].ni, 1.0f);
}

TEST(MtlLoader, SeveralMaterialsInOrder) {
    const std::vector<Material> materials =
        parse("newmtl a\nKd 1 0 0\n\nnewmtl b\nKd 0 1 0\nnewmtl c\n");
    ASSERT_EQ(materials.size(), 3u);
    EXPECT_EQ(materials[0].name, "a");
    EXPECT_EQ(materials[1].kd, glm::vec3(0, 1, 0));
    EXPECT_EQ(materials[2].name, "c");
    EXPECT_EQ(materials[2].kd, glm::vec3(0.8f));
}

TEST(MtlLoader, SingleNumberIsGrey) {
    EXPECT_EQ(parse("newmtl g\nKd 0.25\n")[0].kd, glm::vec3(0.25f));
}

TEST(MtlLoader, KeywordsAreCaseInsensitive) {
    // The dragon scene's MTL (written by assimp) uses lower-case keywords.
    const std::vector<Material> materials =
        parse("NEWMTL $Material_0\nkd 0.6 0.6 0.6\nka 0.05 0.05 0.05\nKS 0.5 0.5 0.5\nILLUM 1\n");
    ASSERT_EQ(materials.size(), 1u);
    EXPECT_EQ(materials[0].name, "$Material_0");
    EXPECT_EQ(materials[0].kd, glm::vec3(0.6f));
    EXPECT_EQ(materials[0].ks, glm::vec3(0.5f));
    EXPECT_EQ(materials[0].illum, 1);
}

TEST(MtlLoader, WhitespaceCommentsAndCrlf) {
    std::vector<std::string> warnings;
    const std::vector<Material> materials = parse(
        "# Cornell box style\r\n"
        "newmtl leftWall   # the red one\r\n"
        "  Ns 10.0000\r\n"
        "\tKa 0.63 0.065 0.05 # Red\r\n"
        "  Kd  0.63\t0.065 0.05   \r\n"
        "\r\n"
        "newmtl  light\r\n"
        "  Ke 17 12 4",  // no final newline
        &warnings);
    ASSERT_EQ(materials.size(), 2u);
    EXPECT_EQ(materials[0].name, "leftWall");
    EXPECT_EQ(materials[0].kd, glm::vec3(0.63f, 0.065f, 0.05f));
    EXPECT_EQ(materials[1].name, "light");
    EXPECT_EQ(materials[1].ke, glm::vec3(17, 12, 4));
    EXPECT_TRUE(warnings.empty()) << "Ka is accepted quietly";
}

TEST(MtlLoader, NamesMayContainSpaces) {
    EXPECT_EQ(parse("newmtl  dark red  \n")[0].name, "dark red");
}

TEST(MtlLoader, UnmodelledKeywordsAreReportedOnceEach) {
    std::vector<std::string> warnings;
    parse(
        "newmtl a\n"
        "map_Kd a.png\n"
        "d 1.0\n"
        "Tr 0\n"
        "Ni 1.5\n"
        "bump -bm 0.5 b.png\n"
        "newmtl b\n"
        "map_Kd b.png\n"  // again, and in another case below: not reported again
        "MAP_KD c.png\n"
        "d 0.5\n"
        "refl -type sphere r.png\n",
        &warnings);
    const std::vector<std::string> expected = {
        "m.mtl:3: MTL feature 'd' is not modelled (ignored)",
        "m.mtl:4: MTL feature 'Tr' is not modelled (ignored)",
        "m.mtl:6: MTL feature 'bump' is not modelled (ignored)",
        "m.mtl:11: MTL feature 'refl' is not modelled (ignored)",
    };
    EXPECT_EQ(warnings, expected);
}

TEST(MtlLoader, WarningsAreAppended) {
    std::vector<std::string> warnings = {"earlier"};
    parse("newmtl a\nmap_Ks a.png\n", &warnings);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(warnings[0], "earlier");
}

TEST(MtlLoader, NegativeColoursAreClampedWithOneWarningPerFile) {
    std::vector<std::string> warnings;
    const std::vector<Material> materials =
        parse("newmtl a\nKe -1 2 3\nKd -0.5\nnewmtl b\nKs 0.1 -0.2 0.3\nTf 1 1 -1\nKd 0 -0 0\n",
              &warnings);
    ASSERT_EQ(materials.size(), 2u);
    EXPECT_EQ(materials[0].ke, glm::vec3(0, 2, 3));  // no negative radiance
    EXPECT_EQ(materials[0].kd, glm::vec3(0));
    EXPECT_EQ(materials[1].ks, glm::vec3(0.1f, 0, 0.3f));
    EXPECT_EQ(materials[1].tf, glm::vec3(1, 1, 0));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0],
              "m.mtl:2: 'Ke' has a negative component: negative colour components are clamped to "
              "0 (4 statements in this file)");
}

// Values the BSDF replaces are kept as written but warned about, with the line.
TEST(MtlLoader, InvalidNiAndNsAreWarnedAboutWithTheLine) {
    std::vector<std::string> warnings;
    parse("newmtl a\nNi 0\nNi -1.5\nNs -1e30\nNi 0.5\nNs 0\n", &warnings);
    EXPECT_EQ(warnings, (std::vector<std::string>{
                            "m.mtl:2: Ni 0 is not a positive index of refraction; 1.5 is used",
                            "m.mtl:3: Ni -1.5 is not a positive index of refraction; 1.5 is used",
                            "m.mtl:4: Ns -1e+30 is negative; 0 is used"}));
}

// Thousands of warnings of one kind are ten and a count.
TEST(MtlLoader, RepeatedWarningsStopAfterTenOfAKind) {
    std::string text;
    for (int i = 0; i < 1000; ++i) text += "newmtl m" + std::to_string(i) + "\nNi 0\n";
    std::vector<std::string> warnings;
    parse(text, &warnings);
    ASSERT_EQ(warnings.size(), 11u);
    EXPECT_TRUE(contains(warnings[9], "m.mtl:20: Ni 0"));
    EXPECT_EQ(warnings[10], "m.mtl: ... and 990 more invalid Ni values");
}

TEST(MtlLoader, ErrorsQuoteOnlyAShortEscapedExcerptOfTheFile) {
    // Any file can be named by mtllib; a message must not copy its content.
    const std::string secret = "root:x:0:0:" + std::string(200, 's') + "\x1b[31m\n";
    const std::string message = error_of(secret);
    EXPECT_TRUE(contains(message, "m.mtl:1: unexpected 'root:x:0:0:sssss"));
    EXPECT_LT(message.size(), 100u) << message;
    const std::string binary = error_of(
        "\x7f"
        "ELF\x02\x01\x01\xff\xfe rest\n");
    EXPECT_TRUE(contains(binary, "m.mtl:1: unexpected '\\x7FELF\\x02\\x01\\x01\\xFF\\xFE'"));
}

TEST(MtlLoader, EmptyTextHasNoMaterials) {
    EXPECT_TRUE(parse("").empty());
    EXPECT_TRUE(parse("# only a comment\n\n").empty());
}

struct BadMtl {
    const char* name;
    std::string text;
    const char* message;
};

class MtlErrors : public ::testing::TestWithParam<BadMtl> {};

TEST_P(MtlErrors, NameTheProblemAndTheLine) {
    EXPECT_TRUE(contains(error_of(GetParam().text), GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    MtlLoader, MtlErrors,
    ::testing::Values(
        BadMtl{"KeywordBeforeNewmtl", "# header\nKd 1 1 1\nnewmtl a\n",
               "m.mtl:2: 'Kd' before any newmtl"},
        BadMtl{"UnknownKeywordBeforeNewmtl", "map_Kd x.png\n",
               "m.mtl:1: 'map_Kd' before any newmtl"},
        BadMtl{"NewmtlWithoutName", "newmtl a\nnewmtl   # no name\n",
               "m.mtl:2: newmtl without a material name"},
        BadMtl{"BadNumber", "newmtl a\n\nKd 1 x 1\n", "m.mtl:3: bad number 'x'"},
        BadMtl{"TrailingGarbage", "newmtl a\nNs 10abc\n", "m.mtl:2: bad number '10abc'"},
        BadMtl{"NaN", "newmtl a\nKs 0 nan 0\n", "m.mtl:2: non-finite number 'nan'"},
        BadMtl{"Inf", "newmtl a\nKe inf 0 0\n", "m.mtl:2: non-finite number 'inf'"},
        BadMtl{"Overflow", "newmtl a\nNi 1e40\n", "m.mtl:2: number '1e40' is out of range"},
        BadMtl{"TwoNumbers", "newmtl a\nKd 1 1\n", "m.mtl:2: 'Kd' needs 1 or 3 numbers, found 2"},
        BadMtl{"FourNumbers", "newmtl a\nKd 1 1 1 1\n", "m.mtl:2: 'Kd' needs 1 or 3 numbers"},
        BadMtl{"NoNumber", "newmtl a\nkd\n", "m.mtl:2: 'kd' needs 1 or 3 numbers, found 0"},
        BadMtl{"SpectralColour", "newmtl a\nKd spectral x.rfl\n", "m.mtl:2: bad number"},
        BadMtl{"BadAmbient", "newmtl a\nKa 1 q 1\n", "m.mtl:2: bad number 'q'"},
        BadMtl{"NsMissing", "newmtl a\nNs\n", "m.mtl:2: 'Ns' needs a number"},
        BadMtl{"NsTwice", "newmtl a\nNs 1 2\n", "m.mtl:2: 'Ns' needs exactly one number"},
        BadMtl{"IllumFloat", "newmtl a\nillum 2.5\n", "m.mtl:2: bad integer '2.5'"},
        BadMtl{"IllumHuge", "newmtl a\nillum 99999999999\n", "m.mtl:2: bad integer"},
        BadMtl{"NulByte", std::string("newmtl a\nKd 1\0 1 1\n", 18), "m.mtl:2: NUL byte"},
        BadMtl{"NotAStatement", "newmtl a\n<html>\n", "m.mtl:2: unexpected '<html>'"},
        BadMtl{"ManyKindsOfUnknownStatement",
               [] {
                   std::string text = "newmtl a\n";
                   for (int i = 0; i <= 64; ++i)
                       text.append("x").append(std::to_string(i)).append(" 1\n");
                   return text;
               }(),
               "m.mtl:66: more than 64 kinds of unknown statement"},
        BadMtl{"LoneCrCountsAsLineBreak", "newmtl a\rKd 1 1 1\rNs x\r", "m.mtl:3: bad number"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace edacrt
