// Surfaces, offsets, emitting elements and direction sampling that the final gather's paths
// and the caustic photons share (path_geometry.h).

#include "path_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::raytrace {

namespace {

/// Offset of a ray's origin along the geometric normal, relative to the scene's diagonal.
constexpr double k_ray_offset = 1e-5;

/// Barycentric weights of \p p (in the plane) in the triangle (a, b, c), unclamped.
std::array<double, 3> triangle_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = cross(b - a, c - a);
    const double area2 = dot(n, n);
    if (!(area2 > 0))
        return {1.0, 0.0, 0.0};
    const double w1 = dot(cross(p - a, c - a), n) / area2;
    const double w2 = dot(cross(b - a, p - a), n) / area2;
    return {1.0 - w1 - w2, w1, w2};
}

/// The polygon's vertex normals interpolated at \p p: in the fan triangle (0, k, k + 1) that
/// contains it (the one it lies deepest in, against rounding). Unit; \p flat without normals.
Vec3 interpolated_normal(const Polygon& polygon, const Vec3& p, const Vec3& flat) {
    const auto& v = polygon.vertices;
    const auto& n = polygon.normals;
    if (n.size() != v.size() || v.size() < 3)
        return flat;
    double best = -std::numeric_limits<double>::infinity();
    Vec3 normal = flat;
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
        const auto w = triangle_weights(p, v[0], v[k], v[k + 1]);
        const double depth = std::min({w[0], w[1], w[2]});
        if (depth > best) {
            best = depth;
            normal = n[0] * w[0] + n[k] * w[1] + n[k + 1] * w[2];
        }
    }
    const double len = length(normal);
    return len > 0 && std::isfinite(len) ? normal / len : flat;
}

} // namespace

Vec3 cosine_hemisphere(double u1, double u2) {
    const double r = std::sqrt(u1), phi = 2.0 * k_pi * u2;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
}

Vec3 uniform_cone(double cos_max, double u1, double u2) {
    const double z = 1.0 - u1 * (1.0 - cos_max);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * k_pi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 uniform_sphere(double u1, double u2) {
    return uniform_cone(-1.0, u1, u2);
}

AreaLights::AreaLights(const RadiosityMesh& mesh) : AreaLights(mesh, std::span<const Rgb>{}) {}

AreaLights::AreaLights(const RadiosityMesh& mesh, std::span<const Rgb> exitance)
    : probability_(mesh.element_count(), 0.0) {
    double total = 0;
    for (std::uint32_t e = 0; e < mesh.element_count(); ++e) {
        const Rgb m = exitance.empty() ? mesh.patch_of(e).emission : exitance[e];
        const double power = channel_mean(m) * mesh.element_area[e];
        if (power > 0) {
            elements_.push_back(e);
            total += power;
            cdf_.push_back(total);
        }
    }
    // Backwards, so that cdf_[k − 1] is still the unnormalised sum when k reads it.
    for (std::size_t k = elements_.size(); k-- > 0;) {
        const double before = k == 0 ? 0.0 : cdf_[k - 1];
        probability_[elements_[k]] = (cdf_[k] - before) / total;
        cdf_[k] /= total;
    }
    power_ = total;
}

std::uint32_t AreaLights::pick(double u) const {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    return elements_[std::min<std::size_t>(std::size_t(it - cdf_.begin()), elements_.size() - 1)];
}

SurfaceGeometry::SurfaceGeometry(const EmbreeScene& rt, const Scene& scene)
    : mesh_(rt.mesh()), scene_(scene),
      offset_(k_ray_offset * std::max(rt.mesh().scene_diagonal, 1e-3)) {}

SurfaceHit SurfaceGeometry::surface_of(const EmbreeScene::Hit& hit, const Vec3& origin,
                                       const Vec3& dir) const {
    const auto element = std::uint32_t(hit.element >= 0 ? hit.element : hit.front_element);
    const Patch& patch = mesh_.patch_of(element);
    const Vec3 p = origin + dir * double(hit.t);
    // The polygon's normals face its front: the back side's patch turns them round.
    const Vec3 front = patch.back ? -patch.normal : patch.normal;
    // Hand-made meshes (tests) may name no polygon of the scene: shaded flat.
    Vec3 shading = patch.polygon < scene_.polygons.size()
                       ? interpolated_normal(scene_.polygons[patch.polygon], p, front)
                       : front;
    if (dot(shading, front) <= 0)
        shading = front; // a normal that turned past the plane says nothing useful
    return {p, patch.normal, element, patch.back ? -shading : shading};
}

double SurfaceGeometry::element_size(std::uint32_t element) const {
    return std::sqrt(2.0 * mesh_.element_area[element]);
}

bool receives_photons(const Material& m) {
    return !diffuse_reflectance(m).is_black();
}

bool passes_photons(const Material& m) {
    return m.lobe.has_value() && !receives_photons(m);
}

Vec3 uniform_point_on(const RadiosityMesh& mesh, std::uint32_t element, double u1, double u2) {
    if (u1 + u2 > 1) {
        u1 = 1 - u1;
        u2 = 1 - u2;
    }
    const auto& tri = mesh.triangles[element];
    const Vec3 p0 = mesh.vertex(tri[0]);
    return p0 + (mesh.vertex(tri[1]) - p0) * u1 + (mesh.vertex(tri[2]) - p0) * u2;
}

} // namespace penumbra::raytrace
