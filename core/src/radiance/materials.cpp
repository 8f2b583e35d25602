// Radiance's material primitives as Penumbra materials (Radiance reference manual, "Materials").
// Radiosity transports the diffuse part. The specular part of plastic and metal (spec, and
// Ward's roughness) is checked and then left out, until the final gather's glossy lobe
// (issue #28) takes Radiance's highlights: a plastic's diffuse reflectance is its colour ×
// (1 − spec), a metal's likewise (its specular part has the metal's colour).

#include "modifiers.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace penumbra::radiance {

namespace {

Rgb colour_of(const Primitive& p, std::size_t first = 0) {
    return {float(p.reals[first]), float(p.reals[first + 1]), float(p.reals[first + 2])};
}

[[noreturn]] void fail_argument(const Primitive& p, const std::string& what) {
    fail(p.where, fmt::format("{} '{}': {}", p.type, p.id, what));
}

void expect_colour(const Primitive& p, const Rgb& c, const char* what, bool below_one) {
    for (int i = 0; i < 3; ++i)
        if (!(c[i] >= 0) || (below_one && !(c[i] < 1)))
            fail_argument(p, fmt::format("{} must be in [0, {}) per channel, got ({}, {}, {})",
                                         what, below_one ? "1" : "∞", c.r, c.g, c.b));
}

double fraction(const Primitive& p, std::size_t index, const char* what) {
    const double v = p.reals[index];
    if (!(v >= 0 && v <= 1))
        fail_argument(p, fmt::format("{} must be in [0, 1], got {}", what, v));
    return v;
}

/// plastic and metal: "red green blue spec rough".
SurfaceMaterial reflector(const Primitive& p) {
    expect_arguments(p, 0, {5}, "red green blue spec rough");
    const double spec = fraction(p, 3, "spec");
    if (!(p.reals[4] >= 0))
        fail_argument(p, fmt::format("rough must be >= 0, got {}", p.reals[4]));
    SurfaceMaterial m;
    m.material.reflectance = colour_of(p) * float(1 - spec);
    expect_colour(p, m.material.reflectance, "the diffuse reflectance colour × (1 − spec)", true);
    return m;
}

/// glass: "red green blue [index]" transmissivities at normal incidence, index 1.52.
SurfaceMaterial glass(const Primitive& p) {
    expect_arguments(p, 0, {3, 4}, "red green blue [refractive index]");
    ThinGlass pane;
    pane.transmissivity = colour_of(p);
    for (int i = 0; i < 3; ++i)
        if (!(pane.transmissivity[i] >= 0 && pane.transmissivity[i] <= 1))
            fail_argument(p, "the transmissivities must be in [0, 1]");
    if (p.reals.size() == 4)
        pane.ior = p.reals[3];
    if (!(pane.ior > 1 && pane.ior < 10))
        fail_argument(p, fmt::format("the refractive index must be in (1, 10), got {}", pane.ior));
    SurfaceMaterial m;
    m.material.reflectance = Rgb{}; // all its reflection is the pane's, specular
    m.material.lobe = pane;
    return m;
}

/// trans: "red green blue spec rough trans tspec". Of what is not reflected specularly, the
/// fraction trans passes, and of that tspec without scattering (left out like spec).
SurfaceMaterial translucent(const Primitive& p) {
    expect_arguments(p, 0, {7}, "red green blue spec rough trans tspec");
    const double spec = fraction(p, 3, "spec");
    const double trans = fraction(p, 5, "trans");
    const double tspec = fraction(p, 6, "tspec");
    const Rgb c = colour_of(p);
    expect_colour(p, c, "the colour", true);
    SurfaceMaterial m;
    m.material.reflectance = c * float((1 - spec) * (1 - trans));
    m.material.diffuse_transmittance = c * float((1 - spec) * trans * (1 - tspec));
    return m;
}

/// light, glow and illum: an emitted radiance, W/(sr·m²), from the front side; no reflection.
SurfaceMaterial emitter(const Primitive& p) {
    if (p.type == "glow")
        expect_arguments(p, 0, {4}, "red green blue maxradius");
    else if (p.type == "illum" && p.strings.size() == 1)
        expect_arguments(p, 1, {3}, "red green blue"); // its alternate material is not drawn
    else
        expect_arguments(p, 0, {3}, "red green blue");
    SurfaceMaterial m{.emitter = true};
    m.material.reflectance = Rgb{};
    m.material.emission = colour_of(p);
    expect_colour(p, m.material.emission, "the radiance", false);
    return m;
}

} // namespace

void expect_arguments(const Primitive& p, std::size_t strings,
                      std::initializer_list<std::size_t> reals, const char* names) {
    const bool reals_ok = std::find(reals.begin(), reals.end(), p.reals.size()) != reals.end();
    if (p.strings.size() != strings || !p.integers.empty() || !reals_ok)
        fail_argument(p, fmt::format("expects {} string, 0 integer and {} real arguments ({}), "
                                     "got {}, {} and {}",
                                     strings, fmt::join(reals, " or "), names, p.strings.size(),
                                     p.integers.size(), p.reals.size()));
}

std::optional<SurfaceMaterial> material_from(const Primitive& p) {
    std::optional<SurfaceMaterial> m;
    if (p.type == "plastic" || p.type == "metal")
        m = reflector(p);
    else if (p.type == "glass")
        m = glass(p);
    else if (p.type == "trans")
        m = translucent(p);
    else if (p.type == "light" || p.type == "glow" || p.type == "illum")
        m = emitter(p);
    if (m)
        m->material.name = p.id;
    return m;
}

} // namespace penumbra::radiance
