#include "mesher/exact_direct.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::test {

namespace {

struct P2 {
    double x, y;
};

double cross2(const P2& o, const P2& a, const P2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

std::vector<P2> convex_hull(std::vector<P2> p) {
    std::sort(p.begin(), p.end(),
              [](const P2& a, const P2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    if (p.size() < 3)
        return p;
    std::vector<P2> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
            --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
            --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

// Sutherland–Hodgman: subject clipped by the counter-clockwise convex polygon clip.
std::vector<P2> clip(const std::vector<P2>& subject, const std::vector<P2>& hull) {
    std::vector<P2> out = subject;
    for (std::size_t i = 0; i < hull.size() && !out.empty(); ++i) {
        const P2 a = hull[i], b = hull[(i + 1) % hull.size()];
        std::vector<P2> in = out;
        out.clear();
        for (std::size_t j = 0; j < in.size(); ++j) {
            const P2 c = in[j], d = in[(j + 1) % in.size()];
            const double sc = cross2(a, b, c), sd = cross2(a, b, d);
            if (sc >= 0)
                out.push_back(c);
            if ((sc >= 0) != (sd >= 0)) {
                const double t = sc / (sc - sd);
                out.push_back({c.x + (d.x - c.x) * t, c.y + (d.y - c.y) * t});
            }
        }
    }
    return out;
}

// Signed Lambert sum: ½ Σ θ_i n·(r_i × r_{i+1}) / |r_i × r_{i+1}| with unit r_i.
double lambert_sum(const Vec3& p, const Vec3& n, const std::vector<Vec3>& poly) {
    double sum = 0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3 a = normalize(poly[i] - p), b = normalize(poly[(i + 1) % poly.size()] - p);
        const Vec3 c = cross(a, b);
        const double s = length(c);
        if (s < 1e-300)
            continue;
        sum += 0.5 * std::atan2(s, dot(a, b)) * dot(n, c) / s;
    }
    return sum;
}

struct LightFrame {
    Vec3 origin, u, v, normal;
    P2 to_2d(const Vec3& q) const { return {dot(q - origin, u), dot(q - origin, v)}; }
    Vec3 to_3d(const P2& q) const { return origin + u * q.x + v * q.y; }
};

} // namespace

double polygon_irradiance(const Vec3& p, const Vec3& n, const std::vector<Vec3>& polygon) {
    return std::abs(lambert_sum(p, n, polygon));
}

double exact_irradiance(const Vec3& p, const Vec3& n, const std::vector<Vec3>& light,
                        double radiance, const std::vector<std::vector<Vec3>>& blockers) {
    LightFrame f;
    f.origin = light[0];
    f.u = normalize(light[1] - light[0]);
    f.normal = normalize(cross(light[1] - light[0], light[2] - light[0]));
    f.v = cross(f.normal, f.u);
    std::vector<P2> light2;
    for (const Vec3& q : light)
        light2.push_back(f.to_2d(q));
    const double height = dot(f.origin - p, f.normal);
    const double lift = 1e-7;
    // Each blocker's shadow on the light's plane, seen from p.
    std::vector<std::vector<P2>> hulls;
    for (const auto& blocker : blockers) {
        std::vector<P2> pts;
        for (Vec3 c : blocker) {
            if (dot(c - p, n) < lift)
                c += n * (lift - dot(c - p, n));
            const double t = height / dot(c - p, f.normal);
            if (t < 1)
                continue; // beyond the light: cannot hide it
            pts.push_back(f.to_2d(p + (c - p) * t));
        }
        if (pts.size() >= 3)
            hulls.push_back(convex_hull(pts));
    }
    auto sum_of = [&](const std::vector<P2>& poly2) {
        std::vector<Vec3> poly;
        for (const P2& q : poly2)
            poly.push_back(f.to_3d(q));
        return poly.size() >= 3 ? lambert_sum(p, n, poly) : 0.0;
    };
    double total = sum_of(light2);
    // Inclusion–exclusion over the blockers' shadows.
    const std::size_t m = hulls.size();
    for (std::size_t mask = 1; mask < (std::size_t(1) << m); ++mask) {
        std::vector<P2> part = light2;
        int bits = 0;
        for (std::size_t k = 0; k < m; ++k)
            if (mask & (std::size_t(1) << k)) {
                part = clip(part, hulls[k]);
                ++bits;
            }
        total += (bits % 2 ? -1.0 : 1.0) * sum_of(part);
    }
    return radiance * std::abs(total);
}

} // namespace penumbra::test
