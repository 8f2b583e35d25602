// Caustic photons (issue #28): the sun straight down through a glass sphere onto a floor. The
// flux the photons bring into the sphere's shadow disc equals E_n π R² T̄, T̄ from a 1-D
// integral over the sphere's cross-section computed here; the photons do not depend on the
// thread count.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "common/test_util.h"
#include "core/scene.h"
#include "raytrace/raytrace.h"

namespace penumbra {
namespace {

constexpr double k_radius = 0.5, k_centre_height = 1.0, k_ior = 1.5, k_sun_w_m2 = 1000;

/// A UV sphere of quads (triangles at the poles), fronts outward, with its exact normals at
/// the vertices (the renderer interpolates them).
void add_sphere(Scene& scene, std::uint32_t material, const Vec3& centre, double radius,
                int segments, int rings) {
    auto unit = [&](int ring, int segment) {
        // segment % segments: the seam's vertices are bitwise the same on both sides.
        const double theta = k_pi * ring / rings, phi = 2 * k_pi * (segment % segments) / segments;
        return Vec3{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                    std::cos(theta)};
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            // Counter-clockwise seen from outside: down the meridian, then east.
            std::vector<Vec3> corners{unit(i, j), unit(i + 1, j), unit(i + 1, j + 1),
                                      unit(i, j + 1)};
            if (i == 0)
                corners.erase(corners.begin() + 3);
            else if (i == rings - 1)
                corners.erase(corners.begin() + 2);
            Polygon polygon;
            polygon.material = material;
            polygon.name = "sphere";
            for (const Vec3& n : corners) {
                polygon.vertices.push_back(centre + n * radius);
                polygon.normals.push_back(n);
            }
            scene.polygons.push_back(polygon);
        }
}

Scene sun_through_glass_sphere() {
    Scene scene;
    const auto floor = test::add_material(scene, "floor", Rgb(0.5f), {}, false);
    const auto glass = test::add_lobe_material(scene, "glass", Dielectric{k_ior, true, Rgb(1.0f)});
    test::add_rect(scene, "floor", floor, {-4, -4, 0}, {8, 0, 0}, {0, 8, 0});
    add_sphere(scene, glass, {0, 0, k_centre_height}, k_radius, 96, 48);
    Sun sun;
    sun.direction = {0, 0, 1};
    sun.irradiance = Rgb(float(k_sun_w_m2));
    sun.angular_diameter_deg = 0;
    scene.sun = sun;
    scene.render.caustic_photons = 100000;
    return scene;
}

/// Unpolarised Fresnel reflectance of a dielectric interface, incidence cos θi, relative
/// index eta = n_t / n_i.
double fresnel(double cos_i, double eta) {
    const double sin_t2 = (1 - cos_i * cos_i) / (eta * eta);
    if (sin_t2 >= 1)
        return 1;
    const double cos_t = std::sqrt(1 - sin_t2);
    const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

struct Ray2 {
    double x, z, dx, dz;
};

/// Refraction of unit d at unit normal n (facing d's origin side), relative index eta.
void refract(double& dx, double& dz, double nx, double nz, double eta) {
    const double cos_i = -(dx * nx + dz * nz);
    const double k = 1 - (1 - cos_i * cos_i) / (eta * eta);
    const double c = cos_i / eta - std::sqrt(k);
    dx = dx / eta + nx * c;
    dz = dz / eta + nz * c;
}

/// Fraction of the sun's light through the sphere's cross-section (impact parameter b,
/// uniform over the disc) that lands on the floor inside the shadow disc |x| < R. Counted:
/// the paths refracted in and out with k = 0 … 7 internal reflections, each weighted by
/// (1 − F)² F^k (F the same at every interface of a sphere: the internal angle of incidence
/// is the refraction angle); by symmetry each path stays in the plane through the axis, so
/// the meridional plane (x, z) traces it.
double shadow_disc_transmittance() {
    constexpr int k_steps = 20000, k_internal_reflections = 8;
    double sum = 0;
    for (int i = 0; i < k_steps; ++i) {
        const double b = k_radius * (i + 0.5) / k_steps;
        const double h = std::sqrt(k_radius * k_radius - b * b);
        const double f = fresnel(h / k_radius, k_ior);
        Ray2 r{b, k_centre_height + h, 0, -1};
        refract(r.dx, r.dz, b / k_radius, h / k_radius, k_ior);
        double weight = (1 - f) * (1 - f);
        for (int k = 0; k < k_internal_reflections; ++k, weight *= f) {
            // The chord to the next surface point: |p + s d − c| = R, s > 0.
            const double px = r.x, pz = r.z - k_centre_height;
            const double s = -2 * (px * r.dx + pz * r.dz);
            r.x += s * r.dx;
            r.z += s * r.dz;
            const double nx = r.x / k_radius, nz = (r.z - k_centre_height) / k_radius;
            double ox = r.dx, oz = r.dz; // leaving: refract out of the glass
            refract(ox, oz, -nx, -nz, 1 / k_ior);
            if (oz < 0) {
                const double land = r.x + ox * (-r.z / oz);
                if (std::abs(land) < k_radius)
                    sum += weight * b;
            }
            const double dn = r.dx * nx + r.dz * nz; // reflect inside for the next path
            r.dx -= 2 * dn * nx;
            r.dz -= 2 * dn * nz;
        }
    }
    // (1 / (π R²)) ∫ … 2π b db by the midpoint rule.
    return sum * (k_radius / k_steps) * 2 / (k_radius * k_radius);
}

/// One patch per polygon, a fan of elements each, one-sided: the polygons as given (the
/// mesher simplifies a finely tessellated sphere's polar rings), watertight where they share
/// vertices.
RadiosityMesh polygon_mesh(const Scene& scene) {
    RadiosityMesh mesh;
    for (std::uint32_t i = 0; i < scene.polygons.size(); ++i) {
        const Polygon& polygon = scene.polygons[i];
        const auto& v = polygon.vertices;
        const Vec3 normal = normalize(cross(v[1] - v[0], v[2] - v[0]));
        Patch patch;
        patch.polygon = patch.surface = i;
        patch.material = polygon.material;
        patch.normal = normal;
        patch.reflectance = diffuse_reflectance(scene.materials[polygon.material]);
        mesh.patches.push_back(patch);
        const auto first = std::uint32_t(mesh.positions.size());
        for (const Vec3& p : v) {
            mesh.positions.push_back(Vec3f(p));
            mesh.vertex_patch.push_back(i);
        }
        for (std::uint32_t k = 1; k + 1 < v.size(); ++k) {
            mesh.geometry_elements.push_back(std::uint32_t(mesh.triangles.size()));
            mesh.triangles.push_back({first, first + k, first + k + 1});
            mesh.element_patch.push_back(i);
            mesh.element_twin.push_back(-1);
            mesh.element_level.push_back(0);
            mesh.element_area.push_back(0.5 * length(cross(v[k] - v[0], v[k + 1] - v[0])));
        }
    }
    mesh.scene_diagonal = scene.bounds().diagonal();
    return mesh;
}

double flux_in_shadow_disc(const raytrace::CausticPhotons& photons) {
    double flux = 0;
    for (const raytrace::CausticPhoton& p : photons.photons) {
        EXPECT_NEAR(p.position.z, 0.0, 1e-6); // only the floor receives
        if (p.position.x * p.position.x + p.position.y * p.position.y < k_radius * k_radius)
            flux += p.power_w.g;
    }
    return flux;
}

TEST(CausticPhotons, SunThroughAGlassSphereFillsItsShadowDisc) {
    const Scene scene = sun_through_glass_sphere();
    const Context ctx = test::quiet_context();
    const RadiosityMesh mesh = polygon_mesh(scene);
    const raytrace::EmbreeScene rt(mesh);
    const raytrace::CausticPhotons photons = raytrace::shoot_caustic_photons(rt, scene, ctx);
    ASSERT_GE(photons.photons.size(), 100000u);
    const double t_bar = shadow_disc_transmittance();
    const double expected = k_sun_w_m2 * k_pi * k_radius * k_radius * t_bar;
    EXPECT_NEAR(flux_in_shadow_disc(photons), expected, 0.03 * expected) << "T̄ = " << t_bar;
    EXPECT_GT(t_bar, 0.5); // the integral counts most of the light
}

TEST(CausticPhotons, BitwiseIdenticalForOneAndTwoThreads) {
    Scene scene = sun_through_glass_sphere();
    scene.render.caustic_photons = 20000;
    const RadiosityMesh mesh = polygon_mesh(scene);
    const raytrace::EmbreeScene rt(mesh);
    const auto one = raytrace::shoot_caustic_photons(rt, scene, test::quiet_context(1));
    const auto two = raytrace::shoot_caustic_photons(rt, scene, test::quiet_context(2));
    ASSERT_EQ(one.photons.size(), two.photons.size());
    EXPECT_EQ(one.shot, two.shot);
    for (std::size_t i = 0; i < one.photons.size(); ++i) {
        ASSERT_EQ(one.photons[i].position, two.photons[i].position) << i;
        ASSERT_EQ(one.photons[i].power_w, two.photons[i].power_w) << i;
    }
}

} // namespace
} // namespace penumbra
