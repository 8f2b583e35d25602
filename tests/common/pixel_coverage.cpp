#include "common/pixel_coverage.h"

#include <algorithm>
#include <cmath>

namespace penumbra::test {

std::pair<double, double> footprint(const Camera& c, int pixel, int count, bool vertical) {
    const double half = std::tan(c.fov_deg * k_pi / 360.0) * std::abs(c.eye.z);
    const double scale = vertical ? half * c.height / c.width : half;
    double lo = (2.0 * pixel / count - 1.0) * scale, hi = (2.0 * (pixel + 1) / count - 1.0) * scale;
    return vertical ? std::pair(-hi, -lo) : std::pair(lo, hi);
}

// The box clipped by each edge's half-plane (Sutherland–Hodgman), then the shoelace formula.
double area_inside(double x0, double x1, double y0, double y1, const std::vector<Vec3>& poly) {
    std::vector<Vec2> clip{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (std::size_t e = 0; e < poly.size(); ++e) {
        const Vec3 &a = poly[e], &b = poly[(e + 1) % poly.size()];
        const auto side = [&](const Vec2& p) {
            return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        };
        std::vector<Vec2> out;
        for (std::size_t i = 0; i < clip.size(); ++i) {
            const Vec2 &p = clip[i], &q = clip[(i + 1) % clip.size()];
            const double sp = side(p), sq = side(q);
            if (sp >= 0)
                out.push_back(p);
            if ((sp >= 0) != (sq >= 0))
                out.push_back(p + (q - p) * (sp / (sp - sq)));
        }
        clip = out;
    }
    double twice = 0;
    for (std::size_t i = 0; i < clip.size(); ++i) {
        const Vec2 &p = clip[i], &q = clip[(i + 1) % clip.size()];
        twice += p.x * q.y - q.x * p.y;
    }
    return 0.5 * std::abs(twice);
}

double covered_share(const Camera& c, int x, int y, const std::vector<Vec3>& poly) {
    const auto [x0, x1] = footprint(c, x, c.width, false);
    const auto [y0, y1] = footprint(c, y, c.height, true);
    return area_inside(x0, x1, y0, y1, poly) / ((x1 - x0) * (y1 - y0));
}

RimErrors rim_errors(const Camera& c, const Image& plain, const Image& refined,
                     const std::vector<Vec3>& lamp, double radiance) {
    RimErrors r;
    double squares = 0;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            const double cover = covered_share(c, x, y, lamp);
            const double want = radiance * cover;
            r.worst_plain = std::max(r.worst_plain, std::abs(plain.at(x, y).g - want));
            const double error = refined.at(x, y).g - want;
            r.worst_refined = std::max(r.worst_refined, std::abs(error));
            squares += error * error; // every pixel: those off the rim should be exact
            r.pixels += cover > 0 && cover < 1;
        }
    r.rms_refined = r.pixels > 0 ? std::sqrt(squares / r.pixels) : 0;
    return r;
}

} // namespace penumbra::test
