// Texel supersamples and dilation.

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "lightmap/layout_checks.h"
#include "lightmap/texels.h"

namespace penumbra::test {
namespace {

using namespace lightmap;

TEST(Texels, SupersamplesStayOnTheChartInsideTheTexel) {
    Scene scene;
    // A right triangle: interior texels get all n² samples, texels on the hypotenuse fewer.
    Polygon p;
    p.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.name = "triangle";
    p.material = add_material(scene, "white", Rgb(0.5, 0.5, 0.5));
    scene.polygons.push_back(p);
    const Context ctx = quiet_context();
    const Charts charts = build_charts(scene, {}, ctx);
    const AtlasLayout layout = pack_atlases(charts, {.texels_per_metre = 10, .size = 16}, ctx);
    const std::vector<AtlasTexels> atlases = rasterize(charts, layout, ctx);
    ASSERT_EQ(atlases.size(), 1u);
    std::size_t full = 0, partial = 0;
    for (const Texel& t : atlases[0].texels) {
        const auto samples =
            texel_samples(charts.charts[0], layout.placements[0], atlases[0], t, 4);
        ASSERT_FALSE(samples.empty());
        (samples.size() == 16 ? full : partial) += 1;
        for (const SurfacePoint& s : samples) {
            EXPECT_GE(s.texel_uv.x, t.x);
            EXPECT_LE(s.texel_uv.x, t.x + 1);
            EXPECT_GE(s.texel_uv.y, t.y);
            EXPECT_LE(s.texel_uv.y, t.y + 1);
            EXPECT_LT(distance_to_triangle(s.position, p.vertices[0], p.vertices[1], p.vertices[2]),
                      1e-9);
            EXPECT_NEAR(s.position.z, 0, 1e-12);
            EXPECT_DOUBLE_EQ(s.normal.z, 1.0);
        }
    }
    // 10 × 10 texels, half a square: 45 strictly inside, 10 on the diagonal plus the
    // neighbours it grazes.
    EXPECT_EQ(full, 45u);
    EXPECT_GE(partial, 10u);
}

TEST(Texels, DilationCopiesTheNearestCoveredTexelWithinTheRadius) {
    Image image(7, 1);
    std::vector<std::uint8_t> covered(7, 0);
    image.at(1, 0) = Rgb(1, 0, 0);
    image.at(4, 0) = Rgb(0, 1, 0);
    covered[1] = covered[4] = 1;
    dilate(image, covered, 2);
    EXPECT_EQ(image.at(0, 0), Rgb(1, 0, 0));
    EXPECT_EQ(image.at(2, 0), Rgb(1, 0, 0));
    EXPECT_EQ(image.at(3, 0), Rgb(0, 1, 0));
    EXPECT_EQ(image.at(5, 0), Rgb(0, 1, 0));
    EXPECT_EQ(image.at(6, 0), Rgb(0, 1, 0));

    Image far(5, 1);
    std::vector<std::uint8_t> one(5, 0);
    far.at(0, 0) = Rgb(1, 1, 1);
    one[0] = 1;
    dilate(far, one, 2);
    EXPECT_EQ(far.at(2, 0), Rgb(1, 1, 1));
    EXPECT_EQ(far.at(3, 0), Rgb(0, 0, 0)); // beyond the radius
}

TEST(Texels, DilationTiesGoToTheFirstTexelInRowMajorOrder) {
    Image image(3, 3);
    std::vector<std::uint8_t> covered(9, 0);
    image.at(1, 0) = Rgb(1, 0, 0); // above the centre
    image.at(0, 1) = Rgb(0, 1, 0); // left of it, the same distance
    covered[1] = covered[3] = 1;
    dilate(image, covered, 1);
    EXPECT_EQ(image.at(1, 1), Rgb(1, 0, 0));
}

} // namespace
} // namespace penumbra::test
