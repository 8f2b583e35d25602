// Sky patches: Radiance's counts (gendaymtx -m), Tregenza's published rows, solid angles that
// tile the sphere (2π for the sky, π projected), the lookup against the bounds for each centre
// and random directions, and the lookup integrated over an equal-area grid against each
// patch's solid angle (an independent quadrature of the same partition).

#include "annual/sky_patches.h"

#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/rng.h"

namespace penumbra::annual {
namespace {

constexpr double k_deg = k_pi / 180;

/// A compass that is not the default frame: up along +y, north along −x.
Compass tilted_compass() {
    return Compass{Vec3(0, 1, 0), Vec3(-1, 0, 0)};
}

class SkyPatchesBySubdivision : public testing::TestWithParam<int> {};

TEST_P(SkyPatchesBySubdivision, CountAsRadianceDoes) {
    // gendaymtx: 144 MF² + 2 rows of the matrix (ground, sky, cap); 146, 578, 1298, 2306.
    const int mf = GetParam();
    const SkyPatches patches(mf);
    EXPECT_EQ(patches.size(), std::size_t(144 * mf * mf + 2));
    EXPECT_DOUBLE_EQ(patches.row_height_deg(), 90.0 / (7 * mf + 0.5));
}

TEST_P(SkyPatchesBySubdivision, TileTheSphere) {
    const SkyPatches patches(GetParam(), tilted_compass());
    double sky = 0, projected = 0;
    for (std::size_t p = 1; p < patches.size(); ++p) {
        sky += patches[p].solid_angle_sr;
        projected += patches[p].horizontal_projected_solid_angle_sr;
    }
    EXPECT_NEAR(sky, 2 * k_pi, 1e-12);
    EXPECT_NEAR(projected, k_pi, 1e-12);
    EXPECT_DOUBLE_EQ(patches[SkyPatches::ground].solid_angle_sr, 2 * k_pi);
    EXPECT_EQ(patches[SkyPatches::ground].horizontal_projected_solid_angle_sr, 0);
    const double half_row = patches.row_height_deg() / 2 * k_deg;
    EXPECT_NEAR(patches[patches.size() - 1].solid_angle_sr, 2 * k_pi * (1 - std::cos(half_row)),
                1e-14);
}

TEST_P(SkyPatchesBySubdivision, FindEachCentreInItsOwnPatch) {
    const SkyPatches patches(GetParam(), tilted_compass());
    for (std::size_t p = 0; p < patches.size(); ++p)
        ASSERT_EQ(patches.find(patches[p].centre), p) << "patch " << p;
}

bool azimuth_within(double azimuth, const SkyPatch& patch) {
    for (double shifted : {azimuth - 360, azimuth, azimuth + 360})
        if (shifted >= patch.azimuth_min_deg && shifted <= patch.azimuth_max_deg)
            return true;
    return false;
}

TEST_P(SkyPatchesBySubdivision, FindRandomDirectionsWithinTheirPatchBounds) {
    const Compass compass = tilted_compass();
    const SkyPatches patches(GetParam(), compass);
    Pcg32 rng(7, 11);
    for (int i = 0; i < 20000; ++i) {
        const double altitude = std::asin(2 * rng.next_double() - 1) / k_deg; // uniform on sphere
        const double azimuth = 360 * rng.next_double();
        const std::size_t p = patches.find(compass.direction(altitude, azimuth) * 3.0);
        const SkyPatch& patch = patches[p];
        SCOPED_TRACE(fmt::format("altitude {} azimuth {} → patch {}", altitude, azimuth, p));
        ASSERT_GE(altitude, patch.altitude_min_deg - 1e-9);
        ASSERT_LE(altitude, patch.altitude_max_deg + 1e-9);
        ASSERT_TRUE(azimuth_within(azimuth, patch));
        ASSERT_EQ(p == SkyPatches::ground, altitude < 0);
    }
}

INSTANTIATE_TEST_SUITE_P(Mf, SkyPatchesBySubdivision, testing::Values(1, 2, 3, 4),
                         [](const auto& info) { return "mf" + std::to_string(info.param); });

TEST(SkyPatches, TregenzasRowsAreTwelveDegreesHigh) {
    // Tregenza 1987: rows 0–12°, …, 72–84° of 30, 30, 24, 24, 18, 12, 6 patches, a cap above.
    const SkyPatches patches(1);
    const int counts[] = {30, 30, 24, 24, 18, 12, 6, 1};
    std::size_t p = 1;
    for (int row = 0; row < 8; ++row) {
        for (int k = 0; k < counts[row]; ++k, ++p) {
            EXPECT_NEAR(patches[p].altitude_min_deg, 12.0 * row, 1e-12);
            EXPECT_NEAR(patches[p].altitude_max_deg, row < 7 ? 12.0 * (row + 1) : 90.0, 1e-12);
        }
    }
    EXPECT_EQ(p, patches.size());
    // Each row starts centred on north and runs clockwise (north → east) seen from above.
    EXPECT_NEAR(patches[1].azimuth_min_deg, -6, 1e-12);
    EXPECT_NEAR(patches[2].azimuth_min_deg, 6, 1e-12);
    const Compass compass;
    EXPECT_NEAR(dot(patches[1].centre, compass.north), std::cos(6 * k_deg), 1e-12);
    EXPECT_GT(dot(patches[2].centre, compass.east()), 0);
    EXPECT_NEAR(patches[31].altitude_min_deg, 12, 1e-12); // the second row's first patch
}

TEST(SkyPatches, LookupIntegratesToEachPatchsSolidAngle) {
    // A 0.1° × 0.1° grid in altitude and azimuth, each cell weighed by its exact solid angle
    // and given to the patch its centre falls in: a patch gets its solid angle within the cells
    // its edges cut. Tregenza's edges lie on the grid (exact but for the 0.037° offset in
    // azimuth); MF 2's rows, 6.207° high, can gain up to one 0.1° cell: 1.6 %.
    for (int mf : {1, 2}) {
        const SkyPatches patches(mf);
        constexpr int n_altitude = 900, n_azimuth = 3600;
        const double step = 0.1 * k_deg;
        std::vector<double> found(patches.size(), 0.0);
        for (int i = 0; i < n_altitude; ++i) {
            const double cell = step * (std::sin((i + 1) * step) - std::sin(i * step));
            for (int j = 0; j < n_azimuth; ++j)
                found[patches.find(Compass{}.direction((i + 0.5) * 0.1, (j + 0.37) * 0.1))] += cell;
        }
        for (std::size_t p = 1; p < patches.size(); ++p)
            ASSERT_NEAR(found[p] / patches[p].solid_angle_sr, 1, mf == 1 ? 0.005 : 0.017)
                << "MF " << mf << " patch " << p;
    }
}

TEST(SkyPatches, RefuseASubdivisionOutOfRange) {
    EXPECT_THROW(SkyPatches(0), ConfigError);
    EXPECT_THROW(SkyPatches(17), ConfigError);
}

} // namespace
} // namespace penumbra::annual
