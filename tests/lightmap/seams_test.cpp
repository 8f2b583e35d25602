// Seams (issue #29): a fold between two charts is found once, and each seam sample names the
// same 3D point in both charts' atlas coordinates; stitching a step across it closes it.

#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "lightmap/atlas.h"
#include "lightmap/seams.h"

namespace penumbra::test {
namespace {

using namespace lightmap;

// The 3D point at atlas coordinates \p uv of the chart triangle that holds it (barycentric
// coordinates of the triangle's texel_uv), if any.
std::optional<Vec3> point_at(const Chart& chart, const ChartPlacement& place, const Vec2& uv) {
    for (const ChartTriangle& t : chart.triangles) {
        const Vec2 a = place.texel_uv[t.vertices[0]], b = place.texel_uv[t.vertices[1]],
                   c = place.texel_uv[t.vertices[2]];
        const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        const double u = ((uv.x - a.x) * (c.y - a.y) - (c.x - a.x) * (uv.y - a.y)) / det;
        const double v = ((b.x - a.x) * (uv.y - a.y) - (uv.x - a.x) * (b.y - a.y)) / det;
        if (u < -1e-9 || v < -1e-9 || u + v > 1 + 1e-9)
            continue;
        return chart.vertices[t.vertices[0]].position * (1 - u - v) +
               chart.vertices[t.vertices[1]].position * u +
               chart.vertices[t.vertices[2]].position * v;
    }
    return std::nullopt;
}

// The 3D point of one side of a seam sample: whichever chart of its atlas holds it.
std::optional<Vec3> seam_point(const Charts& charts, const AtlasLayout& layout, std::uint32_t atlas,
                               const Vec2& uv) {
    for (std::size_t c = 0; c < charts.charts.size(); ++c)
        if (layout.placements[c].atlas == atlas)
            if (const auto p = point_at(charts.charts[c], layout.placements[c], uv))
                return p;
    return std::nullopt;
}

TEST(Seams, AFoldIsOneSeamWhoseSamplesMeetIn3D) {
    Scene scene;
    const auto m = add_material(scene, "white", Rgb(0.5f));
    add_rect(scene, "floor", m, {0, 0, 0}, {1, 0, 0}, {0, 0.6, 0});
    add_rect(scene, "wall", m, {0, 0.6, 0}, {1, 0, 0}, {0, 0, 0.4}); // folded up at y = 0.6
    const Context ctx = quiet_context();
    const Charts charts = build_charts(scene, {}, ctx);
    ASSERT_EQ(charts.charts.size(), 2u);
    AtlasSettings settings;
    settings.texels_per_metre = 20;
    settings.size = 64;
    const AtlasLayout layout = pack_atlases(charts, settings, ctx);
    EXPECT_EQ(find_seams(charts, layout, 1e-9).edges, 0u); // a crease: not stitched by default
    const Seams seams = find_seams(charts, layout, 1e-9, 180);
    EXPECT_EQ(seams.edges, 1u);
    ASSERT_EQ(seams.samples.size(), 60u); // 1 m at 20 texels/m, 3 samples per texel
    for (const SeamSample& s : seams.samples) {
        const auto a = seam_point(charts, layout, s.atlas_a, s.uv_a);
        const auto b = seam_point(charts, layout, s.atlas_b, s.uv_b);
        ASSERT_TRUE(a && b);
        EXPECT_LT(length(*a - *b), 1e-9);
        EXPECT_NEAR(a->y, 0.6, 1e-9);
    }
    // A step across the fold: 1 on the floor's side, 0 on the wall's; stitched, both sides
    // meet near 1/2 and the seam error drops a hundredfold.
    // The floor's texels and the ring of padding its bilinear lookups reach are 1 (the padding
    // keeps the two rings apart).
    std::vector<Image> atlas{Image(64, 64)};
    for (std::size_t c = 0; c < charts.charts.size(); ++c) {
        if (charts.charts[c].object != "floor")
            continue;
        const TexelRect& r = layout.placements[c].rect;
        for (int y = r.y - 1; y < r.y + r.height + 1; ++y)
            for (int x = r.x - 1; x < r.x + r.width + 1; ++x)
                atlas[0].at(x, y) = Rgb(1.0f);
    }
    const SeamStitch st = stitch_seams(atlas, seams, 10);
    EXPECT_NEAR(st.before.mean, 1.0, 1e-6);
    EXPECT_LT(st.after.mean, 0.01);
}

} // namespace
} // namespace penumbra::test
