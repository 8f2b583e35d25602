// The visibility interface's defaults (core/visibility.h): a query that only answers
// occluded() reports transmittances of 1 (open) and 0 (blocked), and unnamed first hits.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "core/visibility.h"

namespace penumbra {
namespace {

// An opaque wall at x = 0 for y >= 0: a segment is blocked where it crosses that half plane.
class HalfWall final : public VisibilityQuery {
public:
    void occluded(std::span<const Segment> segments, std::span<std::uint8_t> out) const override {
        for (std::size_t i = 0; i < segments.size(); ++i) {
            const Segment& s = segments[i];
            const float t = -s.origin.x / s.direction.x; // where it meets the plane x = 0
            const float y = s.origin.y + t * s.direction.y;
            out[i] = t > s.tnear && t < s.tfar && y >= 0 ? 1 : 0;
        }
    }
    std::uint64_t rays_traced() const override { return 0; }
};

std::vector<Segment> crossings() {
    return {{{-1, 1, 0}, {2, 0, 0}, 0, 1},    // through the wall
            {{-1, -1, 0}, {2, 0, 0}, 0, 1},   // beside it
            {{-1, 1, 0}, {2, 0, 0}, 0, 0.4f}, // stops short of it
            {{1, 2, 0}, {-2, -1, 0}, 0, 1}};  // through it, from the other side
}

TEST(VisibilityQuery, DefaultTransmittanceIsOpenOrBlocked) {
    const HalfWall wall;
    const std::vector<Segment> segments = crossings();
    std::vector<float> t(segments.size(), -1.0f);
    wall.transmittance(segments, t);
    EXPECT_EQ(t, (std::vector<float>{0.0f, 1.0f, 1.0f, 0.0f}));

    std::vector<std::int32_t> hit(segments.size(), 7);
    wall.first_hit(segments, hit);
    EXPECT_EQ(hit, (std::vector<std::int32_t>{-2, -1, -1, -2}));
}

TEST(VisibilityQuery, NothingBlocksTransmitsEverything) {
    const std::vector<Segment> segments = crossings();
    std::vector<float> t(segments.size(), -1.0f);
    NoOcclusion().transmittance(segments, t);
    EXPECT_EQ(t, std::vector<float>(segments.size(), 1.0f));
}

} // namespace
} // namespace penumbra
