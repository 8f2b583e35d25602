// Point and spot lights: the profile over a triangle (exact range, profile-weighted solid
// angle), shooting them onto the elements and the escaping fraction of their power.

#include "sources/point_lights.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/rng.h"
#include "kernels/form_factor.h"

namespace penumbra::solver {

namespace {

constexpr int k_escape_rays_per_light = 4096;
/// A part of a triangle over which a spot's profile varies is split further while its
/// Ω × (profile range) exceeds this fraction of the light's ∫ profile dω (the bound of the
/// centroid estimate's error), down to k_profile_max_depth levels.
constexpr double k_profile_tolerance = 1e-5;
constexpr int k_profile_max_depth = 12;

// Whether the ray from p along d passes through triangle t (Möller & Trumbore 1997).
bool ray_hits_triangle(const Vec3& p, const Vec3& d, const std::array<Vec3, 3>& t) {
    const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
    const Vec3 s = cross(d, e2);
    const double det = dot(e1, s);
    if (det == 0)
        return false; // along the plane: the edges bound cos θ
    const Vec3 o = p - t[0];
    const double u = dot(o, s) / det;
    if (u < 0 || u > 1)
        return false;
    const Vec3 q = cross(o, e1);
    const double v = dot(d, q) / det;
    return v >= 0 && u + v <= 1 && dot(e2, q) / det > 0;
}

// Widens [lo, hi] by cos θ = dot(x − p, d) / |x − p| over x on [a, b]. Along a line,
// (α + βt) / √(A + 2Bt + Ct²) has one stationary point, t = (αB − βA) / (βB − αC).
void widen_by_segment(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, double& lo,
                      double& hi) {
    const Vec3 u = a - p, w = b - a;
    const double alpha = dot(u, d), beta = dot(w, d);
    const double aa = dot(u, u), bb = dot(u, w), cc = dot(w, w);
    auto widen_at = [&](double t) {
        const double q = aa + t * (2.0 * bb + cc * t);
        if (q <= 0)
            return;
        const double c = std::clamp((alpha + beta * t) / std::sqrt(q), -1.0, 1.0);
        lo = std::min(lo, c);
        hi = std::max(hi, c);
    };
    widen_at(0.0);
    widen_at(1.0);
    const double den = beta * bb - alpha * cc;
    if (den != 0) {
        const double t = (alpha * bb - beta * aa) / den;
        if (t > 0 && t < 1)
            widen_at(t);
    }
}

// A direction uniformly distributed over the cap of directions within acos(cos_max) of the
// unit \p axis.
Vec3 sample_cap(const Vec3& axis, double cos_max, double u1, double u2) {
    const double z = 1.0 - u1 * (1.0 - cos_max);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * k_pi * u2;
    return Frame::from_normal(axis).to_world(Vec3(r * std::cos(phi), r * std::sin(phi), z));
}

double visible_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                        const Vec3& light, PointSource id, std::uint32_t j,
                        const RowSettings& settings) {
    Pcg32 rng =
        Pcg32::for_stream(RngPurpose::point_light_visibility, id.index, j, 0, settings.seed);
    const int rays = std::max(1, settings.visibility_rays);
    return double(light_rays_open(light, geo.oriented(j), geo.offset, rays, visibility, rng)) /
           double(rays);
}

} // namespace

ProfileRange profile_range(const PointLight& light, const std::array<Vec3, 3>& tri) {
    if (!light.spot)
        return {};
    const Vec3& p = light.position;
    const Vec3& d = light.spot->direction;
    double lo = 1, hi = -1;
    for (int k = 0; k < 3; ++k)
        widen_by_segment(p, d, tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)], lo, hi);
    if (ray_hits_triangle(p, d, tri))
        hi = 1;
    if (ray_hits_triangle(p, -d, tri))
        lo = -1;
    return {light.profile_cos(lo), light.profile_cos(hi)};
}

