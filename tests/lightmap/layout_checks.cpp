#include "lightmap/layout_checks.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace penumbra::test {

using namespace lightmap;

double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return length(p - a);
    const Vec3 bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return length(p - b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return length(p - (a + ab * (d1 / (d1 - d3))));
    const Vec3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return length(p - c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return length(p - (a + ac * (d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double denom = 1 / (va + vb + vc);
    return length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

namespace {

void expect_padding_kept(const AtlasTexels& atlas, int padding) {
    const int size = atlas.size;
    std::vector<std::int64_t> owner(std::size_t(size) * std::size_t(size), -1);
    for (const Texel& t : atlas.texels) {
        ASSERT_GE(t.x, padding);
        ASSERT_GE(t.y, padding);
        ASSERT_LT(t.x, size - padding);
        ASSERT_LT(t.y, size - padding);
        std::int64_t& o = owner[std::size_t(t.y) * std::size_t(size) + std::size_t(t.x)];
        ASSERT_EQ(o, -1) << "texel (" << t.x << ", " << t.y << ") listed twice";
        o = t.chart;
    }
    for (const Texel& t : atlas.texels)
        for (int y = std::max(0, t.y - padding); y <= std::min(size - 1, t.y + padding); ++y)
            for (int x = std::max(0, t.x - padding); x <= std::min(size - 1, t.x + padding); ++x) {
                const std::int64_t o = owner[std::size_t(y) * std::size_t(size) + std::size_t(x)];
                ASSERT_TRUE(o == -1 || o == std::int64_t(t.chart))
                    << "charts " << t.chart << " and " << o << " closer than the padding at (" << x
                    << ", " << y << ")";
            }
}

void expect_on_surface(const Chart& chart, const ChartPlacement& placement, const Texel& t) {
    const SurfacePoint& s = t.centre;
    const auto& v = chart.triangles[s.triangle].vertices;
    const Vec3 a = chart.vertices[v[0]].position, b = chart.vertices[v[1]].position,
               c = chart.vertices[v[2]].position;
    EXPECT_LT(distance_to_triangle(s.position, a, b, c), 1e-6);
    EXPECT_GE(s.texel_uv.x, t.x - 1e-9);
    EXPECT_LE(s.texel_uv.x, t.x + 1 + 1e-9);
    EXPECT_GE(s.texel_uv.y, t.y - 1e-9);
    EXPECT_LE(s.texel_uv.y, t.y + 1 + 1e-9);
    // The texel point mapped to 3D by the triangle's affine map, independently of the
    // sample's own barycentric coordinates.
    const Vec2 p = s.texel_uv, ta = placement.texel_uv[v[0]], tb = placement.texel_uv[v[1]],
               tc = placement.texel_uv[v[2]];
    const double det = (tb.x - ta.x) * (tc.y - ta.y) - (tc.x - ta.x) * (tb.y - ta.y);
    const double beta = ((p.x - ta.x) * (tc.y - ta.y) - (tc.x - ta.x) * (p.y - ta.y)) / det;
    const double gamma = ((tb.x - ta.x) * (p.y - ta.y) - (p.x - ta.x) * (tb.y - ta.y)) / det;
    const Vec3 mapped = a + (b - a) * beta + (c - a) * gamma;
    EXPECT_LT(length(mapped - s.position), 1e-6);
}

} // namespace

void expect_valid_layout(const Charts& charts, const AtlasLayout& layout,
                         const std::vector<AtlasTexels>& atlases) {
    ASSERT_EQ(int(atlases.size()), layout.atlas_count);
    ASSERT_EQ(layout.placements.size(), charts.charts.size());
    std::vector<std::size_t> texels_per_chart(charts.charts.size(), 0);
    for (const AtlasTexels& atlas : atlases) {
        expect_padding_kept(atlas, layout.padding);
        for (const Texel& t : atlas.texels) {
            ++texels_per_chart[t.chart];
            expect_on_surface(charts.charts[t.chart], layout.placements[t.chart], t);
        }
    }
    for (std::size_t c = 0; c < charts.charts.size(); ++c)
        EXPECT_GT(texels_per_chart[c], 0u) << "chart " << c << " covers no texel";
}

void expect_no_flips(const Charts& charts, const AtlasLayout& layout) {
    for (std::size_t c = 0; c < charts.charts.size(); ++c) {
        const Chart& chart = charts.charts[c];
        if (chart.kind == ChartKind::imported)
            continue;
        const auto& uv = layout.placements[c].texel_uv;
        for (const ChartTriangle& t : chart.triangles) {
            const Vec2 a = uv[t.vertices[0]], b = uv[t.vertices[1]], d = uv[t.vertices[2]];
            EXPECT_GT((b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y), 0)
                << "chart " << c << " of '" << chart.object << "'";
        }
    }
}

} // namespace penumbra::test
