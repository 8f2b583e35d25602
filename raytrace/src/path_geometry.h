#pragma once
// What camera paths (final_gather.cpp) and caustic photons (caustic_photons.cpp) share: the
// surface a ray meets with its shading normal, ray offsets, the emitting elements, direction
// sampling, and which materials pass photons on and which receive them. Internal to raytrace/.

#include "raytrace/raytrace.h"

#include "core/material.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/vec.h"

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace penumbra::raytrace {

inline constexpr float k_infinity = std::numeric_limits<float>::infinity();

/// Cosine-distributed unit vector about +z of (u1, u2) ∈ [0, 1)².
Vec3 cosine_hemisphere(double u1, double u2);
/// Uniform unit vector in the cone about +z of half-angle acos(cos_max).
Vec3 uniform_cone(double cos_max, double u1, double u2);
/// Uniform unit vector on the sphere.
Vec3 uniform_sphere(double u1, double u2);

/// \brief A uniformly distributed point on triangle \p element of \p mesh from two uniform
///        numbers (folded into the triangle).
Vec3 uniform_point_on(const RadiosityMesh& mesh, std::uint32_t element, double u1, double u2);

inline float channel_mean(const Rgb& c) {
    return (c.r + c.g + c.b) / 3.0f;
}

/// The emitting elements, chosen in proportion to their emitted power.
class AreaLights {
public:
    explicit AreaLights(const RadiosityMesh& mesh);
    /// The elements as sources of exitance \p exitance (one per element, W/m²) instead of
    /// their emission.
    AreaLights(const RadiosityMesh& mesh, std::span<const Rgb> exitance);

    bool empty() const { return elements_.empty(); }
    /// The element of \p u ∈ [0, 1).
    std::uint32_t pick(double u) const;
    /// The probability that pick() returns \p element.
    double probability(std::uint32_t element) const { return probability_[element]; }
    /// Σ mean(M) A over the emitting elements, W (channel mean).
    double power() const { return power_; }

private:
    std::vector<std::uint32_t> elements_;
    std::vector<double> cdf_;
    std::vector<double> probability_;
    double power_ = 0;
};

/// Where a ray met a surface, and the side whose material and normal scatter it.
struct SurfaceHit {
    Vec3 p;
    Vec3 normal;           ///< geometric normal of \p element's side
    std::uint32_t element; ///< the side facing the ray, or the front of a one-sided surface
    Vec3 shading;          ///< the interpolated vertex normal on that side, else \p normal
};

/// The scene's surfaces as paths meet them.
class SurfaceGeometry {
public:
    SurfaceGeometry(const EmbreeScene& rt, const Scene& scene);

    const Material& material_of(std::uint32_t element) const {
        return scene_.materials[mesh_.patch_of(element).material];
    }
    /// The surface of \p hit along the ray (origin, unit dir).
    SurfaceHit surface_of(const EmbreeScene::Hit& hit, const Vec3& origin, const Vec3& dir) const;
    /// A ray origin off the surface, on the side \p w leaves to.
    Vec3 offset(const SurfaceHit& s, const Vec3& w) const {
        return s.p + s.normal * (dot(w, s.normal) >= 0 ? offset_ : -offset_);
    }
    /// The distance offset() moves an origin.
    double offset_distance() const { return offset_; }
    /// Edge of a right isosceles triangle of the element's area: the mesh's local size.
    double element_size(std::uint32_t element) const;

    static Vec3 facing(const Vec3& normal, const Vec3& w) {
        return dot(normal, w) >= 0 ? normal : -normal;
    }
    /// Whether wi leaves on the side of the geometric normal a scattering of \p wo from this
    /// lobe must: reflection on wo's side, transmission on the other (shading normals can
    /// send light through the surface otherwise).
    static bool geometric_side_agrees(const SurfaceHit& s, const Vec3& wo, const Vec3& wi,
                                      bool transmission) {
        const bool same = dot(wo, s.normal) * dot(wi, s.normal) > 0;
        return same != transmission;
    }

private:
    const RadiosityMesh& mesh_;
    const Scene& scene_;
    double offset_ = 0;
};

/// A surface that caustic photons land on: its diffuse part is not black (Lambertian, plastic).
bool receives_photons(const Material& m);
/// A surface that passes photons on: a lobe (mirror, glass, glossy) and no diffuse part.
bool passes_photons(const Material& m);

} // namespace penumbra::raytrace
