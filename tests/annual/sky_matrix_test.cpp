// Sky vectors: exact patch means for skies with closed forms (uniform; the CIE overcast sky,
// linear in sin altitude), the sky's horizontal illuminance reproduced by the patches under
// Perez skies of the Chicago file (overcast, clear, intermediate, low sun) against
// Sky::horizontal_illuminance_lx()'s own quadrature, and a year of the Chicago file: night
// hours black, the ground's radiance from the sky and sun it receives, the sun against the
// file's own illuminance fields, results independent of the thread count.

#include "annual/sky_matrix.h"

#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/rgb.h"

#include "common/test_util.h"

namespace penumbra::annual {
namespace {

constexpr double k_deg = k_pi / 180;

const Weather& chicago() {
    static const Weather weather =
        read_epw(test::source_path("data/weather/chicago_ohare_tmy3.epw"));
    return weather;
}

/// Σ mean radiance × projected solid angle over the sky's patches, lx.
double horizontal_lx(const Eigen::VectorXf& vector, const SkyPatches& patches) {
    double sum = 0;
    for (std::size_t p = 1; p < patches.size(); ++p)
        sum += vector(Eigen::Index(p)) * patches[p].horizontal_projected_solid_angle_sr;
    return sum * k_luminous_efficacy_lm_per_w;
}

TEST(SkyVector, UniformSkyGivesItsRadianceInEveryPatch) {
    SkyDescription uniform;
    uniform.model = UniformSky{};
    uniform.level = ZenithLuminance{179 * 3.0};
    const Sky sky = make_sky(uniform);
    const SkyPatches patches(2);
    const Eigen::VectorXf v = sky_vector(sky, patches);
    for (std::size_t p = 1; p < patches.size(); ++p)
        ASSERT_NEAR(v(Eigen::Index(p)), 3.0, 3e-6) << "patch " << p;
    EXPECT_NEAR(v(0), *sky.ground_radiance, 1e-6);
}

TEST(SkyVector, OvercastSkyMeansAreExact) {
    // L = L_z (1 + 2 sin alt) / 3 is linear in z = sin alt, so a patch's mean is L_z (1 +
    // z0 + z1) / 3 (dω = dz dφ).
    SkyDescription overcast;
    overcast.level = ZenithLuminance{179};
    const Sky sky = make_sky(overcast);
    for (int mf : {1, 4}) {
        const SkyPatches patches(mf);
        const Eigen::VectorXf v = sky_vector(sky, patches);
        for (std::size_t p = 1; p < patches.size(); ++p) {
            const double z0 = std::sin(patches[p].altitude_min_deg * k_deg);
            const double z1 = std::sin(patches[p].altitude_max_deg * k_deg);
            ASSERT_NEAR(v(Eigen::Index(p)), (1 + z0 + z1) / 3, 1e-6) << "MF " << mf << " " << p;
        }
    }
}

/// The Perez sky and sun of hour \p index of the Chicago file, as sky_matrix() builds them.
PerezSkyAndSun chicago_hour(std::size_t index, const Compass& compass = {}) {
    const Weather& w = chicago();
    const WeatherHour& h = w.hours[index];
    const SolarAngles angles = sun_position(w, index);
    return perez_sky_and_sun(SolarIrradiance{h.direct_normal_w_m2, h.diffuse_horizontal_w_m2},
                             compass, compass.direction(angles.altitude_deg, angles.azimuth_deg),
                             day_of_year(w, index));
}

// Hours of the Chicago file (index = line − 9): 3/25 hour 11 overcast (DNI 0), 6/21 hour 13
// clear (DNI 734), 9/15 hour 10 intermediate (DNI 316, DHI 271), 3/21 hour 7 low sun (DNI
// 241), 1/1 hour 12 clear winter (DNI 521).
constexpr std::size_t k_test_hours[] = {2002, 4116, 6177, 1902, 11};

/// \p sky's mean radiance over \p patch by a 400 × 400 midpoint rule in (sin alt, azimuth).
double midpoint_mean(const Sky& sky, const SkyPatch& patch) {
    const double z0 = std::sin(patch.altitude_min_deg * k_deg);
    const double z1 = std::sin(patch.altitude_max_deg * k_deg);
    const double width = patch.azimuth_max_deg - patch.azimuth_min_deg;
    constexpr int n = 400;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double altitude = std::asin(z0 + (z1 - z0) * (i + 0.5) / n) / k_deg;
        for (int j = 0; j < n; ++j)
            sum += to_photometric(sky.radiance(
                sky.compass.direction(altitude, patch.azimuth_min_deg + width * (j + 0.5) / n)));
    }
    return sum / (n * n) / k_luminous_efficacy_lm_per_w;
}

TEST(SkyVector, PatchMeansAreConvergedQuadratures) {
    // Against a 400 × 400 midpoint rule: the patch holding the sun (its circumsolar peak's cusp
    // is the sharpest feature a patch holds) and its neighbour, which take the fine rule, and
    // patches far from the sun (near the horizon opposite, high across), which take the coarse
    // one; a low sun and a high one. Measured: at most 2.4e-4 (MF 1: the coarse rule on the kink
    // at 0.57° where Perez's formula is clamped at Dz = 0.01) and 2.6e-4 (MF 4).
    for (std::size_t hour : {1902u, 4116u}) {
        const Sky sky = chicago_hour(hour).sky;
        const SolarAngles sun = sun_position(chicago(), hour);
        for (int mf : {1, 4}) {
            const SkyPatches patches(mf);
            const Eigen::VectorXf v = sky_vector(sky, patches);
            const std::size_t sun_patch = patches.find(sky.sun_direction);
            const Compass compass;
            for (std::size_t p : {sun_patch, sun_patch + 1,
                                  patches.find(compass.direction(5, sun.azimuth_deg + 180)),
                                  patches.find(compass.direction(60, sun.azimuth_deg + 90))})
                EXPECT_NEAR(v(Eigen::Index(p)) / midpoint_mean(sky, patches[p]), 1, 3e-4)
                    << "hour " << hour << " MF " << mf << " patch " << p;
        }
    }
}

TEST(SkyVector, PatchesReproduceTheSkysHorizontalIlluminance) {
    // Σ mean radiance × projected solid angle against the sky's own ∫ L cos θ dω: they differ
    // by the covariance of L and cos θ within each patch (the quadrature is converged: 4× its
    // nodes change these by < 1e-5). Measured: Tregenza's patches within 0.42 % for the CIE
    // overcast sky and 1.9 % for the low sun; MF 2 within 0.5 %; MF 4 within 0.13 %.
    const double tolerance[] = {0, 0.025, 0.006, 0, 0.002};
    SkyDescription overcast;
    overcast.level = HorizontalIlluminance{10000};
    std::vector<Sky> skies{make_sky(overcast)};
    for (std::size_t index : k_test_hours)
        skies.push_back(chicago_hour(index).sky);
    for (int mf : {1, 2, 4}) {
        const SkyPatches patches(mf);
        for (std::size_t k = 0; k < skies.size(); ++k) {
            const double expected = skies[k].horizontal_illuminance_lx();
            const double got = horizontal_lx(sky_vector(skies[k], patches), patches);
            EXPECT_NEAR(got / expected, 1, tolerance[mf]) << "MF " << mf << " sky " << k;
        }
    }
}

class ChicagoYear : public testing::Test {
protected:
    static void SetUpTestSuite() {
        patches_ = new SkyPatches(1);
        matrix_ = new SkyMatrix(sky_matrix(chicago(), *patches_, {}, test::quiet_context()));
    }
    static void TearDownTestSuite() {
        delete matrix_;
        delete patches_;
    }
    static const SkyPatches* patches_;
    static const SkyMatrix* matrix_;
};
const SkyPatches* ChicagoYear::patches_ = nullptr;
const SkyMatrix* ChicagoYear::matrix_ = nullptr;

TEST_F(ChicagoYear, HasOneColumnPerHourAndBlackNights) {
    const SkyMatrix& m = *matrix_;
    ASSERT_EQ(m.radiance.rows(), 146);
    ASSERT_EQ(m.radiance.cols(), 8760);
    ASSERT_EQ(m.suns.size(), 8760u);
    // Black: no diffuse light and no sun above the horizon. awk: 4 057 lines with fields 15 and
    // 16 both 0, and 12 more with 0 diffuse and 1–18 W/m² of direct before sunrise or after
    // sunset at mid-hour (e.g. line 2270, 4/5 hour 6, DNI 18).
    int black = 0, dark = 0;
    for (std::size_t i = 0; i < 8760; ++i) {
        const WeatherHour& h = chicago().hours[i];
        const bool no_light = h.diffuse_horizontal_w_m2 == 0 &&
                              (h.direct_normal_w_m2 == 0 || m.suns[i].angles.altitude_deg <= 0);
        dark += no_light;
        black += m.radiance.col(Eigen::Index(i)).isZero(0);
        if (no_light) {
            ASSERT_TRUE(m.radiance.col(Eigen::Index(i)).isZero(0)) << "hour " << i;
        }
    }
    EXPECT_EQ(dark, 4057 + 12);
    EXPECT_EQ(black, dark);
}

TEST_F(ChicagoYear, SunsLieOnTheirAnglesAndShineOnlyAboveTheHorizon) {
    const Compass compass;
    for (const HourSun& sun : matrix_->suns) {
        const Vec3 expected = compass.direction(sun.angles.altitude_deg, sun.angles.azimuth_deg);
        ASSERT_NEAR(length(sun.direction - expected), 0, 1e-12);
        if (sun.angles.altitude_deg <= 0) {
            ASSERT_EQ(sun.normal_lx, 0);
        }
    }
}

TEST_F(ChicagoYear, GroundReflectsTheSkyAndSunItReceives) {
    // Patch 0: ρ_g (E_sky + E_sun sin alt) / (π 179), E_sky the sky's unobstructed horizontal
    // illuminance (its own quadrature, 1e-4), E_sun the matrix's sun.
    for (std::size_t index : k_test_hours) {
        const HourSun& sun = matrix_->suns[index];
        const double global_lx = chicago_hour(index).sky.horizontal_illuminance_lx() +
                                 sun.normal_lx * std::sin(sun.angles.altitude_deg * k_deg);
        EXPECT_NEAR(matrix_->radiance(0, Eigen::Index(index)) / (0.2 * global_lx / (k_pi * 179)), 1,
                    1e-3)
            << "hour " << index;
    }
}

TEST_F(ChicagoYear, SunsIlluminanceAgreesWithTheFilesIlluminanceField) {
    // TMY3's illuminance fields come from Perez et al. 1990's efficacies with each hour's
    // precipitable water; ours use gendaylit's 2 cm. Measured: −2.6 %, −10.9 %, −8.2 %; a
    // wrong field or unit would be off by far more.
    for (std::size_t index : {4116u, 6177u, 11u}) {
        const double file_lx = *chicago().hours[index].direct_normal_lx;
        EXPECT_NEAR(matrix_->suns[index].normal_lx / file_lx, 1, 0.15) << "hour " << index;
    }
}

/// A few hours of the Chicago file as a weather of their own.
Weather chicago_hours(std::size_t first, std::size_t count) {
    Weather w = chicago();
    w.hours = {chicago().hours.begin() + std::ptrdiff_t(first),
               chicago().hours.begin() + std::ptrdiff_t(first + count)};
    return w;
}

TEST(SkyMatrix, IlluminanceInputKeepsTheFilesValues) {
    const Weather w = chicago_hours(4104, 24); // 6/21
    SkyMatrixOptions options;
    options.input = WeatherInput::illuminance;
    const SkyPatches patches(2);
    const SkyMatrix m = sky_matrix(w, patches, options, test::quiet_context());
    for (std::size_t i = 0; i < 24; ++i) {
        if (m.suns[i].angles.altitude_deg <= 0)
            continue;
        EXPECT_NEAR(m.suns[i].normal_lx / *w.hours[i].direct_normal_lx, 1, 1e-6);
        EXPECT_NEAR(horizontal_lx(m.radiance.col(Eigen::Index(i)), patches) /
                        *w.hours[i].diffuse_horizontal_lx,
                    1, 0.006); // MF 2's patches, as above
    }
}

TEST(SkyMatrix, DoesNotDependOnTheThreadCount) {
    const Weather w = chicago_hours(6168, 48);
    const SkyPatches patches(2);
    const SkyMatrix one = sky_matrix(w, patches, {}, test::quiet_context(1));
    const SkyMatrix two = sky_matrix(w, patches, {}, test::quiet_context(2));
    EXPECT_TRUE(one.radiance == two.radiance);
}

TEST(SkyMatrix, NamesAMissingIlluminanceField) {
    Weather w = chicago_hours(4104, 24);
    w.hours[12].diffuse_horizontal_lx.reset();
    SkyMatrixOptions options;
    options.input = WeatherInput::illuminance;
    try {
        sky_matrix(w, SkyPatches(1), options, test::quiet_context());
        FAIL() << "accepted a missing field";
    } catch (const InputError& e) {
        EXPECT_EQ(e.line(), 4104 + 12 + 9);
        EXPECT_EQ(e.key(), "field 19 (diffuse horizontal illuminance)");
    }
    options.input = WeatherInput::irradiance;
    options.ground_reflectance = 1.5;
    EXPECT_THROW(sky_matrix(w, SkyPatches(1), options, test::quiet_context()), ConfigError);
}

} // namespace
} // namespace penumbra::annual
