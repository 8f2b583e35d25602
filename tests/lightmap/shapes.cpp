#include "lightmap/shapes.h"

#include <cmath>

namespace penumbra::test {

namespace {

void add_face(Scene& scene, const std::string& name, std::uint32_t material,
              std::vector<Vec3> vertices) {
    Polygon p;
    p.vertices = std::move(vertices);
    p.material = material;
    p.name = name;
    p.source = "test:" + name;
    scene.polygons.push_back(std::move(p));
}

} // namespace

void add_sphere(Scene& scene, const std::string& name, std::uint32_t material, const Vec3& centre,
                double radius, int rings, int segments) {
    auto point = [&](int ring, int segment) {
        const double theta = k_pi * ring / rings, phi = 2 * k_pi * segment / segments;
        return centre + Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                             std::cos(theta)) *
                            radius;
    };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            // Counter-clockwise seen from outside: down the meridian, then along the parallel.
            const Vec3 a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1),
                       d = point(r, s + 1);
            if (r == 0)
                add_face(scene, name, material, {a, b, c});
            else if (r == rings - 1)
                add_face(scene, name, material, {a, b, d});
            else
                add_face(scene, name, material, {a, b, c, d});
        }
}

void add_cylinder_patch(Scene& scene, const std::string& name, std::uint32_t material,
                        double radius, double height, double angle_rad, int segments) {
    for (int s = 0; s < segments; ++s) {
        const double a0 = angle_rad * s / segments, a1 = angle_rad * (s + 1) / segments;
        const Vec3 p0(radius * std::cos(a0), radius * std::sin(a0), 0);
        const Vec3 p1(radius * std::cos(a1), radius * std::sin(a1), 0);
        const Vec3 up(0, 0, height);
        add_face(scene, name, material, {p0, p1, p1 + up, p0 + up});
    }
}

} // namespace penumbra::test
