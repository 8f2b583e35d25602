#pragma once
// RGB float images and their files: linear OpenEXR and tone-mapped sRGB PNG.

#include <cstdint>
#include <string>
#include <vector>

#include "core/rgb.h"

namespace penumbra {

struct Image {
    int width = 0, height = 0;
    std::vector<Rgb> pixels; ///< row-major, top row first

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(std::size_t(w) * std::size_t(h)) {}
    Rgb& at(int x, int y) { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    const Rgb& at(int x, int y) const {
        return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
};

/// \brief How an OpenEXR file stores its channels.
enum class ExrPixels {
    float32, ///< 32-bit float
    half,    ///< 16-bit float: 3 significant digits, values up to 65 504 (larger are clamped)
};

/// \brief Writes linear RGB OpenEXR (32-bit float unless \p pixels says half) atomically
///        (temp name, then rename).
void write_exr(const std::string& path, const Image& image, ExrPixels pixels = ExrPixels::float32);
/// \brief Reads an RGB OpenEXR file.
Image read_exr(const std::string& path);

/// \brief Automatic exposure: maps the log-average luminance to middle grey 0.18 (Reinhard
///        et al. 2002's key value). Returns 1 for a black image.
double auto_exposure(const Image& image);

/// \brief Writes 8-bit sRGB PNG of image × exposure (clamped), atomically.
void write_png(const std::string& path, const Image& image, double exposure);

/// \brief Writes \p width × \p height pixels of three bytes each (R, G, B, already
///        sRGB-encoded; row-major, top row first) as an 8-bit PNG, atomically. Throws
///        InternalError if \p rgb holds another number of bytes, ExternalError on failure.
void write_png_rgb8(const std::string& path, int width, int height,
                    const std::vector<std::uint8_t>& rgb);

} // namespace penumbra
