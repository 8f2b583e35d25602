// Image files: OpenEXR round trip, PNG encoding, automatic exposure.

#include "core/image.h"

#include "common/test_util.h"
#include "core/error.h"
#include "core/files.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace penumbra {
namespace {

namespace fs = std::filesystem;

Image test_pattern(int width, int height) {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            image.at(x, y) =
                Rgb(0.1f * float(x) + 1e-7f, float(y) / 3.0f, float(x * y) * 1234.567f);
    image.at(0, 0) = Rgb(std::numeric_limits<float>::denorm_min(), -2.5f, 6.5e4f);
    return image;
}

std::size_t files_in(const std::string& dir) {
    return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

std::uint32_t big_endian_u32(const std::string& bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i)
        v = (v << 8) | std::uint8_t(bytes[at + i]);
    return v;
}

TEST(Exr, RoundTripIsExact) {
    const std::string dir = test::temp_dir("exr");
    const std::string path = dir + "/image.exr";
    const Image image = test_pattern(13, 7);
    write_exr(path, image);
    const Image back = read_exr(path);
    ASSERT_EQ(back.width, 13);
    ASSERT_EQ(back.height, 7);
    EXPECT_EQ(
        std::memcmp(back.pixels.data(), image.pixels.data(), image.pixels.size() * sizeof(Rgb)), 0);
    EXPECT_EQ(files_in(dir), 1u); // no temporary file left
}

// Half channels: each value comes back rounded to 11 significant bits (relative error at most
// 2⁻¹¹ in the normal range, 2⁻²⁴ absolute below it); values beyond the largest half, 65 504,
// come back as 65 504, not as infinity.
TEST(Exr, HalfPixelsRoundToElevenBits) {
    const std::string dir = test::temp_dir("exr-half");
    const std::string path = dir + "/image.exr";
    const Image image = test_pattern(13, 7);
    write_exr(path, image, ExrPixels::half);
    const Image back = read_exr(path);
    ASSERT_EQ(back.width, 13);
    ASSERT_EQ(back.height, 7);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double v = std::min(double(image.pixels[i][c]), 65504.0);
            EXPECT_NEAR(back.pixels[i][c], v, std::max(v * 0x1p-11, 0x1p-24)) << i << ", " << c;
        }
    EXPECT_EQ(files_in(dir), 1u);
}

TEST(Exr, OverwritesExistingFile) {
    const std::string path = test::temp_dir("exr") + "/image.exr";
    write_exr(path, test_pattern(4, 4));
    write_exr(path, test_pattern(3, 2));
    EXPECT_EQ(read_exr(path).width, 3);
}

TEST(Exr, ErrorsNameThePath) {
    const std::string dir = test::temp_dir("exr");
    try {
        read_exr(dir + "/missing.exr");
        FAIL() << "no exception";
    } catch (const ExternalError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.exr"), std::string::npos) << e.what();
    }
    write_text_file(dir + "/bad.exr", "not an exr file");
    EXPECT_THROW(read_exr(dir + "/bad.exr"), ExternalError);
    EXPECT_THROW(write_exr(dir + "/no/such/folder/a.exr", test_pattern(2, 2)), ExternalError);
    EXPECT_THROW(write_exr(dir + "/empty.exr", Image()), InternalError);
}

// Issue #32: a full disk (here a file size limit, EFBIG) said "cannot write" or OpenEXR's
// "Error writing"; the message now gives the system's reason, and nothing is left behind.
TEST(Exr, FailedWriteSaysWhyAndLeavesNothing) {
    const std::string dir = test::temp_dir("exr_efbig");
    for (ExrPixels pixels : {ExrPixels::float32, ExrPixels::half}) {
        const std::string path = dir + "/image.exr";
        const std::string message = test::external_error_with_file_limit(
            1000, [&] { write_exr(path, test_pattern(64, 64), pixels); });
        EXPECT_NE(message.find(fmt::format("'{}': {}", path, std::strerror(EFBIG))),
                  std::string::npos)
            << message;
        EXPECT_EQ(files_in(dir), 0u);
    }
}

TEST(Png, FailedWriteSaysWhyAndLeavesNothing) {
    const std::string dir = test::temp_dir("png_efbig");
    const std::string path = dir + "/image.png";
    write_png(path, test_pattern(64, 64), 1.0);
    const std::uintmax_t size = fs::file_size(path);
    fs::remove(path);
    const std::string message = test::external_error_with_file_limit(
        size / 2, [&] { write_png(path, test_pattern(64, 64), 1.0); });
    EXPECT_NE(message.find(fmt::format("'{}': {}", path, std::strerror(EFBIG))), std::string::npos)
        << message;
    EXPECT_EQ(files_in(dir), 0u);
}

