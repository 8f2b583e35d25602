#include "point_lights.h"

#include <algorithm>

#include "core/parallel.h"
#include "core/rng.h"
#include "form_factor.h"

namespace penumbra::solver {

namespace {

constexpr int k_escape_rays_per_light = 4096;

double visible_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                        const Vec3& light, std::size_t light_id, std::uint32_t j,
                        const RowSettings& settings) {
    Pcg32 rng = Pcg32::for_stream(RngPurpose::point_light_visibility, light_id, j, 0,
                                  settings.seed);
    const int rays = std::max(1, settings.visibility_rays);
    return double(light_rays_open(light, geo.oriented(j), geo.offset, rays, visibility, rng)) /
           double(rays);
}

} // namespace

int light_rays_open(const Vec3& light, const OrientedTriangle& target, double offset, int rays,
                    const VisibilityQuery& visibility, Pcg32& rng) {
    std::vector<Segment> segments(std::size_t(std::max(1, rays)));
    for (Segment& seg : segments) {
        Vec3 to = sample_triangle(target.v, rng.next_double(), rng.next_double()) +
                  target.n * offset;
        seg = {Vec3f(light), Vec3f(to - light), 0.0f, 1.0f};
    }
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    return int(std::count(blocked.begin(), blocked.end(), std::uint8_t(0)));
}

double light_escape_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                             const Vec3& light, std::size_t light_id, std::uint64_t seed) {
    Pcg32 rng = Pcg32::for_stream(RngPurpose::escape_estimate, light_id, 1, 0, seed);
    std::vector<Segment> segments(k_escape_rays_per_light);
    const float reach = float(4.0 * geo.diagonal + 1.0);
    for (Segment& seg : segments)
        seg = {Vec3f(light), Vec3f(sample_sphere(rng.next_double(), rng.next_double())), 0.0f,
               reach};
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    auto misses = std::count(blocked.begin(), blocked.end(), std::uint8_t(0));
    return double(misses) / double(segments.size());
}

void shoot_point_lights(ShootingState& state, const ElementGeometry& geo,
                        const std::vector<PointLight>& lights, const VisibilityQuery& visibility,
                        const RowSettings& settings, const Context& ctx) {
    for (std::size_t l = 0; l < lights.size(); ++l) {
        const PointLight& light = lights[l];
        const Vec3 p = light.position;
        state.emitted += RgbD(light.intensity) * (4.0 * k_pi);
        state.escaped += RgbD(light.intensity) *
                         (4.0 * k_pi * light_escape_fraction(geo, visibility, p, l, settings.seed));
        parallel_for_index(geo.size(), 64, [&](std::size_t j) {
            if (dot(p - geo.triangle[j][0], geo.normal[j]) <= 0)
                return; // the light is behind this side
            double omega = solid_angle_triangle(p, geo.triangle[j]);
            if (omega <= 0)
                return;
            omega *= visible_fraction(geo, visibility, p, l, std::uint32_t(j), settings);
            state.receive(j, light.intensity * float(omega / geo.area[j]), Rgb{});
        });
        ctx.debug("point light '{}' shot", light.name);
    }
}

} // namespace penumbra::solver
