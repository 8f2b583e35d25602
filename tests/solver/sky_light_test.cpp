// The sky's irradiance integral (sources/sky_light) against closed forms, with nothing in the
// way and behind an analytic half-space blocker.

#include "sources/sky_light.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/visibility.h"

namespace penumbra::solver {
namespace {

Sky sky_of(const SkyModel& model, double zenith_radiance) {
    Sky sky;
    sky.model = model;
    sky.zenith_radiance = zenith_radiance;
    sky.horizon = Horizon::sharp;
    return sky;
}

RgbD irradiance(const Sky& sky, const Vec3& n, const VisibilityQuery& visibility,
                const SkyQuadrature& q = k_sky_point_quadrature) {
    Pcg32 rng = Pcg32::for_stream(RngPurpose::sky_visibility, 1, 2, 3, 4);
    return sky_point_irradiance(sky, Vec3(0, 0, 0), n, 10.0, visibility, q, rng);
}

TEST(SkyPointIrradiance, UniformSkyGivesPiL) {
    const NoOcclusion open;
    const RgbD e = irradiance(sky_of(UniformSky{}, 2.0), {0, 0, 1}, open);
    // Every cell sees radiance 2: the cells' projected solid angles sum to π exactly.
    EXPECT_NEAR(e.g, 2.0 * k_pi, 1e-9);
}

TEST(SkyPointIrradiance, OvercastSkyGivesSevenPiOverNineLz) {
    const NoOcclusion open;
    // E_h / L_z = 7π/9 (closed form, /work/shared/validation/README.md §3, 5.9); the
    // jittered samples' noise: 1e-3 with 4 096 of them at the start, 3e-3 with 1 024, 5e-3
    // with 576.
    const std::pair<SkyQuadrature, double> cases[] = {{k_sky_point_quadrature, 1e-3},
                                                      {k_sky_vertex_quadrature, 3e-3},
                                                      {k_sky_element_quadrature, 5e-3}};
    for (const auto& [q, tolerance] : cases) {
        const RgbD e = irradiance(sky_of(CieOvercastSky{}, 1.0), {0, 0, 1}, open, q);
        EXPECT_NEAR(e.g, 7.0 * k_pi / 9.0, tolerance * 7.0 * k_pi / 9.0) << q.side << " a side";
    }
}

TEST(SkyPointIrradiance, VerticalPlaneSeesHalfSkyHalfGround) {
    const NoOcclusion open;
    Sky sky = sky_of(UniformSky{}, 3.0);
    sky.ground_radiance = 1.0;
    // Half the hemisphere's projected solid angle (π/2) on each side of a sharp horizon.
    const RgbD e = irradiance(sky, {1, 0, 0}, open);
    EXPECT_NEAR(e.g, k_pi / 2 * (3.0 + 1.0), 2e-3 * k_pi / 2 * 4.0);
}

/// Blocks every ray that heads below the plane z = x tan(slope) through the origin: a
/// straight edge across the sky, which the cells must find.
class HalfSpaceBlocker final : public VisibilityQuery {
public:
    explicit HalfSpaceBlocker(double slope_deg) : tan_(std::tan(slope_deg * k_pi / 180.0)) {}
    void occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const override {
        for (std::size_t i = 0; i < segments.size(); ++i) {
            const Vec3f& d = segments[i].direction;
            out[i] = double(d.z) < double(d.x) * tan_ ? 1 : 0;
        }
    }
    std::uint64_t rays_traced() const override { return 0; }

private:
    double tan_;
};

TEST(SkyPointIrradiance, EdgeAcrossTheSkyIsResolved) {
    // An upward receiver under a uniform sky, the directions below the plane z = x tan β
    // hidden. Projected onto the unit disc (where cosine-weighted solid angle is area), the
    // open part is the half disc x ≤ 0 and, for x > 0, the half ellipse x² / cos² β + y² ≤ 1:
    // π/2 (1 + cos β).
    const double beta = 60.0;
    const HalfSpaceBlocker blocker(beta);
    const RgbD e = irradiance(sky_of(UniformSky{}, 1.0), {0, 0, 1}, blocker);
    const double open = k_pi / 2 * (1 + std::cos(beta * k_pi / 180.0));
    EXPECT_NEAR(e.g, open, 1e-3 * open);
}

} // namespace
} // namespace penumbra::solver
