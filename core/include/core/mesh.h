#pragma once
// The radiosity mesh and its solution as plain arrays (SoA), the data that flows from the
// mesher to the solver, the ray tracer and the viewer.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/light.h"
#include "core/material.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace penumbra {

/// \brief One side of one planar surface. Two-sided surfaces give two patches with their own
///        vertices, so values are never interpolated across a side, a crease or a contact.
struct Patch {
    std::uint32_t polygon = 0;  ///< index of the input polygon in Scene::polygons
    std::uint32_t surface = 0;  ///< planar surface id (a non-planar polygon gives several)
    std::uint32_t material = 0; ///< index into Scene::materials
    bool back = false;          ///< the back side of a two-sided surface
    Vec3 normal;                ///< unit normal of this side
    Rgb reflectance;            ///< the material's diffuse reflectance (radiosity_response)
    /// The material's diffuse transmittance τ: this side's radiosity gains τ times the
    /// irradiance of its twin (the other side).
    Rgb diffuse_transmittance;
    Rgb emission; ///< emitted radiosity πL of this side, W/m²
    /// The material is specular only (RadiosityResponse::specular_only).
    bool specular_only = false;
    /// The pane's optics when the surface is glazing (a ThinGlass material), which rays cross
    /// with its transmittance T(θ); none for every other surface.
    std::optional<ThinGlass> glazing;

    /// Blocks all light: every surface but glazing. Occluder certificates, the mesher's hidden
    /// regions and visibility count only opaque surfaces.
    bool opaque() const { return !glazing; }
};

/// \brief A discontinuity in the illumination (a shadow boundary) that the mesher inserted
///        as element edges (issue #5). order: 0 = D0 (value), 1 = D1 (gradient), 2 = D2.
struct DiscontinuitySegment {
    Vec3 a, b;                        ///< endpoints, metres
    std::uint32_t surface = 0;        ///< the receiving planar surface
    LightSource source = SunSource{}; ///< the light whose shadow boundary it is
    int order = 0;
};

/// \brief One planar surface as the mesher saw it: a planar input polygon, or one fan
///        triangle of a non-planar one. Hidden parts (under or inside other geometry, or
///        covered by a coincident surface) get no elements; their area is kept here.
struct SurfaceInfo {
    std::uint32_t polygon = 0;  ///< index into Scene::polygons
    double area_m2 = 0;         ///< area of the surface (one side)
    double hidden_front_m2 = 0; ///< area of the front side left without elements
    double hidden_back_m2 = 0;  ///< same for the back side (0 for one-sided materials)
};

/// \brief Conforming triangle mesh of all patches. An element is one triangle of one patch,
///        wound counter-clockwise when seen from the side it belongs to.
struct RadiosityMesh {
    std::vector<Vec3f> positions;                        ///< per vertex, metres
    std::vector<std::uint32_t> vertex_patch;             ///< per vertex
    std::vector<std::array<std::uint32_t, 3>> triangles; ///< per element
    std::vector<std::uint32_t> element_patch;            ///< per element
    std::vector<std::int32_t> element_twin;              ///< the other side's element or -1
    std::vector<double> element_area;                    ///< per element, m²
    std::vector<std::int32_t> element_level;             ///< hierarchy level, 0 = mesh triangle
    std::vector<Patch> patches;
    /// Elements that carry geometry for ray tracing (front or one-sided), in primitive order.
    std::vector<std::uint32_t> geometry_elements;
    double scene_diagonal = 0; ///< metres
    /// Shadow boundaries inserted as element edges (empty without discontinuity meshing).
    std::vector<DiscontinuitySegment> discontinuities;
    /// Per planar surface id (Patch::surface).
    std::vector<SurfaceInfo> surfaces;

    std::size_t element_count() const { return triangles.size(); }
    std::size_t vertex_count() const { return positions.size(); }
    Vec3 vertex(std::uint32_t v) const { return Vec3(positions[v]); }
    Vec3 centroid(std::uint32_t e) const;
    const Patch& patch_of(std::uint32_t e) const { return patches[element_patch[e]]; }
};

/// \brief Per-element (cell) and per-vertex (point) results of a solve, W/m² per channel.
struct Solution {
    std::vector<Rgb> radiosity;           ///< per element B = E + ρ H
    std::vector<Rgb> irradiance_direct;   ///< per element, area mean from sources
    std::vector<Rgb> irradiance_indirect; ///< per element, area mean from reflected light
    std::vector<Rgb> vertex_radiosity;
    std::vector<Rgb> vertex_irradiance_direct;
    std::vector<Rgb> vertex_irradiance_indirect;
};

/// \brief Light that reaches diffuse elements through surfaces without a diffuse part (mirror,
///        glass, metal: issue #28), for the radiosity solver, on the elements of the mesh it
///        was traced on.
struct SpecularLight {
    /// \brief A share of the light element \p from reflects that reaches element \p to
    ///        through specular surfaces alone: \p from's reflected exitance M (W/m²) delivers
    ///        M × \p area_m2 watts to \p to (per channel).
    struct Transfer {
        std::uint32_t from = 0, to = 0;
        Rgb area_m2;
    };
    /// Per element (or empty), W/m²: the sources' light (L S+ D), a fixed source.
    std::vector<Rgb> irradiance;
    /// Diffuse to diffuse (D S+ D), linear in the solution's exitance, so that the solve
    /// carries it through any number of such passes.
    std::vector<Transfer> transfers;
    /// Traces the transfers for a guess of the reflected exitance per element (W/m²), the
    /// importance of their photons' sources, when \p transfers is empty: the solver calls it
    /// once its first cycle has that guess, so that one solve refines for them too.
    std::function<std::vector<Transfer>(std::span<const Rgb> exitance)> trace_transfers;

    bool empty() const { return irradiance.empty() && transfers.empty() && !trace_transfers; }
};

/// \brief Irradiance at a sensor point, computed at the point itself.
struct SensorReading {
    Rgb irradiance_direct; ///< W/m²
    Rgb irradiance_total;  ///< W/m²
    double illuminance_direct_lx = 0;
    double illuminance_total_lx = 0;
};

/// \brief Linear interpolation of per-vertex \p values at \p point on the patch side whose
///        normal agrees with \p normal (within 1e-3) and whose plane passes within \p tolerance
///        metres. Returns nothing if no element contains the point.
std::optional<Rgb> interpolate_at(const RadiosityMesh& mesh, const std::vector<Rgb>& values,
                                  const Vec3& point, const Vec3& normal, double tolerance);

} // namespace penumbra
