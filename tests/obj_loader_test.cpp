#include "scene/obj_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "temp_dir.h"
#include "test_paths.h"
#include "util/error.h"

namespace edacrt {
namespace {

namespace fs = std::filesystem;

const MtlReader kNoMtl = [](const std::string&) { return std::optional<std::string>(); };

Scene parse(std::string_view text, const MtlReader& read_mtl = kNoMtl) {
    return parse_obj(text, "t.obj", read_mtl);
}

/// A reader over named in-memory MTL texts.
MtlReader mtl_files(std::map<std::string, std::string> files) {
    return [files = std::move(files)](const std::string& name) -> std::optional<std::string> {
        const auto it = files.find(name);
        if (it == files.end()) return std::nullopt;
        return it->second;
    };
}

/// The message of the InputError that parsing `text` throws.
std::string error_of(std::string_view text, const MtlReader& read_mtl = kNoMtl) {
    try {
        parse(text, read_mtl);
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

// A unit square in z = 0 and a point off it, so that faces over them have area.
constexpr std::string_view kSquare =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n";

using Tri = std::array<std::uint32_t, 3>;

TEST(ObjLoader, SingleTriangle) {
    const Scene scene = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(scene.source, "t.obj");
    ASSERT_EQ(scene.positions.size(), 3u);
    EXPECT_EQ(scene.positions[1], glm::vec3(1, 0, 0));
    ASSERT_EQ(scene.triangles.size(), 1u);
    EXPECT_EQ(scene.triangles[0], (Tri{0, 1, 2}));
    EXPECT_TRUE(scene.normals.empty());
    EXPECT_TRUE(scene.triangle_normals.empty());
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].kd, glm::vec3(0.8f));
    EXPECT_EQ(scene.triangle_materials, std::vector<std::uint32_t>{0});
    EXPECT_FALSE(scene.camera.has_value());
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(ObjLoader, PolygonsAreFanTriangulatedInFileOrder) {
    // A triangle, a quad, a pentagon and a hexagon: 1 + 2 + 3 + 4 triangles.
    const Scene scene = parse(
        "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 2 0\nv -1 1 0\n"
        "f 1 2 3\n"
        "f 1 2 3 4\n"
        "f 1 2 3 4 5\n"
        "f 1 2 3 4 5 6\n");
    const std::vector<Tri> expected = {{0, 1, 2},                                    // triangle
                                       {0, 1, 2}, {0, 2, 3},                         // quad
                                       {0, 1, 2}, {0, 2, 3}, {0, 3, 4},              // pentagon
                                       {0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};  // hexagon
    EXPECT_EQ(scene.triangles, expected);
    EXPECT_EQ(scene.triangle_materials.size(), expected.size());
}

TEST(ObjLoader, AllCornerForms) {
    const Scene scene = parse(std::string(kSquare) +
                              "vt 0 0\nvt 1 0\nvt 1 1\n"
                              "vn 0 0 1\nvn 0 0 2\n"
                              "f 1 2 3\n"
                              "f 1/1 2/2 3/3\n"
                              "f 1//1 2//2 3//1\n"
                              "f 1/1/2 2/2/1 4/3/2\n"
                              "f 1 2//2 3/3\n");
    ASSERT_EQ(scene.triangles.size(), 5u);
    EXPECT_EQ(scene.triangles[3], (Tri{0, 1, 3}));
    ASSERT_EQ(scene.triangle_normals.size(), 5u);
    using Nrm = std::array<std::int32_t, 3>;
    EXPECT_EQ(scene.triangle_normals[0], (Nrm{-1, -1, -1}));
    EXPECT_EQ(scene.triangle_normals[1], (Nrm{-1, -1, -1}));
    EXPECT_EQ(scene.triangle_normals[2], (Nrm{0, 1, 0}));
    EXPECT_EQ(scene.triangle_normals[3], (Nrm{1, 0, 1}));
    EXPECT_EQ(scene.triangle_normals[4], (Nrm{-1, 1, -1}));
    ASSERT_EQ(scene.normals.size(), 2u);
    EXPECT_EQ(scene.normals[1], glm::vec3(0, 0, 1)) << "normals are stored unit length";
}

TEST(ObjLoader, ZeroLengthNormalCountsAsAbsent) {
    const Scene scene = parse(std::string(kSquare) + "vn 0 0 0\nvn 0 0 1\nf 1//1 2//2 3//1\n");
    ASSERT_EQ(scene.triangle_normals.size(), 1u);
    EXPECT_EQ(scene.triangle_normals[0], (std::array<std::int32_t, 3>{-1, 1, -1}));
}

TEST(ObjLoader, NoNormalsWhenOnlyZeroLengthOnesAreUsed) {
    const Scene scene = parse(std::string(kSquare) + "vn 0 0 0\nf 1//1 2//1 3//1\n");
    EXPECT_TRUE(scene.triangle_normals.empty());
    EXPECT_TRUE(scene.normals.empty());
}

TEST(ObjLoader, NegativeIndicesCountBackFromTheVerticesSoFar) {
    const Scene scene = parse(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
        "f -3 -2 -1\n"
        "v 0 0 1\n"
        "f -4 -2 -1\n"
        "vn 0 0 1\n"
        "f -1//-1 -2//-1 -3//-1\n");
    const std::vector<Tri> expected = {{0, 1, 2}, {0, 2, 3}, {3, 2, 1}};
    EXPECT_EQ(scene.triangles, expected);
    ASSERT_EQ(scene.triangle_normals.size(), 3u);
    EXPECT_EQ(scene.triangle_normals[2], (std::array<std::int32_t, 3>{0, 0, 0}));
}

TEST(ObjLoader, CrlfTabsDoubleSpacesCommentsAndBlankLines) {
    const Scene scene = parse(
        "# header\r\n"
        "\r\n"
        "   \t \r\n"
        "v\t0\t0\t0\r\n"
        "v  1.0  0.00   0  \r\n"
        "  v 0 1 0 # trailing comment\r\n"
        "vn 0 0 1\r\n"
        "\r\n"
        "f  1//1 2//1\t3//1 \r\n"
        "f 1 2 3");  // no final newline
    EXPECT_EQ(scene.triangles.size(), 2u);
    EXPECT_EQ(scene.positions[1], glm::vec3(1, 0, 0));
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(ObjLoader, ErrorLinesCountCrlfAndLoneCrAsOneLineBreak) {
    EXPECT_TRUE(contains(error_of("v 0 0 0\r\nv 1 0 0\r\nv x 0 0\r\n"), "t.obj:3: "));
    EXPECT_TRUE(contains(error_of("v 0 0 0\rv 1 0 0\rv x 0 0\r"), "t.obj:3: "));
    EXPECT_TRUE(contains(error_of("\n\r\n\r\rv x 0 0\n"), "t.obj:5: "));
}

TEST(ObjLoader, ByteOrderMarkIsSkipped) {
    EXPECT_EQ(parse("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").triangles.size(), 1u);
}

TEST(ObjLoader, VertexExtrasAndPlusSignAccepted) {
    // w, or r g b vertex colours, are checked and ignored.
    const Scene scene = parse("v 0 0 0 1\nv +1 0 0 0.5 0.5 0.5\nv 0 1 1e-50\nf 1 2 3\n");
    EXPECT_EQ(scene.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.positions[2], glm::vec3(0, 1, 0)) << "underflow flushes to zero";
}

TEST(ObjLoader, GroupsObjectsSmoothingAndTexcoordsAreQuietlyIgnored) {
    const Scene scene = parse("o thing\ng a b\ns 1\ns off\n" + std::string(kSquare) +
                              "vt 0.5\nvt 0 1 0\nf 1/1 2/2 3/1\n");
    EXPECT_EQ(scene.triangles.size(), 1u);
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(ObjLoader, UnsupportedStatementsWarnOncePerKeyword) {
    const Scene scene = parse(std::string(kSquare) + "l 1 2\nl 2 3\np 1\nf 1 2 3\nvp 0.5\n");
    EXPECT_EQ(scene.triangles.size(), 1u);
    ASSERT_EQ(scene.warnings.size(), 3u);
    EXPECT_TRUE(contains(scene.warnings[0], "t.obj:5: OBJ statement 'l' is not supported"));
    EXPECT_TRUE(contains(scene.warnings[1], "t.obj:7: OBJ statement 'p'"));
    EXPECT_TRUE(contains(scene.warnings[2], "t.obj:9: OBJ statement 'vp'"));
}

constexpr std::string_view kTwoMaterials =
    "newmtl red\nKd 1 0 0\n"
    "newmtl green\nKd 0 1 0\n";

TEST(ObjLoader, UsemtlAssignsMaterialsPerTriangle) {
    const Scene scene = parse("mtllib m.mtl\n" + std::string(kSquare) +
                                  "f 1 2 3\n"
                                  "usemtl green\nf 1 2 3 4\n"
                                  "usemtl red\nf 1 2 3\n"
                                  "usemtl green\nf 2 3 4\n",
                              mtl_files({{"m.mtl", std::string(kTwoMaterials)}}));
    // red, green from the library, then the default for the face before any usemtl.
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_EQ(scene.materials[0].name, "red");
    EXPECT_EQ(scene.materials[1].kd, glm::vec3(0, 1, 0));
    EXPECT_EQ(scene.materials[2].kd, glm::vec3(0.8f));
    EXPECT_EQ(scene.triangle_materials, (std::vector<std::uint32_t>{2, 1, 1, 0, 1}));
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(ObjLoader, NoUsemtlMeansOneDefaultMaterial) {
    const Scene scene = parse(std::string(kSquare) + "f 1 2 3\nf 1 3 4\n");
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "default");
    EXPECT_EQ(scene.triangle_materials, (std::vector<std::uint32_t>{0, 0}));
}

TEST(ObjLoader, NoDefaultMaterialWhenEveryFaceHasOne) {
    const Scene scene = parse("mtllib m.mtl\nusemtl red\n" + std::string(kSquare) + "f 1 2 3\n",
                              mtl_files({{"m.mtl", std::string(kTwoMaterials)}}));
    EXPECT_EQ(scene.materials.size(), 2u);
}

TEST(ObjLoader, UndefinedMaterialWarnsOncePerNameAndUsesTheDefault) {
    const Scene scene = parse("mtllib m.mtl\n" + std::string(kSquare) +
                                  "usemtl blue\nf 1 2 3\n"
                                  "usemtl red\nf 1 2 3\n"
                                  "usemtl blue\nf 1 3 4\n",
                              mtl_files({{"m.mtl", std::string(kTwoMaterials)}}));
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_EQ(scene.triangle_materials, (std::vector<std::uint32_t>{2, 0, 2}));
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_TRUE(contains(scene.warnings[0], "t.obj:6: material 'blue' is not defined"));
}

// 20,000 undefined names printed 2.8 MB of warnings: ten of a kind, then a count.
TEST(ObjLoader, RepeatedWarningsStopAfterTenOfAKind) {
    std::string text(kSquare);
    for (int i = 0; i < 20000; ++i) text += "usemtl m" + std::to_string(i) + "\nf 1 2 3\n";
    const Scene scene = parse(text);
    ASSERT_EQ(scene.warnings.size(), 11u);
    EXPECT_TRUE(contains(scene.warnings[9], "t.obj:23: material 'm9' is not defined"));
    EXPECT_EQ(scene.warnings[10], "t.obj: ... and 19990 more undefined materials");
}

TEST(ObjLoader, MtllibMayFollowUsemtl) {
    const Scene scene = parse("usemtl green\n" + std::string(kSquare) + "f 1 2 3\nmtllib m.mtl\n",
                              mtl_files({{"m.mtl", std::string(kTwoMaterials)}}));
    EXPECT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.triangle_materials, std::vector<std::uint32_t>{1});
}

TEST(ObjLoader, SeveralLibrariesAndTheFirstDefinitionWins) {
    const Scene scene =
        parse("mtllib a.mtl b.mtl\nmtllib a.mtl\nusemtl red\n" + std::string(kSquare) + "f 1 2 3\n",
              mtl_files({{"a.mtl", "newmtl red\nKd 1 0 0\n"},
                         {"b.mtl", "newmtl red\nKd 0 0 1\nnewmtl blue\nKd 0 0 1\n"}}));
    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[0].kd, glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.materials[1].name, "blue");
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_TRUE(contains(scene.warnings[0], "b.mtl: material 'red' is defined more than once"));
}

TEST(ObjLoader, MaterialNamesMayContainSpaces) {
    const Scene scene =
        parse("mtllib m.mtl\nusemtl dark red  \n" + std::string(kSquare) + "f 1 2 3\n",
              mtl_files({{"m.mtl", "newmtl dark red\nKd 0.5 0 0\n"}}));
    EXPECT_EQ(scene.materials.size(), 1u);
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(ObjLoader, MtlWarningsReachTheScene) {
    const Scene scene = parse("mtllib m.mtl\n" + std::string(kSquare) + "f 1 2 3\n",
                              mtl_files({{"m.mtl", "newmtl a\nmap_Ks a.png\n"}}));
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_TRUE(contains(scene.warnings[0], "m.mtl:2: MTL feature 'map_Ks' is not modelled"));
}

TEST(ObjLoader, MtlErrorsNameTheMtlFileAndLine) {
    EXPECT_TRUE(contains(error_of("mtllib m.mtl\n", mtl_files({{"m.mtl", "newmtl a\nKd 1 x 1\n"}})),
                         "m.mtl:2: bad number 'x'"));
}

TEST(ObjLoader, MissingMaterialLibraryWarnsAndUsesTheDefault) {
    const Scene scene = parse("# lib\nmtllib gone.mtl\nusemtl red\n" + std::string(kSquare) +
                              "f 1 2 3\nusemtl blue\nf 1 3 4\n");
    EXPECT_EQ(scene.triangles.size(), 2u);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "default");
    // One warning for the library and one for its materials, not one per usemtl name.
    ASSERT_EQ(scene.warnings.size(), 2u);
    EXPECT_EQ(scene.warnings[0],
              "t.obj:2: cannot read material library 'gone.mtl'; its materials are replaced by "
              "the default material");
    EXPECT_EQ(scene.warnings[1],
              "t.obj: 2 materials are not defined (a material library is missing); the default "
              "material is used");
}

TEST(ObjLoader, MtllibNameIsTheRestOfTheLine) {
    const MtlReader read_mtl = mtl_files({{"my materials.mtl", std::string(kTwoMaterials)},
                                          {"a.mtl", "newmtl red\nKd 1 0 0\n"},
                                          {"b.mtl", "newmtl green\nKd 0 1 0\n"}});
    // A name with a space.
    Scene scene = parse(
        "mtllib my materials.mtl \nusemtl green\n" + std::string(kSquare) + "f 1 2 3\n", read_mtl);
    EXPECT_EQ(scene.materials.size(), 2u);
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    // No file of the whole name: several names, of which the missing one is reported.
    scene =
        parse("mtllib a.mtl gone.mtl b.mtl\nusemtl green\n" + std::string(kSquare) + "f 1 2 3\n",
              read_mtl);
    EXPECT_EQ(scene.materials.size(), 2u);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_TRUE(contains(scene.warnings[0], "t.obj:1: cannot read material library 'gone.mtl'"));
    // None of them: the whole line is reported once.
    scene = parse("mtllib my gone.mtl\n" + std::string(kSquare) + "f 1 2 3\n", read_mtl);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_TRUE(contains(scene.warnings[0], "t.obj:1: cannot read material library 'my gone.mtl'"));
}

TEST(ObjLoader, MtllibNameFromTheFileIsEscapedInMessages) {
    const std::string name = "m\x1b[2J" + std::string(100, 'x') + ".mtl";
    const std::string message =
        error_of("mtllib " + name + "\n", mtl_files({{name, "newmtl a\nKd 1 x 1\n"}}));
    EXPECT_TRUE(contains(message, "m\\x1B[2J" + std::string(55, 'x') + "...:2: bad number 'x'"));
}

// Found by tests/fuzz/obj_fuzzer: the library name from the OBJ text prefixed the library's
// messages unescaped.
TEST(ObjLoader, MtlErrorsEscapeControlBytesInTheLibraryName) {
    EXPECT_EQ(error_of("mtllib \x02m.mtl\n", mtl_files({{"\x02m.mtl", "Kd 1 1 1\n"}})),
              "\\x02m.mtl:1: 'Kd' before any newmtl");
}

TEST(ObjLoader, DegenerateTrianglesKeepFileOrderAndAreCountedInOneWarning) {
    const Scene scene = parse(std::string(kSquare) +
                              "v 0 0 0\n"    // 5: same position as 1
                              "v 2 2 0\n"    // 6: on the diagonal through 1 and 3
                              "f 1 2 3\n"    // triangle 0
                              "f 1 1 2\n"    // 1: repeated index
                              "f 1 5 2\n"    // 2: two corners at the same position
                              "f 2 3 4\n"    // triangle 3
                              "f 1 3 6\n");  // 4: collinear
    const std::vector<Tri> expected = {{0, 1, 2}, {0, 0, 1}, {0, 4, 1}, {1, 2, 3}, {0, 2, 5}};
    EXPECT_EQ(scene.triangles, expected);
    EXPECT_EQ(scene.triangle_materials.size(), 5u);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_EQ(scene.warnings[0], "t.obj: 3 degenerate triangles (zero area), never hit");
}

TEST(ObjLoader, DegenerateFanTrianglesKeepNormalsAligned) {
    // The quad's first fan triangle is degenerate; the second keeps its own normals.
    const Scene scene = parse(std::string(kSquare) + "vn 0 0 1\nvn 1 0 0\nf 1//1 1//1 3//1 4//2\n");
    ASSERT_EQ(scene.triangles.size(), 2u);
    EXPECT_EQ(scene.triangles[1], (Tri{0, 2, 3}));
    EXPECT_EQ(scene.triangle_normals[1], (std::array<std::int32_t, 3>{0, 0, 1}));
}

TEST(ObjLoader, AllTrianglesDegenerateIsAnEmptyScene) {
    const std::string message = error_of(std::string(kSquare) + "f 1 1 2\nf 1 2 1 2\n");
    EXPECT_TRUE(contains(message, "t.obj: no triangles"));
    EXPECT_TRUE(contains(message, "all 3 triangles are degenerate"));
}

TEST(ObjLoader, EmptySceneIsAnError) {
    EXPECT_TRUE(contains(error_of(""), "t.obj: no triangles"));
    EXPECT_TRUE(contains(error_of("# nothing\n\n"), "t.obj: no triangles"));
    EXPECT_TRUE(contains(error_of(kSquare), "t.obj: no triangles (the file has no faces)"));
}

struct BadObj {
    const char* name;
    std::string text;
    std::string message;  // expected part of the error, with the line
};

class ObjErrors : public ::testing::TestWithParam<BadObj> {};

TEST_P(ObjErrors, NameTheProblemAndTheLine) {
    const MtlReader read_mtl = mtl_files({{"m.mtl", "newmtl a\n"}});
    EXPECT_TRUE(contains(error_of(GetParam().text, read_mtl), GetParam().message));
}

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

INSTANTIATE_TEST_SUITE_P(
    ObjLoader, ObjErrors,
    ::testing::Values(
        BadObj{"IndexZero", kTri + "f 0 1 2\n", "t.obj:4: face vertex index 0 is invalid"},
        BadObj{"IndexTooLarge", kTri + "f 1 2 4\n",
               "t.obj:4: face vertex index 4 out of range (3 vertices defined so far)"},
        BadObj{"NegativeIndexTooFar", kTri + "f -1 -2 -4\n",
               "t.obj:4: face vertex index -4 out of range (3 vertices"},
        BadObj{"IndexBeforeItsVertex", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n",
               "t.obj:3: face vertex index 3 out of range (2 vertices"},
        BadObj{"HugeIndex", kTri + "f 1 2 99999999999999999999999\n",
               "t.obj:4: face vertex index 99999999999999999999999 out of range"},
        BadObj{"HugeNegativeIndex", kTri + "f 1 2 -99999999999\n",
               "t.obj:4: face vertex index -99999999999 out of range"},
        BadObj{"LongIndexIsCut", kTri + "f 1 2 " + std::string(500, '9') + "\n",
               "t.obj:4: face vertex index " + std::string(60, '9') + "... out of range"},
        BadObj{"TexcoordIndexOutOfRange", kTri + "vt 0 0\nf 1/1 2/2 3/1\n",
               "t.obj:5: face texture coordinate index 2 out of range (1 texture coordinates"},
        BadObj{"NormalIndexOutOfRange", kTri + "vn 0 0 1\nf 1//1 2//1 3//-2\n",
               "t.obj:5: face normal index -2 out of range (1 normals"},
        BadObj{"NormalIndexZero", kTri + "vn 0 0 1\nf 1//0 2//1 3//1\n",
               "t.obj:5: face normal index 0 is invalid"},
        BadObj{"BadIndex", kTri + "f 1 2 3x\n", "t.obj:4: bad face vertex index '3x'"},
        BadObj{"FloatIndex", kTri + "f 1 2 3.0\n", "t.obj:4: bad face vertex index '3.0'"},
        BadObj{"TooManySlashes", kTri + "f 1 2 3/1/1/1\n", "t.obj:4: bad face corner '3/1/1/1'"},
        BadObj{"NoVertexIndex", kTri + "f 1 2 /1\n", "t.obj:4: face corner '/1' has no vertex"},
        BadObj{"TwoCorners", kTri + "f 1 2\n", "t.obj:4: face with 2 corner(s)"},
        BadObj{"NoCorners", kTri + "f\n", "t.obj:4: face with 0 corner(s)"},
        BadObj{"NaN", "v 0 0 0\nv nan 0 0\n", "t.obj:2: non-finite number 'nan'"},
        BadObj{"NegativeInf", "v 0 -inf 0\n", "t.obj:1: non-finite number '-inf'"},
        BadObj{"Infinity", "v 0 0 infinity\n", "t.obj:1: non-finite number 'infinity'"},
        BadObj{"FloatOverflow", "v 1e40 0 0\n", "t.obj:1: number '1e40' is out of range for float"},
        BadObj{"DoubleOverflow", "v 0 -1e400 0\n", "t.obj:1: number '-1e400' is out of range"},
        BadObj{"Garbage", "v 1 abc 2\n", "t.obj:1: bad number 'abc'"},
        BadObj{"TrailingGarbage", "v 1 2.5.1 2\n", "t.obj:1: bad number '2.5.1'"},
        BadObj{"CommaDecimal", "v 1 2,5 2\n", "t.obj:1: bad number '2,5'"},
        BadObj{"PlusMinus", "v 1 +-2 2\n", "t.obj:1: bad number '+-2'"},
        BadObj{"TooFewCoordinates", "v 1 2\n", "t.obj:1: 'v' needs 3 numbers, found 2"},
        BadObj{"TooManyCoordinates", "v 1 2 3 4 5 6 7 8\n", "t.obj:1: too many numbers after 'v'"},
        BadObj{"NormalTooShort", "vn 0 1\n", "t.obj:1: 'vn' needs 3 numbers, found 2"},
        BadObj{"NormalTooLong", "vn 0 1 0 1\n", "t.obj:1: too many numbers after 'vn'"},
        BadObj{"NormalGarbage", "vn 0 1 z\n", "t.obj:1: bad number 'z'"},
        BadObj{"NormalNaN", "vn 0 nan 1\n", "t.obj:1: non-finite number 'nan'"},
        BadObj{"TexcoordGarbage", "vt 0 q\n", "t.obj:1: bad number 'q'"},
        BadObj{"MtllibWithoutName", "mtllib\n", "t.obj:1: mtllib without a file name"},
        BadObj{"UsemtlWithoutName", "usemtl  \n", "t.obj:1: usemtl without a material name"},
        BadObj{"LineContinuation", "v 1 2 \\\n3\n", "t.obj:1: line continuation"},
        BadObj{"NulByte", kTri + std::string("f 1 2 3\0\n", 9), "t.obj:4: NUL byte"},
        BadObj{"NotAStatement", "v 0 0 0\n{\"json\": true}\n",
               "t.obj:2: unexpected '{\"json\":' (not an OBJ statement)"},
        BadObj{"BinaryGarbage", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\x01\0", 20),
               "t.obj:1: unexpected '\\x89PNG' (not an OBJ statement)"},
        BadObj{"ManyKindsOfUnsupportedStatement",
               [] {
                   std::string text;
                   for (int i = 0; i <= 32; ++i)
                       text.append("x").append(std::to_string(i)).append(" 1\n");
                   return text;
               }(),
               "t.obj:33: more than 32 kinds of unsupported statement"},
        BadObj{"ControlBytesAreEscaped", "v 0 0 0\n\x01\x02x 1\n",
               "t.obj:2: unexpected '\\x01\\x02x'"}),
    [](const auto& info) { return std::string(info.param.name); });

using test::TempDir;

std::string load_error(const fs::path& path) {
    try {
        load_obj(path);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError loading " << path;
    return {};
}

TEST(LoadObj, MissingFileNamesThePath) {
    const TempDir dir;
    const fs::path path = dir.path() / "nope.obj";
    EXPECT_TRUE(
        contains(load_error(path), path.string() + ": cannot read OBJ file (no such file)"));
}

TEST(LoadObj, DirectoryIsNotAnObjFile) {
    const TempDir dir;
    EXPECT_TRUE(contains(load_error(dir.path()), "not a regular file"));
}

TEST(LoadObj, ReadsMaterialLibrariesBesideTheObj) {
    const TempDir dir;
    dir.write("m.mtl", "newmtl lamp\nKe 1 2 3\n");
    const fs::path obj = dir.write("s.obj", "mtllib m.mtl\nusemtl lamp\n" + kTri + "f 1 2 3\n");
    const Scene scene = load_obj(obj);
    EXPECT_EQ(scene.source, obj.string());
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].ke, glm::vec3(1, 2, 3));
}

TEST(LoadObj, MissingMaterialLibraryNamesTheMtlTheObjLineAndTheDirectory) {
    const TempDir dir;
    const fs::path obj = dir.write("s.obj", kTri + "mtllib gone.mtl\nf 1 2 3\n");
    const Scene scene = load_obj(obj);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_EQ(scene.warnings[0],
              obj.string() + ":4: cannot read material library 'gone.mtl' (looked in " +
                  dir.path().string() + "); its materials are replaced by the default material");
}

TEST(LoadObj, UnreadableMaterialLibraryIsReportedLikeAMissingOne) {
    const TempDir dir;
    fs::create_directory(dir.path() / "dir.mtl");  // exists, but cannot be read as a file
    const fs::path obj = dir.write("s.obj", "mtllib dir.mtl\n" + kTri + "f 1 2 3\n");
    const Scene scene = load_obj(obj);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_TRUE(contains(scene.warnings[0], ":1: cannot read material library 'dir.mtl'"));
}

TEST(LoadObj, MtlErrorNamesTheMtlPath) {
    const TempDir dir;
    dir.write("m.mtl", "Kd 1 1 1\n");
    const fs::path obj = dir.write("s.obj", "mtllib m.mtl\n");
    EXPECT_TRUE(
        contains(load_error(obj), (dir.path() / "m.mtl").string() + ":1: 'Kd' before any newmtl"));
}

TEST(LoadObj, CornellBoxAsset) {
    const Scene scene = load_obj(test::source_dir() / "assets/cornell-box/CornellBox-Original.obj");
    EXPECT_EQ(scene.triangles.size(), 36u);
    EXPECT_EQ(scene.positions.size(), 72u);
    ASSERT_EQ(scene.materials.size(), 8u) << "every face has a usemtl: no default material";
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();

    int lights = 0;
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        const Material& material = scene.materials[scene.triangle_materials[i]];
        if (!material.emissive()) continue;
        ++lights;
        EXPECT_EQ(material.name, "light");
        EXPECT_EQ(material.ke, glm::vec3(17, 12, 4));
    }
    EXPECT_EQ(lights, 2) << "one light quad";

    const Aabb box = scene.bounds();
    EXPECT_EQ(box.lo, glm::vec3(-1.02f, 0.0f, -1.04f));
    EXPECT_EQ(box.hi, glm::vec3(1.0f, 1.99f, 0.99f));
}

}  // namespace
}  // namespace edacrt
