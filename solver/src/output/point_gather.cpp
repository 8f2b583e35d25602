// Point gathering: E(x) = Σ_s B_s F(x → s) V(x, s) over source triangles s, plus
// I profile cos θ / d² V for point lights and E_n cos θ V for the sun. Unoccluded values are
// exact (analytic F).

#include "output/point_gather.h"

#include <cmath>
#include <span>
#include <vector>

#include "core/rng.h"
#include "kernels/form_factor.h"
#include "sources/sky_light.h"
#include "sources/sun_light.h"

namespace penumbra::solver {

namespace {

// Where the rays from p toward triangle s start, and the lift their targets on s take: as in
// kernels/element_rows.cpp, both ends are lifted off both planes where they meet at an angle.
struct TriangleRays {
    Vec3 from, lift;
};
TriangleRays rays_toward(const ElementGeometry& geo, const GatherPoint& p, std::uint32_t s) {
    const double cross_weight = geo.offset * (1.0 - std::abs(dot(p.normal, geo.normal[s])));
    return {p.position + p.normal * geo.offset + geo.normal[s] * cross_weight,
            geo.normal[s] * geo.offset + p.normal * cross_weight};
}

// Visible fractions of triangles \p sources from p, into \p out. Four probe rays each (the
// centroid, and the corners pulled 2 % of the way to it), all traced at once, decide where
// they agree, as the hierarchical links' probes do; where they disagree, the triangle is in
// p's penumbra and 4 × \p rays rays on a jittered grid (stratified through the
// area-preserving square-to-triangle map) estimate it, triangle by triangle in order.
void triangle_visibilities(const ElementGeometry& geo, const VisibilityQuery& visibility,
                           const GatherPoint& p, std::span<const std::uint32_t> sources, int rays,
                           Pcg32& rng, std::vector<double>& out) {
    thread_local std::vector<Segment> segments;
    thread_local std::vector<std::uint8_t> blocked;
    segments.clear();
    for (const std::uint32_t s : sources) {
        const TriangleRays r = rays_toward(geo, p, s);
        const auto& t = geo.triangle[s];
        const Vec3 c = (t[0] + t[1] + t[2]) / 3.0;
        for (const Vec3& target :
             {c, t[0] * 0.98 + c * 0.02, t[1] * 0.98 + c * 0.02, t[2] * 0.98 + c * 0.02})
            segments.push_back({Vec3f(r.from), Vec3f(target + r.lift - r.from), 0.0f, 1.0f});
    }
    blocked.resize(segments.size());
    visibility.occluded(segments, blocked);
    out.resize(sources.size());
    for (std::size_t i = 0; i < sources.size(); ++i) {
        int open = 0;
        for (std::size_t k = 4 * i; k < 4 * i + 4; ++k)
            open += blocked[k] ? 0 : 1;
        out[i] = double(open) / 4.0;
    }
    const int side = int(std::ceil(std::sqrt(double(4 * std::max(rays, 1)))));
    for (std::size_t i = 0; i < sources.size(); ++i) {
        if (out[i] == 0.0 || out[i] == 1.0)
            continue;
        const std::uint32_t s = sources[i];
        const TriangleRays r = rays_toward(geo, p, s);
        const auto& t = geo.triangle[s];
        segments.clear();
        for (int a = 0; a < side; ++a)
            for (int b = 0; b < side; ++b) {
                const Vec3 target = sample_triangle(t, (a + rng.next_double()) / side,
                                                    (b + rng.next_double()) / side);
                segments.push_back({Vec3f(r.from), Vec3f(target + r.lift - r.from), 0.0f, 1.0f});
            }
        blocked.resize(segments.size());
        visibility.occluded(segments, blocked);
        std::size_t open = 0;
        for (auto b : blocked)
            open += b ? 0 : 1;
        out[i] = double(open) / double(segments.size());
    }
}

// Form factor from p to element s if s faces p, else 0.
double facing_form_factor(const ElementGeometry& geo, const GatherPoint& p, std::uint32_t s) {
    if (dot(p.position - geo.triangle[s][0], geo.normal[s]) <= geo.offset * 1e-3)
        return 0;
    return form_factor_point_triangle(p.position, p.normal, geo.triangle[s]);
}

// Σ radiosity[s] F(p → s) V(p, s) over the triangles s that \p each_candidate(fn) calls fn
// with: the facing ones' form factors, then their visibilities all at once.
template <typename Candidates>
RgbD gather_triangles(const ElementGeometry& geo, const VisibilityQuery& visibility,
                      const GatherPoint& p, const std::vector<Rgb>& radiosity, int rays, Pcg32& rng,
                      Candidates&& each_candidate) {
    thread_local std::vector<std::uint32_t> facing;
    thread_local std::vector<double> f, visible;
    facing.clear();
    f.clear();
    each_candidate([&](std::uint32_t s) {
        const double fs = facing_form_factor(geo, p, s);
        if (fs <= 0)
            return;
        facing.push_back(s);
        f.push_back(fs);
    });
    triangle_visibilities(geo, visibility, p, facing, rays, rng, visible);
    RgbD sum;
    for (std::size_t i = 0; i < facing.size(); ++i)
        sum += RgbD(radiosity[facing[i]]) * (f[i] * visible[i]);
    return sum;
}

} // namespace

Rgb gather_direct(const ElementGeometry& geo, const GatherSources& sources,
                  const VisibilityQuery& visibility, const GatherPoint& p, int rays_per_source,
                  std::uint64_t seed, const std::vector<std::uint32_t>* emitters) {
    Pcg32 rng = Pcg32::for_stream(p.purpose, p.id, 1, 0, seed);
    RgbD sum = gather_triangles(geo, visibility, p, sources.emission, rays_per_source, rng,
                                [&](auto&& fn) {
                                    for (std::uint32_t s : emitters ? *emitters : sources.emitters)
                                        fn(s);
                                });
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
            const double v =
                sun_point_visibility(sun, p.position + p.normal * geo.offset, geo.diagonal,
                                     rays_per_source, visibility, sun_rng);
            sum += RgbD(sun.irradiance) * (cos_theta * v);
        }
    }
    if (sources.sky) {
        Pcg32 sky_rng =
            Pcg32::for_stream(RngPurpose::sky_visibility, p.id, 3, std::uint64_t(p.purpose), seed);
        sum += sky_point_irradiance(
            *sources.sky, p.position + p.normal * geo.offset, p.normal, geo.diagonal, visibility,
            p.purpose == RngPurpose::sensor_visibility ? k_sky_point_quadrature
                                                       : k_sky_vertex_quadrature,
            sky_rng);
    }
    return Rgb(float(sum.r), float(sum.g), float(sum.b));
}

