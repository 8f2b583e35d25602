// Point gathering: E(x) = Σ_s B_s F(x → s) V(x, s) over source triangles s, plus
// I profile cos θ / d² V for point lights and E_n cos θ V for the sun. Unoccluded values are
// exact (analytic F).

#include "point_gather.h"

#include <cmath>

#include "core/rng.h"
#include "form_factor.h"
#include "sun_light.h"

namespace penumbra::solver {

namespace {

// Visible fraction of triangle s from p. Four probe rays (the centroid, and the corners
// pulled 2 % of the way to it) decide where they agree, as the hierarchical links'
// probes do; where they disagree, the triangle is in p's penumbra and 4 × \p rays rays on a
// jittered grid (stratified through the area-preserving square-to-triangle map) estimate it.
double triangle_visibility(const ElementGeometry& geo, const VisibilityQuery& visibility,
                           const GatherPoint& p, std::uint32_t s, int rays, Pcg32& rng) {
    // As in element_rows.cpp: lift both ends off both planes where they meet at an angle.
    const double cross_weight = geo.offset * (1.0 - std::abs(dot(p.normal, geo.normal[s])));
    const Vec3 from = p.position + p.normal * geo.offset + geo.normal[s] * cross_weight;
    const Vec3 lift = geo.normal[s] * geo.offset + p.normal * cross_weight;
    auto open_fraction = [&](const std::vector<Vec3>& targets) {
        std::vector<Segment> segments(targets.size());
        for (std::size_t i = 0; i < targets.size(); ++i)
            segments[i] = {Vec3f(from), Vec3f(targets[i] + lift - from), 0.0f, 1.0f};
        std::vector<std::uint8_t> blocked(segments.size());
        visibility.occluded(segments, blocked);
        std::size_t open = 0;
        for (auto b : blocked)
            open += b ? 0 : 1;
        return double(open) / double(segments.size());
    };
    const auto& t = geo.triangle[s];
    const Vec3 c = (t[0] + t[1] + t[2]) / 3.0;
    const double probe =
        open_fraction({c, t[0] * 0.98 + c * 0.02, t[1] * 0.98 + c * 0.02, t[2] * 0.98 + c * 0.02});
    if (probe == 0.0 || probe == 1.0)
        return probe;
    const int side = int(std::ceil(std::sqrt(double(4 * std::max(rays, 1)))));
    std::vector<Vec3> targets;
    targets.reserve(std::size_t(side * side));
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            targets.push_back(sample_triangle(t, (i + rng.next_double()) / side,
                                              (j + rng.next_double()) / side));
    return open_fraction(targets);
}

// Form factor from p to element s if s faces p, else 0.
double facing_form_factor(const ElementGeometry& geo, const GatherPoint& p, std::uint32_t s) {
    if (dot(p.position - geo.triangle[s][0], geo.normal[s]) <= geo.offset * 1e-3)
        return 0;
    return form_factor_point_triangle(p.position, p.normal, geo.triangle[s]);
}

} // namespace

Rgb gather_direct(const ElementGeometry& geo, const GatherSources& sources,
                  const VisibilityQuery& visibility, const GatherPoint& p, int rays_per_source,
                  std::uint64_t seed, const std::vector<std::uint32_t>* emitters) {
    RgbD sum;
    Pcg32 rng = Pcg32::for_stream(p.purpose, p.id, 1, 0, seed);
    for (std::uint32_t s : emitters ? *emitters : sources.emitters) {
        double f = facing_form_factor(geo, p, s);
        if (f <= 0)
            continue;
        f *= triangle_visibility(geo, visibility, p, s, rays_per_source, rng);
        sum += RgbD(sources.emission[s]) * f;
    }
    for (const PointLight& light : sources.lights) {
        Vec3 d = light.position - p.position;
        double dist2 = dot(d, d);
        double cos_theta = dot(d, p.normal) / std::sqrt(dist2);
        if (cos_theta <= 0)
            continue;
        const double profile = light.profile(-d / std::sqrt(dist2));
        if (profile <= 0)
            continue; // outside a spot's cone: no ray needed
        Vec3 from = p.position + p.normal * geo.offset;
        Segment seg{Vec3f(from), Vec3f(light.position - from), 0.0f, 1.0f - 1e-6f};
        std::uint8_t blocked = 0;
        visibility.occluded({&seg, 1}, {&blocked, 1});
        if (!blocked)
            sum += RgbD(light.intensity) * (profile * cos_theta / dist2);
    }
    if (sources.sun && !sources.sun->irradiance.is_black()) {
        const Sun& sun = *sources.sun;
        const double cos_theta = dot(p.normal, sun.direction);
        if (cos_theta > 0) {
            Pcg32 sun_rng = Pcg32::for_stream(RngPurpose::sun_visibility, p.id, 2,
                                              std::uint64_t(p.purpose), seed);
            const double v = sun_point_visibility(sun, p.position + p.normal * geo.offset,
                                                  geo.diagonal, rays_per_source, visibility,
                                                  sun_rng);
            sum += RgbD(sun.irradiance) * (cos_theta * v);
        }
    }
    return Rgb(float(sum.r), float(sum.g), float(sum.b));
}

Rgb gather_elements(const ElementGeometry& geo, const std::vector<Rgb>& exitance,
                    const VisibilityQuery& visibility, const GatherPoint& p, int rays_per_element,
                    std::uint64_t seed) {
    RgbD sum;
    Pcg32 rng = Pcg32::for_stream(p.purpose, p.id, 2, 0, seed);
    for (std::uint32_t s = 0; s < geo.size(); ++s) {
        if (exitance[s].is_black())
            continue;
        double f = facing_form_factor(geo, p, s);
        if (f <= 0)
            continue;
        f *= triangle_visibility(geo, visibility, p, s, rays_per_element, rng);
        sum += RgbD(exitance[s]) * f;
    }
    return Rgb(float(sum.r), float(sum.g), float(sum.b));
}

} // namespace penumbra::solver
