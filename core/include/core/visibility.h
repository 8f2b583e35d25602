#pragma once
// The visibility interface the solver uses. raytrace implements it with Embree; tests may
// implement it with an analytic oracle.

#include <cstdint>
#include <span>
#include <vector>

#include "core/vec.h"

namespace penumbra {

/// A ray segment: points origin + t·direction for t in (tnear, tfar).
struct Segment {
    Vec3f origin;
    Vec3f direction;
    float tnear = 0;
    float tfar = 0;
};

/// \brief Batched occlusion queries. Implementations are thread-safe and deterministic.
class VisibilityQuery {
public:
    virtual ~VisibilityQuery() = default;
    /// Sets out[i] = 1 if anything blocks segments[i], else 0. Sizes must match.
    virtual void occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const = 0;
    /// Sets hit[i] to the mesh element segments[i] meets first (either side of a two-sided
    /// surface may be named), -1 if nothing blocks it, or -2 if something does that this
    /// query cannot name (the default, which calls occluded()). Sizes must match.
    virtual void first_hit(std::span<const Segment> segments, std::span<std::int32_t> hit) const;
    /// Sets out[i] to the fraction of light that passes along segments[i]: 1 if nothing is in
    /// the way, 0 if an opaque surface is, else the product of the transmittances T(θ) of the
    /// panes of glazing it crosses (ThinGlass::transmittance at its angle to each pane; one
    /// value for all channels, so grey panes until coloured glazing needs more, issue #30).
    /// The default, for queries where every surface is opaque, is 1 − occluded(). Sizes must
    /// match.
    virtual void transmittance(std::span<const Segment> segments, std::span<float> out) const;
    /// Total rays traced so far.
    virtual std::uint64_t rays_traced() const = 0;
};

inline void VisibilityQuery::first_hit(std::span<const Segment> segments,
                                       std::span<std::int32_t> hit) const {
    std::vector<std::uint8_t> blocked(segments.size());
    occluded(segments, blocked);
    for (std::size_t i = 0; i < blocked.size() && i < hit.size(); ++i)
        hit[i] = blocked[i] ? -2 : -1;
}

inline void VisibilityQuery::transmittance(std::span<const Segment> segments,
                                           std::span<float> out) const {
    std::vector<std::uint8_t> blocked(segments.size());
    occluded(segments, blocked);
    for (std::size_t i = 0; i < blocked.size() && i < out.size(); ++i)
        out[i] = blocked[i] ? 0.0f : 1.0f;
}

/// \brief A query that reports nothing blocked: for convex scenes and tests.
class NoOcclusion final : public VisibilityQuery {
public:
    void occluded(std::span<const Segment>, std::span<std::uint8_t> out) const override {
        for (auto& o : out)
            o = 0;
    }
    std::uint64_t rays_traced() const override { return 0; }
};

} // namespace penumbra
