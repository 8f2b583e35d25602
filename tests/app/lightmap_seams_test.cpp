// Seam stitching (issue #29) on the Cornell box: the seam error of the filled atlases drops
// below a stated bound, and every texel outside the seams' bilinear footprints keeps its bits.

#include <cmath>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "app/lightmap.h"
#include "common/bake_util.h"
#include "common/test_util.h"
#include "lightmap/seams.h"

namespace penumbra {
namespace {

TEST(LightmapSeams, CornellSeamsCloseAndOtherTexelsStayPut) {
    Scene scene = test::cornell_box(0.3);
    scene.solver.method = SolverMethod::shooting; // fast; the solution's accuracy is not tested
    app::LightmapOptions options;
    options.atlas.texels_per_metre = 60;
    options.atlas.size = 256;
    options.stitch_seams = false;
    const app::LightmapResult r = app::bake_lightmaps(scene, options, test::quiet_context());
    const BBox box = scene.bounds();
    const lightmap::Seams seams =
        lightmap::find_seams(r.charts, r.layout, 1e-6 * length(box.hi - box.lo), 180);
    // Creases included (180°): the room's 8 edges between walls, floor and ceiling; 8 per
    // block (4 upright, 4 on top; the blocks have no bottom). The lamp only touches the ceiling.
    EXPECT_EQ(seams.edges, 24u);
    // By default only smooth seams: the Cornell box has none (every chart edge is a crease).
    EXPECT_EQ(lightmap::find_seams(r.charts, r.layout, 1e-6 * length(box.hi - box.lo)).edges, 0u);
    std::vector<Image> stitched = r.atlases;
    const lightmap::SeamStitch s = lightmap::stitch_seams(stitched, seams, 10);
    // Seam error, W/m² (largest channel); measured with the hierarchical solve: mean 0.41,
    // max 4.3 before (under the lamp the ceiling's and the walls' irradiance differ most),
    // 0.002 and 0.09 after (docs/lightmaps.md).
    EXPECT_GT(s.before.mean, 0.02);
    EXPECT_LT(s.after.mean, 0.01 * s.before.mean);
    EXPECT_LT(s.after.max, 0.05 * s.before.max); // where three charts meet at a block's corner
    // The footprints: the four texels around each sample point, on both sides.
    std::set<std::tuple<std::uint32_t, int, int>> footprint;
    for (const lightmap::SeamSample& p : seams.samples)
        for (const auto& [atlas, uv] : {std::pair(p.atlas_a, p.uv_a), std::pair(p.atlas_b, p.uv_b)})
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx)
                    footprint.emplace(atlas, int(std::floor(uv.x - 0.5)) + dx,
                                      int(std::floor(uv.y - 0.5)) + dy);
    EXPECT_EQ(footprint.size(), s.texels);
    std::size_t kept = 0;
    for (std::uint32_t a = 0; a < stitched.size(); ++a)
        for (int y = 0; y < stitched[a].height; ++y)
            for (int x = 0; x < stitched[a].width; ++x) {
                if (footprint.count({a, x, y}))
                    continue;
                const Rgb before = r.atlases[a].at(x, y), after = stitched[a].at(x, y);
                ASSERT_TRUE(before.r == after.r && before.g == after.g && before.b == after.b)
                    << "texel " << x << ", " << y << " moved";
                ++kept;
            }
    EXPECT_GT(kept, 60000u);
}

} // namespace
} // namespace penumbra
