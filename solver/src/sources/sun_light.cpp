// The sun: visibility of its disc and its direct light on elements and points.

#include "sources/sun_light.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/parallel.h"
#include "kernels/form_factor.h"

namespace penumbra::solver {

namespace {

constexpr int k_rim_probes = 16;
/// A point in a penumbra casts this many times solver.visibility_rays rays over the disc.
constexpr int k_penumbra_rays_factor = 8;

/// The transmittances of some segments: their mean (the fraction open, panes of glazing
/// counting their T(θ)) and whether they all agree.
struct OpenFraction {
    double mean = 0;
    bool agree = true;
};

OpenFraction open_fraction(const std::vector<Segment>& segments,
                           const VisibilityQuery& visibility) {
    std::vector<float> t(segments.size());
    visibility.transmittance(segments, t);
    OpenFraction out;
    double open = 0;
    for (float x : t) {
        open += double(x);
        out.agree = out.agree && x == t.front();
    }
    out.mean = open / double(segments.size());
    return out;
}

// The direction of the disc at the point (a, b) of [0, 1)² by Shirley & Chiu's concentric
// map to the unit disc (compact strata from a grid), then the disc's area fraction to the
// cap's solid-angle fraction.
Vec3 sun_disc_direction_concentric(const Sun& sun, double a, double b) {
    const double x = 2 * a - 1, y = 2 * b - 1;
    if (x == 0 && y == 0)
        return sun.direction;
    const bool wide = std::abs(x) > std::abs(y);
    const double radius = wide ? x : y;
    const double phi = wide ? (k_pi / 4) * (y / x) : (k_pi / 2) - (k_pi / 4) * (x / y);
    return sun_disc_direction(sun, radius * radius, (phi + (radius < 0 ? k_pi : 0)) / (2 * k_pi));
}

} // namespace

Vec3 sun_disc_direction(const Sun& sun, double u1, double u2) {
    const double cos_max = std::cos(sun.angular_radius());
    const double z = 1.0 - u1 * (1.0 - cos_max);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * k_pi * u2;
    return Frame::from_normal(sun.direction)
        .to_world(Vec3(r * std::cos(phi), r * std::sin(phi), z));
}

SunRays sun_rays_open(const Sun& sun, const OrientedTriangle& target, double offset,
                      double diagonal, int rays, const VisibilityQuery& visibility, Pcg32& rng) {
    std::vector<Segment> segments(std::size_t(std::max(1, rays)));
    const float reach = distant_reach(diagonal);
    for (Segment& seg : segments) {
        const Vec3 from =
            sample_triangle(target.v, rng.next_double(), rng.next_double()) + target.n * offset;
        const Vec3 dir = sun_disc_direction(sun, rng.next_double(), rng.next_double());
        seg = {Vec3f(from), Vec3f(dir), 0.0f, reach};
    }
    std::vector<float> t(segments.size());
    visibility.transmittance(segments, t);
    SunRays out;
    int blocked = 0;
    for (float x : t) {
        out.open += double(x);
        blocked += x > 0.0f ? 0 : 1;
    }
    out.partial = blocked > 0 && blocked < rays;
    return out;
}

double sun_point_visibility(const Sun& sun, const Vec3& from, double diagonal, int rays,
                            const VisibilityQuery& visibility, Pcg32& rng) {
    const float reach = distant_reach(diagonal);
    const Vec3f origin(from);
    const double radius = sun.angular_radius();
    std::vector<Segment> probes{{origin, Vec3f(sun.direction), 0.0f, reach}};
    if (radius > 0) {
        const Frame frame = Frame::from_normal(sun.direction);
        const double s = std::sin(radius), c = std::cos(radius);
        for (int k = 0; k < k_rim_probes; ++k) {
            const double phi = 2.0 * k_pi * k / k_rim_probes;
            probes.push_back({origin,
                              Vec3f(frame.to_world(Vec3(s * std::cos(phi), s * std::sin(phi), c))),
                              0.0f, reach});
        }
    }
    const OpenFraction probe = open_fraction(probes, visibility);
    if (probe.agree)
        return probe.mean;
    const int side = int(std::ceil(std::sqrt(double(k_penumbra_rays_factor * std::max(rays, 1)))));
    std::vector<Segment> segments;
    segments.reserve(std::size_t(side * side));
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            segments.push_back(
                {origin,
                 Vec3f(sun_disc_direction_concentric(sun, (i + rng.next_double()) / side,
                                                     (j + rng.next_double()) / side)),
                 0.0f, reach});
    return open_fraction(segments, visibility).mean;
}

SunIrradiance sun_triangle_irradiance(const Sun& sun, const OrientedTriangle& target, double offset,
                                      double diagonal, std::uint64_t key, std::uint64_t kind,
                                      const VisibilityQuery& visibility, const RowSettings& rows) {
    const double cos_theta = dot(target.n, sun.direction);
    if (cos_theta <= 0 || sun.irradiance.is_black())
        return {};
    Pcg32 rng = Pcg32::for_stream(RngPurpose::sun_visibility, key, kind, 0, rows.seed);
    const int rays = std::max(1, rows.visibility_rays);
    const SunRays open = sun_rays_open(sun, target, offset, diagonal, rays, visibility, rng);
    return {sun.irradiance * float(cos_theta * open.open / double(rays)), open.partial};
}

RgbD shoot_sun(ShootingState& state, const ElementGeometry& geo, const Sun& sun,
               const VisibilityQuery& visibility, const RowSettings& settings, const Context& ctx) {
    std::vector<Rgb> received(geo.size());
    parallel_for_index(geo.size(), 64, [&](std::size_t j) {
        received[j] = sun_triangle_irradiance(sun, geo.oriented(std::uint32_t(j)), geo.offset,
                                              geo.diagonal, j, 0, visibility, settings)
                          .irradiance;
    });
    const RgbD delivered = state.receive_from_afar(received, geo.area);
    ctx.debug("sun shot: {:.6g} lm delivered", to_photometric(delivered));
    return delivered;
}

} // namespace penumbra::solver
