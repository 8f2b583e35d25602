// Lightmaps through the whole pipeline (issue #29): texels against the furnace's analytic
// irradiance, no light under or through a wall, finite non-negative values, the same bits for
// any thread count.

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "app/lightmap.h"
#include "common/bake_util.h"
#include "common/test_util.h"

namespace penumbra {
namespace {

using test::add_material;
using test::add_rect;

app::LightmapResult bake_lightmaps(const Scene& scene, double texels_per_metre, int size,
                                   int threads = 0) {
    app::LightmapOptions options;
    options.atlas.texels_per_metre = texels_per_metre;
    options.atlas.size = size;
    return app::bake_lightmaps(scene, options, test::quiet_context(threads));
}

// ---- Furnace: a closed box whose every surface emits E with reflectance ρ receives
// H = E / (1 − ρ) everywhere: E directly from the walls, ρ H by reflection. ----

TEST(LightmapFurnace, EveryTexelReceivesEOverOneMinusRho) {
    const float rho = 0.5f, exitance = 1.0f;
    Scene scene = test::furnace_room(rho, exitance);
    const app::LightmapResult r = bake_lightmaps(scene, 12, 64);
    const double expected = exitance / (1 - rho);
    double worst = 0;
    std::size_t texels = 0;
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels) {
            const Rgb h = r.atlases[a].at(t.x, t.y);
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(h[c] - expected) / expected);
            ++texels;
        }
    EXPECT_GT(texels, 400u); // the six walls, their edge and corner texels included
    EXPECT_LT(worst, 0.005);
    EXPECT_EQ(r.counts.unlit_texels, 0u);
}

// ---- Leaks: a one-sided lamp on one side of a 10 cm thick wall standing on a floor, every
// reflectance 0. Texels wholly or partly beyond the wall's far face and not reaching its near
// face (some of them partly under the wall) receive nothing: exactly 0. ----

struct WallScene {
    Scene scene;
    double near_x = 2.012, far_x = 2.112; ///< the wall's faces; no texel edge on either
};

WallScene wall_on_floor() {
    WallScene w;
    Scene& s = w.scene;
    const auto black = add_material(s, "black", Rgb(0.0f));
    const auto lamp = add_material(s, "lamp", Rgb(0.0f), Rgb(10.0f), false);
    add_rect(s, "floor", black, {0, 0, 0}, {4, 0, 0}, {0, 2, 0});
    const double x0 = w.near_x, x1 = w.far_x, y0 = -0.5, y1 = 2.5, h = 1.0;
    // A box without a bottom, as the Cornell box's blocks: its sides face outwards.
    add_rect(s, "wall", black, {x0, y0, h}, {x1 - x0, 0, 0}, {0, y1 - y0, 0});
    add_rect(s, "wall", black, {x0, y0, 0}, {x1 - x0, 0, 0}, {0, 0, h});
    add_rect(s, "wall", black, {x1, y0, 0}, {0, y1 - y0, 0}, {0, 0, h});
    add_rect(s, "wall", black, {x1, y1, 0}, {x0 - x1, 0, 0}, {0, 0, h});
    add_rect(s, "wall", black, {x0, y1, 0}, {0, y0 - y1, 0}, {0, 0, h});
    add_rect(s, "lamp", lamp, {0.5, 0.5, 0.8}, {0, 1, 0}, {1, 0, 0}); // faces down, below the top
    s.mesher.max_edge_length = 0.25;
    return w;
}

TEST(LightmapLeak, NothingReachesTheFloorBeyondAWall) {
    const WallScene w = wall_on_floor();
    const double density = 20, half = 0.5 / density;
    const app::LightmapResult r = bake_lightmaps(w.scene, density, 256);
    std::size_t beyond = 0, straddling = 0, lit = 0;
    for (std::size_t a = 0; a < r.texels.size(); ++a)
        for (const lightmap::Texel& t : r.texels[a].texels) {
            const lightmap::Chart& chart = r.charts.charts[t.chart];
            if (chart.object != "floor")
                continue;
            // The floor's chart is axis-aligned in either orientation: a texel's footprint
            // spans its centre ± half a texel along x.
            const double x = t.centre.position.x;
            const Rgb h = r.atlases[a].at(t.x, t.y);
            if (x + half < w.near_x)
                lit += h.g > 0;
            if (x - half < w.near_x || x + half <= w.far_x)
                continue;
            ++beyond;
            straddling += x - half < w.far_x;
            EXPECT_EQ(h.r, 0.0f) << "texel " << t.x << ", " << t.y << " at x = " << x;
            EXPECT_EQ(h.g, 0.0f);
            EXPECT_EQ(h.b, 0.0f);
        }
    EXPECT_GT(beyond, 1000u);
    EXPECT_GT(straddling, 30u); // the column half under the wall's foot
    EXPECT_GT(lit, 1000u);      // the lamp's side is lit
    EXPECT_GT(r.counts.hidden_samples, 0u);
}

// ---- The Cornell box: finite values ≥ 0 in every texel, padding included, and the same
// bits (atlases and preview) on 1 and 2 threads. ----

TEST(LightmapCornell, FiniteNonNegativeAndTheSameForAnyThreadCount) {
    const Scene scene = test::cornell_box(0.15);
    const app::LightmapResult one = bake_lightmaps(scene, 60, 256, 1);
    const app::LightmapResult two = bake_lightmaps(scene, 60, 256, 2);
    ASSERT_EQ(one.atlases.size(), two.atlases.size());
    std::size_t lit = 0;
    for (std::size_t a = 0; a < one.atlases.size(); ++a) {
        for (const Rgb& h : one.atlases[a].pixels)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(h[c]));
                ASSERT_GE(h[c], 0.0f);
                lit += h[c] > 0;
            }
        const auto& p1 = one.atlases[a].pixels;
        const auto& p2 = two.atlases[a].pixels;
        ASSERT_EQ(p1.size(), p2.size());
        EXPECT_EQ(std::memcmp(p1.data(), p2.data(), p1.size() * sizeof(Rgb)), 0)
            << "atlas " << a << " differs between 1 and 2 threads";
    }
    EXPECT_GT(lit, 3 * one.counts.texels / 2);
    // The preview of the box's camera, too.
    ASSERT_TRUE(one.preview && two.preview);
    ASSERT_EQ(one.preview->pixels.size(), two.preview->pixels.size());
    EXPECT_EQ(std::memcmp(one.preview->pixels.data(), two.preview->pixels.data(),
                          one.preview->pixels.size() * sizeof(Rgb)),
              0);
}

} // namespace
} // namespace penumbra
