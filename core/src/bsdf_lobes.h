#pragma once
// Private to penumbra_core: each lobe of core/bsdf.h in its local frame (z = the normal).
// Opaque lobes (Lambert, GGX, plastic, mirror) see wo above the surface (wo.z > 0): Bsdf
// turns the back side of a two-sided material onto the front. The dielectric and thin glass
// take wo on either side.

#include <optional>

#include "core/bsdf.h"

namespace penumbra {

Rgb eval_local(const LambertLobe& lobe, const Vec3& wo, const Vec3& wi);
double pdf_local(const LambertLobe& lobe, const Vec3& wo, const Vec3& wi);
std::optional<BsdfSample> sample_local(const LambertLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2& u, TransportMode mode);

Rgb eval_local(const GgxLobe& lobe, const Vec3& wo, const Vec3& wi);
double pdf_local(const GgxLobe& lobe, const Vec3& wo, const Vec3& wi);
std::optional<BsdfSample> sample_local(const GgxLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2& u, TransportMode mode);

Rgb eval_local(const PlasticLobe& lobe, const Vec3& wo, const Vec3& wi);
double pdf_local(const PlasticLobe& lobe, const Vec3& wo, const Vec3& wi);
std::optional<BsdfSample> sample_local(const PlasticLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2& u, TransportMode mode);

/// The probability with which a plastic samples its coat from \p wo: the coat's share of the
/// albedo, E / (E + ρ (1 − E)) averaged over the channels.
double plastic_coat_probability(const PlasticLobe& lobe, const Vec3& wo);

std::optional<BsdfSample> sample_local(const MirrorLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2& u, TransportMode mode);
std::optional<BsdfSample> sample_local(const DielectricLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2& u, TransportMode mode);
std::optional<BsdfSample> sample_local(const ThinGlassLobe& lobe, const Vec3& wo, double u_lobe,
                                       const Vec2& u, TransportMode mode);

} // namespace penumbra