TEST(Png, WritesEightBitRgbOfTheRightSize) {
    const std::string dir = test::temp_dir("png");
    const std::string path = dir + "/image.png";
    write_png(path, test_pattern(13, 7), 1.0);
    const std::string bytes = read_text_file(path);
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    ASSERT_GT(bytes.size(), 33u);
    EXPECT_EQ(std::memcmp(bytes.data(), signature, 8), 0);
    EXPECT_EQ(bytes.substr(12, 4), "IHDR");
    EXPECT_EQ(big_endian_u32(bytes, 16), 13u);
    EXPECT_EQ(big_endian_u32(bytes, 20), 7u);
    EXPECT_EQ(std::uint8_t(bytes[24]), 8); // bit depth
    EXPECT_EQ(std::uint8_t(bytes[25]), 2); // colour type RGB
    EXPECT_EQ(files_in(dir), 1u);
}

TEST(Png, EncodesSrgbWithExposureAndClamp) {
    const std::string path = test::temp_dir("png") + "/image.png";
    Image image(4, 1);
    image.at(0, 0) = Rgb(0.25f, 0.0f, 1.0f); // × 2: 0.5, 0, 2 (clamped)
    image.at(1, 0) = Rgb(-1.0f, std::numeric_limits<float>::quiet_NaN(), 0.001f);
    image.at(2, 0) = Rgb(0.5f);
    image.at(3, 0) = Rgb(std::numeric_limits<float>::infinity());
    write_png(path, image, 2.0);

    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&png, path.c_str())) << png.message;
    png.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(png));
    ASSERT_TRUE(png_image_finish_read(&png, nullptr, rgb.data(), 0, nullptr)) << png.message;
    // sRGB(0.5) = 0.7354 → 188; sRGB(0.002) = 12.92 × 0.002 = 0.0258 → 7; ≥ 1 → 255.
    const std::vector<std::uint8_t> expected = {188, 0, 255, 0, 0, 7, 255, 255, 255, 255, 255, 255};
    EXPECT_EQ(rgb, expected);
}

// Bytes already sRGB-encoded are written as they are, rows from the top.
TEST(Png, WritesEightBitPixelsUnchanged) {
    const std::string path = test::temp_dir("png") + "/rgb8.png";
    const std::vector<std::uint8_t> bytes = {0, 1, 2, 3, 4, 5, 250, 251, 252, 253, 254, 255};
    write_png_rgb8(path, 2, 2, bytes);
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&png, path.c_str())) << png.message;
    EXPECT_EQ(png.width, 2u);
    EXPECT_EQ(png.height, 2u);
    png.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(png));
    ASSERT_TRUE(png_image_finish_read(&png, nullptr, rgb.data(), 0, nullptr)) << png.message;
    EXPECT_EQ(rgb, bytes);
    EXPECT_THROW(write_png_rgb8(path, 3, 2, bytes), InternalError);
}

TEST(Png, ErrorsNameThePath) {
    const std::string dir = test::temp_dir("png");
    try {
        write_png(dir + "/no/such/folder/a.png", test_pattern(2, 2), 1.0);
        FAIL() << "no exception";
    } catch (const ExternalError& e) {
        EXPECT_NE(std::string(e.what()).find("a.png"), std::string::npos) << e.what();
    }
    EXPECT_THROW(write_png(dir + "/a.png", test_pattern(2, 2), 0.0), ConfigError);
}

TEST(AutoExposure, UniformImageMapsToMiddleGrey) {
    Image image(5, 3);
    const Rgb colour(0.2f, 0.4f, 0.1f);
    for (Rgb& p : image.pixels)
        p = colour;
    const double y = 0.265 * double(colour.r) + 0.670 * double(colour.g) + 0.065 * double(colour.b);
    EXPECT_NEAR(auto_exposure(image), 0.18 / y, 1e-12 * (0.18 / y));

    // Black pixels are ignored.
    image.at(0, 0) = Rgb();
    image.at(4, 2) = Rgb();
    EXPECT_NEAR(auto_exposure(image), 0.18 / y, 1e-12 * (0.18 / y));
}

TEST(AutoExposure, LogAverageAndBlackImage) {
    Image image(2, 1);
    image.at(0, 0) = Rgb(1.0f);
    image.at(1, 0) = Rgb(4.0f); // luminance 1 and 4: log average 2
    EXPECT_NEAR(auto_exposure(image), 0.09, 1e-12);
    EXPECT_EQ(auto_exposure(Image(3, 3)), 1.0);
    EXPECT_EQ(auto_exposure(Image()), 1.0);
}

} // namespace
} // namespace penumbra
