#pragma once
// Embree 3 scene of the radiosity mesh: batched visibility for the solver and a camera
// renderer that reads the radiosity solution.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/context.h"
#include "core/enum_names.h"
#include "core/image.h"
#include "core/mesh.h"
#include "core/scene.h"
#include "core/visibility.h"

struct RTCIntersectContext; // Embree's, kept out of this header

namespace penumbra::raytrace {

/// \brief Embree device + scene (RTC_SCENE_FLAG_ROBUST) over the geometry elements of a mesh.
///        Thread-safe for queries. The mesh must outlive this object.
class EmbreeScene final : public VisibilityQuery {
public:
    explicit EmbreeScene(const RadiosityMesh& mesh);
    ~EmbreeScene() override;
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    /// Opaque elements block every query; panes of glazing (Patch::glazing) only
    /// transmittance(), which multiplies each pane's T(θ) (the mean of its channels) once per
    /// pane surface crossed. occluded(), first_hit() and intersect() see through panes (the
    /// camera sees the room behind a window, the final gather's paths taking the panes'
    /// transmittance; light between two surfaces through a pane passes unattenuated until the
    /// solver's links carry transmittance, issue #30).
    void occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const override;
    /// Names the front element of a two-sided surface.
    void first_hit(std::span<const Segment> segments, std::span<std::int32_t> hit) const override;
    void transmittance(std::span<const Segment> segments, std::span<float> out) const override;
    std::uint64_t rays_traced() const override;

    struct Hit {
        std::int32_t element = -1; ///< element hit on the side facing the ray; -1 if none
        float t = 0, u = 0, v = 0; ///< distance and barycentrics of vertices 1 and 2
        bool back_of_one_sided = false;
        /// The front (or one-sided) element of the surface hit, on either side: the renderer
        /// follows rays inside solid glass, which meet the backs of one-sided elements.
        std::int32_t front_element = -1;
    };
    /// Closest hit along the ray (origin, direction) within (tnear, tfar).
    Hit intersect(const Vec3f& origin, const Vec3f& direction, float tnear, float tfar) const;

    const RadiosityMesh& mesh() const { return mesh_; }

private:
    /// The batched traversal occluded() and first_hit() share (embree_scene.cpp).
    template <typename Ray, typename Trace, typename Read, typename Prepare>
    void trace_batches(const char* what, const char* call, std::span<const Segment> segments,
                       std::size_t results, RTCIntersectContext* context, Trace&& trace,
                       Read&& read, Prepare&& prepare) const;

