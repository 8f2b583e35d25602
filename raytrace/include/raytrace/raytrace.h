#pragma once
// Embree 3 scene of the radiosity mesh: batched visibility for the solver and a camera
// renderer that reads the radiosity solution.

#include <atomic>
#include <cstdint>
#include <memory>

#include "core/context.h"
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
    /// camera sees the room behind a window; light between two surfaces through a pane passes
    /// unattenuated until the solver's links carry transmittance, issue #30).
    void occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const override;
    /// Names the front element of a two-sided surface.
    void first_hit(std::span<const Segment> segments, std::span<std::int32_t> hit) const override;
    void transmittance(std::span<const Segment> segments, std::span<float> out) const override;
    std::uint64_t rays_traced() const override;

    struct Hit {
        std::int32_t element = -1; ///< element hit on the side facing the ray; -1 if none
        float t = 0, u = 0, v = 0; ///< distance and barycentrics of vertices 1 and 2
        bool back_of_one_sided = false;
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

/// \brief Renders the camera view of the radiosity solution: radiance B/π interpolated from
///        vertex radiosity, stratified anti-aliasing with content-named random streams.
///        Returns linear radiance, W/(sr·m²).
Image render_solution(const EmbreeScene& scene, const Solution& solution, const Camera& camera,
                      const Context& ctx);

} // namespace penumbra::raytrace
