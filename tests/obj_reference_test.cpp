// Differential test: our OBJ loader against tinyobjloader on the bundled assets and the large
// scenes, triangle by triangle in file order.
//
// tinyobjloader 2.0rc10 with triangulate=true splits a quad along its shorter diagonal and
// ear-clips larger polygons, so its triangles cannot be matched corner by corner with our fan.
// It is therefore asked for the polygons (triangulate=false) and they are fanned here, which
// compares every face exactly, n-gons included.
#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <filesystem>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "scene/obj_loader.h"
#include "test_paths.h"

namespace edacrt {
namespace {

namespace fs = std::filesystem;

/// The loader's documented rule: the cross product of two edges, in double, is exactly zero.
bool zero_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    return glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a)) ==
           glm::dvec3(0.0);
}

/// tinyobjloader keeps keywords it does not know, such as a lower-case "kd", as unknown
/// parameters; its Kd is then the default and not comparable.
bool kd_unread(const tinyobj::material_t& material) {
    for (const auto& [key, value] : material.unknown_parameter)
        if (key.size() == 2 && (key[0] == 'k' || key[0] == 'K') && (key[1] == 'd' || key[1] == 'D'))
            return true;
    return false;
}

glm::vec3 vec3_at(const std::vector<tinyobj::real_t>& values, int index) {
    const auto i = static_cast<std::size_t>(index) * 3;
    return {values[i], values[i + 1], values[i + 2]};
}

struct Counts {
    std::size_t triangles = 0;   // in tinyobjloader's polygons, fanned
    std::size_t zero_area = 0;   // of those, with zero area
    std::size_t coincident = 0;  // of those, with two corners at the same position
    std::size_t loaded = 0;      // in our scene
};

/// Loads `path` with both loaders and compares the scenes.
Counts compare_with_tinyobj(const fs::path& path) {
    const Scene ours = load_obj(path);

    tinyobj::ObjReaderConfig config;
    config.triangulate = false;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path.string(), config)) {
        ADD_FAILURE() << "tinyobjloader cannot read " << path << ": " << reader.Error();
        return {};
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const std::vector<tinyobj::material_t>& materials = reader.GetMaterials();

    constexpr int kMaxReports = 5;  // per kind of difference, so a bad load stays readable
    int position_diffs = 0;
    int normal_diffs = 0;
    int material_diffs = 0;
    Counts counts;
    counts.loaded = ours.triangles.size();
    std::size_t k = 0;  // our triangle
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            const tinyobj::index_t* polygon = &shape.mesh.indices[offset];
            const std::size_t n = shape.mesh.num_face_vertices[f];
            offset += n;
            const int material_id = shape.mesh.material_ids[f];
            for (std::size_t i = 1; i + 1 < n; ++i) {
                const tinyobj::index_t corners[3] = {polygon[0], polygon[i], polygon[i + 1]};
                glm::vec3 p[3];
                for (int c = 0; c < 3; ++c)
                    p[c] = vec3_at(attrib.vertices, corners[c].vertex_index);
                ++counts.triangles;
                if (zero_area(p[0], p[1], p[2])) {
                    ++counts.zero_area;
                    counts.coincident += p[0] == p[1] || p[1] == p[2] || p[0] == p[2];
                }
                if (k >= ours.triangles.size()) {
                    ADD_FAILURE() << path << ": we have fewer triangles than tinyobjloader";
                    return counts;
                }
                for (int c = 0; c < 3; ++c) {
                    const glm::vec3& q = ours.positions[ours.triangles[k][c]];
                    if (q != p[c] && ++position_diffs <= kMaxReports) {
                        ADD_FAILURE() << path << ": triangle " << k << " corner " << c << ": ("
                                      << q.x << ", " << q.y << ", " << q.z << ") vs tinyobj ("
                                      << p[c].x << ", " << p[c].y << ", " << p[c].z << ")";
                    }
                }

                // Same vn index, except that a zero-length vn counts as none for us.
                for (int c = 0; c < 3; ++c) {
                    int expected = corners[c].normal_index;
                    if (expected >= 0 && vec3_at(attrib.normals, expected) == glm::vec3(0.0f)) {
                        expected = -1;
                    }
                    const int got =
                        ours.triangle_normals.empty() ? -1 : ours.triangle_normals[k][c];
                    const bool same =
                        got == expected &&
                        (got < 0 ||
                         glm::length(ours.normals[got] -
                                     glm::normalize(vec3_at(attrib.normals, got))) < 1e-6f);
                    if (!same && ++normal_diffs <= kMaxReports) {
                        ADD_FAILURE() << path << ": triangle " << k << " corner " << c
                                      << ": normal " << got << " vs tinyobj " << expected;
                    }
                }

                const Material& material = ours.materials[ours.triangle_materials[k]];
                if (material_id < 0) {
                    if (material.kd != glm::vec3(0.8f) && ++material_diffs <= kMaxReports) {
                        ADD_FAILURE() << path << ": triangle " << k << " has material "
                                      << material.name << ", tinyobj none";
                    }
                } else {
                    const tinyobj::material_t& theirs = materials[material_id];
                    const glm::vec3 kd(theirs.diffuse[0], theirs.diffuse[1], theirs.diffuse[2]);
                    const glm::vec3 ke(theirs.emission[0], theirs.emission[1], theirs.emission[2]);
                    const bool same = material.name == theirs.name &&
                                      (kd_unread(theirs) || material.kd == kd) && material.ke == ke;
                    if (!same && ++material_diffs <= kMaxReports) {
                        ADD_FAILURE() << path << ": triangle " << k << " has material "
                                      << material.name << ", tinyobj " << theirs.name;
                    }
                }
                ++k;
            }
        }
    }
    EXPECT_EQ(k, ours.triangles.size()) << path;
    EXPECT_EQ(position_diffs, 0) << path;
    EXPECT_EQ(normal_diffs, 0) << path;
    EXPECT_EQ(material_diffs, 0) << path;
    return counts;
}

