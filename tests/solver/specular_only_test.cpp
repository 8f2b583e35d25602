// Links to a receiver that is specular only (a mirror, a metal, a dielectric: what it shows is
// traced) are refined to k_specular_only_slack times the oracle's thresholds. With the caustic
// photons off, a mirror tall block and a black Lambertian one are the same to the solve (both
// reflect no diffuse light): the mirror must take fewer links, the room's light must stay
// where it was, and the block's own irradiance, still reported, stay close to the black one's.

#include <optional>

#include <gtest/gtest.h>

#include "common/bake_util.h"
#include "common/test_util.h"
#include "core/scene_io.h"

namespace penumbra {
namespace {

// The Cornell box, clustered (the links to the block are cluster links first, then element
// links), with its tall block of material \p block and no caustic photons.
Scene cornell_with_tall_block(const Material& block) {
    Scene scene = load_scene(test::source_path("data/cornell/scene.json"));
    scene.solver.clustering = Clustering::on;
    scene.render.caustic_photons = 0;
    scene.materials.push_back(block);
    for (Polygon& p : scene.polygons)
        if (p.name == "tall_block")
            p.material = std::uint32_t(scene.materials.size() - 1);
    return scene;
}

// Σ H A over the elements of material \p material, summed over the channels: W.
double flux_onto(const app::BakeResult& r, std::uint32_t material) {
    double flux = 0;
    for (std::uint32_t e = 0; e < r.mesh.element_count(); ++e)
        if (r.mesh.patch_of(e).material == material) {
            const Rgb h = r.solution.irradiance_direct[e] + r.solution.irradiance_indirect[e];
            flux += double(h.sum()) * r.mesh.element_area[e];
        }
    return flux;
}

TEST(SpecularOnly, ReceiversAreRefinedLessAndTheRoomKeepsItsLight) {
    Material mirror;
    mirror.name = "mirror";
    mirror.reflectance = Rgb{};
    mirror.lobe = Mirror{Rgb(0.9f)};
    Material black;
    black.name = "black";
    black.reflectance = Rgb{};
    const Scene with_mirror = cornell_with_tall_block(mirror);
    const Scene with_black = cornell_with_tall_block(black);
    const auto block = std::uint32_t(with_mirror.materials.size() - 1);
    ASSERT_TRUE(radiosity_response(with_mirror.materials[block]).specular_only);
    ASSERT_FALSE(radiosity_response(with_black.materials[block]).specular_only);

    const app::BakeResult m = test::bake(with_mirror), b = test::bake(with_black);
    std::printf("links: mirror block %.0f, black block %.0f\n", double(m.stats.links),
                double(b.stats.links));
    EXPECT_LT(double(m.stats.links), 0.9 * double(b.stats.links));
    // The rest of the room, patch by patch.
    const double room = test::relative_patch_l1(m, b, block);
    std::printf("room's patches: relative L1 %.2e\n", room);
    EXPECT_LT(room, 2e-3);
    // The sensors, each at its point.
    ASSERT_EQ(m.sensors.size(), b.sensors.size());
    for (std::size_t s = 0; s < b.sensors.size(); ++s)
        EXPECT_NEAR(m.sensors[s].illuminance_total_lx, b.sensors[s].illuminance_total_lx,
                    0.005 * b.sensors[s].illuminance_total_lx)
            << "sensor " << s;
    // The block's reported irradiance, coarser but not off.
    const double fm = flux_onto(m, block), fb = flux_onto(b, block);
    std::printf("flux onto the block: mirror %.5f W, black %.5f W\n", fm, fb);
    EXPECT_NEAR(fm, fb, 0.03 * fb);
}

} // namespace
} // namespace penumbra