    struct Impl;
    std::unique_ptr<Impl> impl_;
    const RadiosityMesh& mesh_;
};

/// \brief The transmittance of one segment. Without \p glazing (the caller knows the scene has
///        no pane) occluded() alone, 1 or 0: the batched transmittance() of a VisibilityQuery
///        allocates per call.
float segment_transmittance(const EmbreeScene& rt, const Segment& segment, bool glazing);

/// \brief Renders the camera view of the radiosity solution: radiance B/π interpolated from
///        vertex radiosity, stratified anti-aliasing with content-named random streams.
///        Returns linear radiance, W/(sr·m²).
Image render_solution(const EmbreeScene& scene, const Solution& solution, const Camera& camera,
                      const Context& ctx);

/// \brief The radiance (W/(sr·m²)) a camera ray carries back from what it hit (element < 0:
///        nothing). Called from several threads at once.
using HitShader = std::function<Rgb(const EmbreeScene::Hit& hit)>;

/// \brief Renders the camera view with the radiance \p shade gives each primary hit: the
///        pinhole, stratified samples and box filter of render_solution(). Bitwise identical
///        for any thread count. Returns linear radiance, W/(sr·m²).
Image render_hits(const EmbreeScene& scene, const Camera& camera, const HitShader& shade,
                  const Context& ctx);

/// \brief Where render_hits() samples a pixel again, more finely: at an edge of high contrast
///        (a lamp's rim), whose placement the camera's few samples get wrong by a step of
///        1 / samples of the contrast.
struct EdgeRefinement {
    /// A pixel whose first samples differ by R (largest channel range, W/(sr·m²)) is sampled
    /// again with about R / tolerance multi-jittered samples (their mean replaces the first
    /// samples' when they are more): the placement error of an edge near an axis is then
    /// about tolerance / 2. 0: no refinement.
    double tolerance = 0;
    int max_samples_per_axis = 64; ///< caps the refined samples at this squared
};

/// \brief render_hits() with the pixels at high-contrast edges sampled again as \p refine
///        says, with multi-jittered samples (Chiu, Shirley and Wang 1994) from a stream named
///        by the pixel. Bitwise identical for any thread count.
Image render_hits(const EmbreeScene& scene, const Camera& camera, const HitShader& shade,
                  const EdgeRefinement& refine, const Context& ctx);

/// \brief How `penumbra render` finds the light a diffuse surface reflects (issue #28).
enum class GatherMode {
    final_gather, ///< paths read the radiosity solution one diffuse bounce away (final gather)
    none,         ///< a pure path tracer: the solution is not read
    radiosity,    ///< the solution itself, interpolated at the camera's hits (render_solution)
};

/// \brief Settings of render_final_gather().
struct RenderOptions {
    int spp = 16; ///< samples per pixel, stratified (rounded up to a square number), >= 1
    GatherMode gather = GatherMode::final_gather;
    /// Diffuse bounces traced before the solution is read (final mode): 0 = at the first
    /// diffuse hit's gather rays.
    int gather_depth = 0;
    /// Set (final mode): indirect light at the first Lambertian hit of each camera path comes
    /// from Ward's irradiance cache where a record is valid (docs/rendering.md).
    std::optional<IrradianceCacheSettings> irradiance_cache;
};

/// \brief A caustic photon, stored where it first landed on a surface with a diffuse part after
///        one or more bounces off surfaces without one (mirror, glass, metal).
struct CausticPhoton {
    Vec3 position; ///< on the surface, metres
    Vec3 incoming; ///< unit, from the surface toward where the photon came from
    Vec3 normal;   ///< geometric normal of the side it landed on
    Rgb power_w;   ///< the flux it carries, W per channel (already divided by the photons shot)
    std::uint32_t element = 0; ///< the mesh element it landed on (the side it faces)
};

/// \brief The caustic photon map's photons and its density estimate's radius.
struct CausticPhotons {
    std::vector<CausticPhoton> photons;
    std::uint64_t shot = 0; ///< photons emitted to store them
    /// Radius of the density estimate's disc: fixed when \p fixed_radius (the scene's
    /// render.caustic_radius), else the distance to the 64th nearest photon, at most this.
    double radius_m = 0;
    bool fixed_radius = false;
};

/// \brief Shoots caustic photons (Jensen 1996) from every source of \p scene (area emitters,
///        point and spot lights, the sun, the sky) at the surfaces that pass light on
///        (passes_photons: a lobe and no diffuse part), until Scene::render.caustic_photons
///        are stored or 64 times as many shot. The radius is Scene::render.caustic_radius_m,
///        else the 64 nearest photons' (docs/rendering.md). Empty when no surface passes light
///        on or caustic_photons is 0. Bitwise identical for any thread count.
CausticPhotons shoot_caustic_photons(const EmbreeScene& rt, const Scene& scene, const Context& ctx);

/// \brief The light that leaves diffuse elements and reaches others through specular surfaces
///        (D S+ D paths; issue #28), as the solver's SpecularLight::transfers: photons shot as
///        by shoot_caustic_photons() with the elements of \p rt's mesh as the only sources,
///        chosen in proportion to \p exitance (one per element, W/m²: the likely solution's
///        reflected exitance), each one transfer of its power per unit of its element's
///        exitance, in the photons' order. An element of zero exitance is never chosen.
std::vector<SpecularLight::Transfer> specular_transfers(const EmbreeScene& rt, const Scene& scene,
                                                        std::span<const Rgb> exitance,
                                                        const Context& ctx);

/// \brief The irradiance (W/m²) the caustic photons of \p photons bring each element of
///        \p mesh (the mesh they were shot on): Σ Φ / A over the photons that landed on it,
///        summed in the photons' order (bitwise the same for any thread count). Empty when
///        there are no photons. SpecularLight::irradiance (issue #28).
std::vector<Rgb> caustic_irradiance(const CausticPhotons& photons, const RadiosityMesh& mesh);

/// \brief Renders the camera view of \p scene (the scene the mesh of \p rt was built from):
///        direct light from every source with multiple importance sampling, glossy, mirror and
///        glass lobes traced on, indirect diffuse light from \p solution (GatherMode), caustics
///        from a photon map in the final gather (shoot_caustic_photons()), thin-lens
///        depth of field, Scene::render's pixel filter and bounce limit (docs/rendering.md).
///        Bitwise identical for any thread count. Returns linear radiance, W/(sr·m²).
/// \throws ConfigError for spp < 1 or a negative gather depth.
Image render_final_gather(const EmbreeScene& rt, const Scene& scene, const Solution& solution,
                          const Camera& camera, const RenderOptions& options, const Context& ctx);

/// \brief Irradiance (W/m²) at each of \p points on the surface facing \p normals (unit), by
///        the final gather's paths (issue #29's `penumbra lightmap --gather`): \p samples
///        (rounded up to a square) stratified cosine-distributed directions, each a path of
///        render_final_gather() with light sampled from every source at its start (multiple
///        importance sampling) and the solution read one diffuse bounce away; no caustic
///        photons. The surface under a point is found by a short ray down its normal from 10⁻⁴
///        of the scene's diagonal above it; a point with none gets 0. Each point draws from a
///        stream named by its coordinates and normal (RngPurpose::texel_paths): the
///        same bits for any thread count and batching.
/// \throws ConfigError for \p samples < 1.
std::vector<Rgb> gather_irradiance_at(const EmbreeScene& rt, const Scene& scene,
                                      const Solution& solution, std::span<const Vec3> points,
                                      std::span<const Vec3> normals, int samples,
                                      const Context& ctx);

} // namespace penumbra::raytrace

namespace penumbra {
inline constexpr EnumName<raytrace::GatherMode> k_gather_mode_names[] = {
    {"final", raytrace::GatherMode::final_gather},
    {"none", raytrace::GatherMode::none},
    {"radiosity", raytrace::GatherMode::radiosity},
};
template <>
inline constexpr std::span<const EnumName<raytrace::GatherMode>>
    k_enum_names<raytrace::GatherMode> = k_gather_mode_names;
} // namespace penumbra