struct KnownScene {
    const char* name;
    const char* file;  // relative to the repository (bundled) or to scenes_dir()
    std::size_t triangles;
};

class BundledAsset : public ::testing::TestWithParam<KnownScene> {};

TEST_P(BundledAsset, AgreesWithTinyobjloader) {
    const Counts counts = compare_with_tinyobj(test::source_dir() / GetParam().file);
    EXPECT_EQ(counts.triangles, GetParam().triangles);
}

INSTANTIATE_TEST_SUITE_P(
    ObjReference, BundledAsset,
    ::testing::Values(KnownScene{"CornellBox", "assets/cornell-box/CornellBox-Original.obj", 36},
                      KnownScene{"Spot", "assets/spot/spot.obj", 5856},
                      KnownScene{"Teapot", "assets/teapot/teapot.obj", 6320}),
    [](const auto& info) { return std::string(info.param.name); });

// Triangle counts from ../shared/scenes/README.md.
const KnownScene kLargeScenes[] = {
    {"CornellBox", "cornell-box/CornellBox-Original.obj", 36},
    {"Teapot", "teapot/teapot.obj", 6320},
    {"Suzanne", "suzanne/suzanne.obj", 968},
    {"Spot", "spot/spot.obj", 5856},
    {"Dragon", "dragon/dragon_vrip_res3.obj", 47794},
    {"Bunny", "bunny/stanford-bunny.obj", 69451},
    {"Sponza", "sponza/sponza.obj", 66445},
    {"Sibenik", "sibenik/sibenik.obj", 73564},
    {"Buddha", "buddha/buddha.obj", 100000},
    {"Conference", "conference/conference.obj", 331179},
};

class LargeScene : public ::testing::TestWithParam<KnownScene> {};

TEST_P(LargeScene, AgreesWithTinyobjloaderAndTheReadme) {
    if (const std::string why = test::missing_scene(GetParam().file); !why.empty())
        GTEST_SKIP() << why;
    const fs::path path = test::scenes_dir() / GetParam().file;
    const Counts counts = compare_with_tinyobj(path);
    EXPECT_EQ(counts.triangles, GetParam().triangles);
    if (std::string_view(GetParam().name) == "Conference") {
        EXPECT_EQ(counts.coincident, 52670u) << "README: triangles with two coincident vertices";
    }
    // Every triangle, zero-area ones included, so triangles keep their number in file order.
    EXPECT_EQ(counts.loaded, GetParam().triangles);
}

INSTANTIATE_TEST_SUITE_P(ObjReference, LargeScene, ::testing::ValuesIn(kLargeScenes),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace edacrt
