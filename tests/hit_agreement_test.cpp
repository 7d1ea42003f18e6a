// compare_hits, the check behind `edacrt bench`: identical hits agree, a changed hit is found,
// ties and Embree's ill-conditioned rays are told apart from real differences.
#include "trace/hit_agreement.h"

#include <gtest/gtest.h>

#include "scene/builtin_scenes.h"
#include "trace/naive_tracer.h"

namespace edacrt {
namespace {

struct Fixture {
    Scene scene = make_builtin_scene("builtin:sphere:subdiv=3");
    FrameVector<Triangle> triangles = gather_triangles(scene);
    std::vector<Ray> rays;
    std::vector<Hit> hits;

    Fixture() {
        for (int i = 0; i < 400; ++i)  // a fan of rays from outside, most through the sphere
            rays.push_back({{0.0f, 0.0f, 3.0f},
                            {0.003f * float(i % 20 - 10), 0.003f * float(i / 20 - 10), -1.0f}});
        hits.resize(rays.size());
        NaiveTracer naive;
        naive.set_scene(scene);
        naive.trace(rays, hits, Query::closest);
    }
};

TEST(HitAgreement, IdenticalHitsAgree) {
    const Fixture f;
    const Agreement a = compare_hits(f.triangles, f.rays, f.hits, f.hits, Query::closest, true);
    EXPECT_EQ(a.rays, f.rays.size());
    EXPECT_EQ(a.disagreements, 0u);
    EXPECT_EQ(a.first_disagreement, -1);
}

TEST(HitAgreement, AChangedHitIsADisagreement) {
    const Fixture f;
    std::vector<Hit> got = f.hits;
    ASSERT_TRUE(got[7].hit());
    got[7] = Hit{};     // a miss where the reference hits
    got[9].t *= 1.01f;  // the right triangle at the wrong distance
    Agreement a = compare_hits(f.triangles, f.rays, f.hits, got, Query::closest, true);
    EXPECT_EQ(a.disagreements, 2u);
    EXPECT_EQ(a.first_disagreement, 7);

    got = f.hits;
    got[11].prim = (got[11].prim + 1) % std::int32_t(f.triangles.size());  // a triangle not hit
    a = compare_hits(f.triangles, f.rays, f.hits, got, Query::closest, true);
    EXPECT_EQ(a.disagreements, 1u);
    EXPECT_EQ(a.ties, 0u);

    // Any hit: the occluder must block the ray.
    a = compare_hits(f.triangles, f.rays, f.hits, got, Query::any, true);
    EXPECT_EQ(a.disagreements, 1u);
}

TEST(HitAgreement, EmbreeMayDifferOnlyAtEdges) {
    const Fixture f;
    std::vector<Hit> got = f.hits;
    std::size_t edge = 0, middle = 0;
    while (!got[edge].hit()) ++edge;
    middle = edge + 1;
    while (!got[middle].hit()) ++middle;
    std::vector<Hit> expected = f.hits;
    expected[edge].u = 1e-6f;  // the reference hit lies on an edge: Embree may miss it
    expected[middle].u = expected[middle].v = 0.3f;
    got[edge] = got[middle] = Hit{};
    const Agreement exact = compare_hits(f.triangles, f.rays, expected, got, Query::closest, true);
    EXPECT_EQ(exact.disagreements, 2u);
    const Agreement embree =
        compare_hits(f.triangles, f.rays, expected, got, Query::closest, false);
    EXPECT_EQ(embree.tolerated, 1u);
    EXPECT_EQ(embree.disagreements, 1u);
    EXPECT_EQ(embree.first_disagreement, std::int64_t(middle));
}

}  // namespace
}  // namespace edacrt