std::vector<ElementWeight> element_weights(const ElementGeometry& geo,
                                           const std::vector<std::uint8_t>& candidate,
                                           const VisibilityQuery& visibility, const GatherPoint& p,
                                           int rays_per_element, std::uint64_t seed) {
    Pcg32 rng = Pcg32::for_stream(p.purpose, p.id, 2, 0, seed);
    std::vector<std::uint32_t> facing;
    std::vector<double> f, visible;
    for (std::uint32_t s = 0; s < geo.size(); ++s) {
        if (!candidate[s])
            continue;
        const double fs = facing_form_factor(geo, p, s);
        if (fs <= 0)
            continue;
        facing.push_back(s);
        f.push_back(fs);
    }
    triangle_visibilities(geo, visibility, p, facing, rays_per_element, rng, visible);
    std::vector<ElementWeight> out;
    for (std::size_t i = 0; i < facing.size(); ++i)
        if (f[i] * visible[i] > 0)
            out.push_back({facing[i], f[i] * visible[i]});
    return out;
}

Rgb gather_elements(const ElementGeometry& geo, const std::vector<Rgb>& exitance,
                    const VisibilityQuery& visibility, const GatherPoint& p, int rays_per_element,
                    std::uint64_t seed) {
    Pcg32 rng = Pcg32::for_stream(p.purpose, p.id, 2, 0, seed);
    const RgbD sum =
        gather_triangles(geo, visibility, p, exitance, rays_per_element, rng, [&](auto&& fn) {
            for (std::uint32_t s = 0; s < geo.size(); ++s)
                if (!exitance[s].is_black())
                    fn(s);
        });
    return Rgb(float(sum.r), float(sum.g), float(sum.b));
}

} // namespace penumbra::solver
