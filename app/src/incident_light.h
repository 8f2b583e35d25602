#pragma once
// Light arriving at a point from every direction, read from a radiosity solution (issue #29:
// light probes and directional lightmaps): rays that hit a surface see its radiance B/π,
// rays that leave the scene see the sky; point lights, spots and the sun arrive as deltas
// from their exact directions, shadowed by rays. docs/lightmaps.md describes the use.

#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "core/rgb.h"
#include "core/rng.h"
#include "core/scene.h"
#include "core/vec.h"
#include "raytrace/raytrace.h"
#include "solver/solver.h"

namespace penumbra::app {

/// \brief Light from a delta source: it arrives from the unit direction \p dir (from the point
///        toward the source) with \p irradiance on a surface facing it, W/m² per channel.
struct DeltaLight {
    Vec3 dir;
    RgbD irradiance;
};

/// \brief What one ray sees, split into what surfaces reflect and what they emit.
struct RayLight {
    RgbD reflected;            ///< (B − E)/π of the surface hit, or the sky's radiance
    RgbD emitted;              ///< E/π of the surface hit
    std::int32_t element = -1; ///< the element hit (its front side), -1 for none
    double distance = 0;       ///< to the hit, metres
};

/// \brief Incident radiance from a solution. Thread-safe; keeps references to its arguments.
class IncidentLight {
public:
    /// \p rt traces the mesh \p solution lives on, a mesh of \p scene. \p direct leaves out
    ///        the emitted and delta light and the sky of the sources it excludes (their
    ///        reflected light stays: mixed lighting, issue #29).
    IncidentLight(const Scene& scene, const raytrace::EmbreeScene& rt, const Solution& solution,
                  solver::DirectLightOptions direct = {});

    /// \brief Radiance (W/(sr·m²)) arriving at \p origin from the unit direction \p dir,
    ///        trace()'s reflected + emitted.
    RgbD radiance(const Vec3& origin, const Vec3& dir) const;

    /// \brief The light arriving at \p origin from the unit direction \p dir: the front side
    ///        of the first surface along it, (B − E)/π interpolated from its vertices and its
    ///        own E/π; nothing from the back of a one-sided surface; the sky (Scene::sky, else
    ///        nothing) where the ray leaves. Panes of glazing on the way attenuate both by
    ///        their transmittance.
    RayLight trace(const Vec3& origin, const Vec3& dir) const;

    /// \brief Fraction of light passing from \p from along unit \p dir over \p reach metres:
    ///        0 behind an opaque surface, the panes' transmittance through glazing.
    float transmittance(const Vec3& from, const Vec3& dir, float reach) const;

    /// \brief The point lights, spots and the sun as seen from \p origin, each with its
    ///        shadow ray's transmittance applied (lights fully blocked are left out).
    std::vector<DeltaLight> deltas(const Vec3& origin) const;

    /// \brief The ray offset of the mesh: 10⁻⁵ of the scene's diagonal (the renderer's).
    double ray_offset() const { return offset_; }

private:
    const Scene& scene_;
    const raytrace::EmbreeScene& rt_;
    const Solution& solution_;
    bool has_glazing_ = false;
    double offset_ = 0;
    solver::DirectLightOptions direct_;
    /// Whether \p source's direct light is seen (direct_ includes it).
    bool sees(const LightSource& source) const {
        return !direct_.include || direct_.include(source);
    }
};

/// \brief Stratified random directions in a local frame (z up): \p n_z equal bands of z
///        (over [−1, 1], or [0, 1] for a \p hemisphere) times 2 n_z equal sectors of azimuth,
///        one jittered direction in each of these equal-area cells, drawn from \p rng. Each
///        direction stands for the same solid angle, 4π (2π) / (2 n_z²).
std::vector<Vec3> stratified_directions(int n_z, bool hemisphere, Pcg32& rng);

} // namespace penumbra::app
