// Point gathering: E(x) = Σ_s B_s F(x → s) V(x, s) over source triangles s, plus
// I cos θ / d² V for point lights. Unoccluded values are exact (analytic F).

#include "point_gather.h"

#include <cmath>

#include "core/rng.h"
#include "form_factor.h"

namespace penumbra::solver {

namespace {

// Fraction of \p rays segments from p to random points of triangle s that are unblocked.
double triangle_visibility(const ElementGeometry& geo, const VisibilityQuery& visibility,
                           const GatherPoint& p, std::uint32_t s, int rays, Pcg32& rng) {
    std::vector<Segment> segments(std::size_t(std::max(rays, 1)));
    // As in element_rows.cpp: lift both ends off both planes where they meet at an angle.
    const double cross_weight = geo.offset * (1.0 - std::abs(dot(p.normal, geo.normal[s])));
    const Vec3 from = p.position + p.normal * geo.offset + geo.normal[s] * cross_weight;
    for (Segment& seg : segments) {
        Vec3 to = sample_triangle(geo.triangle[s], rng.next_double(), rng.next_double()) +
                  geo.normal[s] * geo.offset + p.normal * cross_weight;
        seg = {Vec3f(from), Vec3f(to - from), 0.0f, 1.0f};
    }
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    std::size_t open = 0;
    for (auto b : blocked)
        open += b ? 0 : 1;
    return double(open) / double(segments.size());
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
                  std::uint64_t seed) {
    RgbD sum;
    Pcg32 rng = Pcg32::for_stream(p.purpose, p.id, 1, 0, seed);
    for (std::uint32_t s : sources.emitters) {
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
        Vec3 from = p.position + p.normal * geo.offset;
        Segment seg{Vec3f(from), Vec3f(light.position - from), 0.0f, 1.0f - 1e-6f};
        std::uint8_t blocked = 0;
        visibility.occluded({&seg, 1}, {&blocked, 1});
        if (!blocked)
            sum += RgbD(light.intensity) * (cos_theta / dist2);
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