double profile_solid_angle_triangle(const PointLight& light, const std::array<Vec3, 3>& tri) {
    const Vec3& p = light.position;
    if (!light.spot)
        return solid_angle_triangle(p, tri);
    const double tolerance = k_profile_tolerance * light.profile_solid_angle();
    struct Part {
        std::array<Vec3, 3> t;
        int depth;
    };
    std::vector<Part> stack{{tri, 0}};
    double sum = 0;
    while (!stack.empty()) {
        const Part part = stack.back();
        stack.pop_back();
        const ProfileRange range = profile_range(light, part.t);
        if (range.hi <= 0)
            continue; // outside the cut-off
        const double omega = solid_angle_triangle(p, part.t);
        if (!range.varies()) {
            sum += omega * range.hi;
            continue;
        }
        const auto& [a, b, c] = part.t;
        if (omega * (range.hi - range.lo) <= tolerance || part.depth == k_profile_max_depth) {
            sum += omega * light.profile(normalize((a + b + c) / 3.0 - p));
            continue;
        }
        const Vec3 ab = (a + b) * 0.5, bc = (b + c) * 0.5, ca = (c + a) * 0.5;
        for (const std::array<Vec3, 3>& child :
             {std::array<Vec3, 3>{a, ab, ca}, std::array<Vec3, 3>{ab, b, bc},
              std::array<Vec3, 3>{ca, bc, c}, std::array<Vec3, 3>{ab, bc, ca}})
            stack.push_back({child, part.depth + 1});
    }
    return sum;
}

int light_rays_open(const Vec3& light, const OrientedTriangle& target, double offset, int rays,
                    const VisibilityQuery& visibility, Pcg32& rng) {
    std::vector<Segment> segments(std::size_t(std::max(1, rays)));
    for (Segment& seg : segments) {
        Vec3 to =
            sample_triangle(target.v, rng.next_double(), rng.next_double()) + target.n * offset;
        seg = {Vec3f(light), Vec3f(to - light), 0.0f, 1.0f};
    }
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    return int(std::count(blocked.begin(), blocked.end(), std::uint8_t(0)));
}

double light_escape_fraction(const ElementGeometry& geo, const VisibilityQuery& visibility,
                             const PointLight& light, PointSource id, std::uint64_t seed) {
    Pcg32 rng = Pcg32::for_stream(RngPurpose::escape_estimate, id.index, 1, 0, seed);
    std::vector<Segment> segments(k_escape_rays_per_light);
    std::vector<double> weight(segments.size(), 1.0);
    const float reach = float(4.0 * geo.diagonal + 1.0);
    const Vec3f from(light.position);
    const double cos_cutoff = light.spot ? std::cos(light.spot->cutoff_deg * k_pi / 180.0) : -1;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const double u1 = rng.next_double(), u2 = rng.next_double();
        if (!light.spot) {
            segments[i] = {from, Vec3f(sample_sphere(u1, u2)), 0.0f, reach};
            continue;
        }
        // Uniform over the cut-off cone, weighted by the profile: the escaping share of the
        // power, not of the directions.
        const Vec3 dir = sample_cap(light.spot->direction, cos_cutoff, u1, u2);
        weight[i] = light.profile(dir);
        segments[i] = {from, Vec3f(dir), 0.0f, reach};
    }
    std::vector<std::uint8_t> blocked(segments.size());
    visibility.occluded(segments, blocked);
    double escaped = 0, total = 0;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        escaped += blocked[i] ? 0.0 : weight[i];
        total += weight[i];
    }
    return total > 0 ? escaped / total : 0.0;
}

void shoot_point_lights(ShootingState& state, const ElementGeometry& geo,
                        const std::vector<PointLight>& lights, const VisibilityQuery& visibility,
                        const RowSettings& settings, const Context& ctx) {
    for (std::uint32_t l = 0; l < lights.size(); ++l) {
        const PointLight& light = lights[l];
        const PointSource id{l};
        const Vec3 p = light.position;
        const RgbD power = light.power();
        state.emitted += power;
        state.escaped += power * light_escape_fraction(geo, visibility, light, id, settings.seed);
        std::vector<Rgb> received(geo.size());
        parallel_for_index(geo.size(), 64, [&](std::size_t j) {
            if (dot(p - geo.triangle[j][0], geo.normal[j]) <= 0)
                return; // the light is behind this side
            double omega = profile_solid_angle_triangle(light, geo.triangle[j]);
            if (omega <= 0)
                return; // outside a spot's cone
            omega *= visible_fraction(geo, visibility, p, id, std::uint32_t(j), settings);
            received[j] = light.intensity * float(omega / geo.area[j]);
        });
        // Serially: a receiver passes light on to its twin, another receiver's slot.
        for (std::size_t j = 0; j < received.size(); ++j)
            if (!received[j].is_black())
                state.receive(j, received[j], Rgb{});
        ctx.debug("point light '{}' shot", light.name);
    }
}

} // namespace penumbra::solver
