// Bsdf: the material's lobes (bsdf_glossy.cpp, bsdf_specular.cpp) in the shading frame, with
// the side conventions of core/bsdf.h.

#include "core/bsdf.h"

#include <cmath>
#include <type_traits>

#include "bsdf_lobes.h"

namespace penumbra {

namespace {

/// Lobes that reflect only, on the side the light comes from.
template <class L>
constexpr bool k_opaque = !std::is_same_v<L, DielectricLobe> && !std::is_same_v<L, ThinGlassLobe>;

template <class L>
constexpr bool k_delta = !std::is_same_v<L, LambertLobe> && !std::is_same_v<L, GgxLobe> &&
                         !std::is_same_v<L, PlasticLobe>;

/// A coat's Fresnel factor a + b (1 − cos)⁵: none (a = s), Schlick (F0 = s) and the
/// dielectric's as Schlick's fit of it (F0 = s ((n − 1)/(n + 1))²).
LinearFresnel coat_fresnel(const GgxGlossy& g) {
    const Rgb s = g.specular;
    if (std::holds_alternative<FresnelNone>(g.fresnel))
        return {s, Rgb{}};
    double f0 = 1.0;
    if (const auto* d = std::get_if<FresnelDielectric>(&g.fresnel))
        f0 = (d->ior - 1) * (d->ior - 1) / ((d->ior + 1) * (d->ior + 1));
    return {s * float(f0), s * float(1.0 - f0)};
}

Bsdf::Lobes glossy_lobes(const GgxGlossy& g, const Rgb& diffuse) {
    const GgxDistribution distribution{g.alpha};
    if (g.diffuse_base)
        return PlasticLobe{GgxLobe{distribution, coat_fresnel(g)}, diffuse};
    if (const auto* d = std::get_if<FresnelDielectric>(&g.fresnel))
        return GgxLobe{distribution, ScaledDielectricFresnel{g.specular, d->ior}};
    return GgxLobe{distribution, coat_fresnel(g)};
}

/// Whether an opaque lobe reflects light toward \p wo: not grazing, not the back of a
/// one-sided material.
bool reflects_toward(const Vec3& wo, bool two_sided) {
    return wo.z > 0 || (wo.z < 0 && two_sided);
}

/// wo and wi on the front for an opaque lobe: the back side of a two-sided material is turned
/// onto the front; false when nothing reflects (see reflects_toward, or wi behind).
bool orient_opaque(Vec3& wo, Vec3& wi, bool two_sided) {
    if (!reflects_toward(wo, two_sided))
        return false;
    if (wo.z < 0) {
        wo.z = -wo.z;
        wi.z = -wi.z;
    }
    return wi.z > 0;
}

} // namespace

Bsdf::Lobes bsdf_lobes(const Material& material) {
    if (!material.lobe)
        return LambertLobe{material.reflectance};
    return std::visit(
        [&](const auto& lobe) -> Bsdf::Lobes {
            using L = std::decay_t<decltype(lobe)>;
            if constexpr (std::is_same_v<L, GgxGlossy>)
                return glossy_lobes(lobe, material.reflectance);
            else if constexpr (std::is_same_v<L, Mirror>)
                return MirrorLobe{lobe.colour};
            else if constexpr (std::is_same_v<L, Dielectric>)
                return DielectricLobe{lobe.ior, lobe.transmittance};
            else
                return ThinGlassLobe{lobe};
        },
        *material.lobe);
}

Bsdf::Bsdf(const Material& material, const Vec3& shading_normal, TransportMode mode)
    : frame_(Frame::from_normal(shading_normal)), lobes_(bsdf_lobes(material)),
      two_sided_(material.two_sided), mode_(mode) {}

bool Bsdf::is_delta() const {
    return std::visit([](const auto& lobe) { return k_delta<std::decay_t<decltype(lobe)>>; },
                      lobes_);
}

Rgb Bsdf::eval(const Vec3& wo_world, const Vec3& wi_world) const {
    return std::visit(
        [&](const auto& lobe) -> Rgb {
            using L = std::decay_t<decltype(lobe)>;
            if constexpr (k_delta<L>)
                return {};
            else {
                Vec3 wo = frame_.to_local(wo_world), wi = frame_.to_local(wi_world);
                return orient_opaque(wo, wi, two_sided_) ? eval_local(lobe, wo, wi) : Rgb{};
            }
        },
        lobes_);
}

Rgb Bsdf::f(const Vec3& wo, const Vec3& wi) const {
    const double cos_i = std::abs(dot(wi, frame_.n));
    return cos_i > 0 ? eval(wo, wi) / float(cos_i) : Rgb{};
}

double Bsdf::pdf(const Vec3& wo_world, const Vec3& wi_world) const {
    return std::visit(
        [&](const auto& lobe) -> double {
            using L = std::decay_t<decltype(lobe)>;
            if constexpr (k_delta<L>)
                return 0.0;
            else {
                Vec3 wo = frame_.to_local(wo_world), wi = frame_.to_local(wi_world);
                return orient_opaque(wo, wi, two_sided_) ? pdf_local(lobe, wo, wi) : 0.0;
            }
        },
        lobes_);
}

std::optional<BsdfSample> Bsdf::sample(const Vec3& wo_world, double u_lobe, const Vec2& u) const {
    return std::visit(
        [&](const auto& lobe) -> std::optional<BsdfSample> {
            using L = std::decay_t<decltype(lobe)>;
            Vec3 wo = frame_.to_local(wo_world);
            const bool back = wo.z < 0;
            if constexpr (k_opaque<L>) {
                if (!reflects_toward(wo, two_sided_))
                    return std::nullopt;
                wo.z = std::abs(wo.z);
            }
            std::optional<BsdfSample> s = sample_local(lobe, wo, u_lobe, u, mode_);
            if (!s)
                return std::nullopt;
            if (k_opaque<L> && back)
                s->wi.z = -s->wi.z;
            s->wi = frame_.to_world(s->wi);
            return s;
        },
        lobes_);
}

} // namespace penumbra
