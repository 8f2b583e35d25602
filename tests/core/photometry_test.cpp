#include "core/rgb.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(Photometry, RadianceWhiteLightConvention) {
    // 1 W of equal-energy white is 179 lm (Radiance's WHTEFFICACY).
    EXPECT_DOUBLE_EQ(to_photometric(Rgb(1.0f)), 179.0);
    // Luminance weights 0.265, 0.670, 0.065.
    EXPECT_NEAR(to_photometric(Rgb(1, 0, 0)), 179.0 * 0.265, 1e-9);
    EXPECT_NEAR(to_photometric(Rgb(0, 1, 0)), 179.0 * 0.670, 1e-9);
    EXPECT_NEAR(to_photometric(Rgb(0, 0, 1)), 179.0 * 0.065, 1e-9);
}

TEST(Photometry, FromPhotometricInvertsAndKeepsColour) {
    Rgb c = from_photometric(1000.0, Rgb(1.0f, 0.5f, 0.25f));
    EXPECT_NEAR(to_photometric(c), 1000.0, 1e-3);
    EXPECT_FLOAT_EQ(c.g / c.r, 0.5f);
    EXPECT_FLOAT_EQ(c.b / c.r, 0.25f);
    EXPECT_TRUE(from_photometric(10.0, Rgb(0.0f)).is_black());
}

TEST(Photometry, CornellLightLuminance) {
    // Radiance (17, 12, 4) W/(sr·m²) → 179 (0.265·17 + 0.670·12 + 0.065·4) cd/m².
    EXPECT_NEAR(to_photometric(Rgb(17, 12, 4)), 179.0 * (4.505 + 8.04 + 0.26), 1e-6);
}

} // namespace
} // namespace penumbra
