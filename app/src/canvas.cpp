#include "canvas.h"

#include <algorithm>
#include <cmath>

#include "core/image.h"

// stb_easy_font (Debian's libstb-dev) is a header of static functions, some unused here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace penumbra::app {

namespace {

/// One vertex of stb_easy_font's output: x, y, z and a colour, 16 bytes.
struct FontVertex {
    float x, y, z;
    unsigned char colour[4];
};
static_assert(sizeof(FontVertex) == 16);

} // namespace

Canvas::Canvas(int width, int height, Rgb8 background)
    : width_(width), height_(height), rgb_(3 * std::size_t(width) * std::size_t(height)) {
    fill(0, 0, width, height, background);
}

Rgb8 Canvas::at(int x, int y) const {
    const std::size_t i = 3 * (std::size_t(y) * std::size_t(width_) + std::size_t(x));
    return {rgb_[i], rgb_[i + 1], rgb_[i + 2]};
}

void Canvas::set(int x, int y, Rgb8 colour) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_)
        return;
    const std::size_t i = 3 * (std::size_t(y) * std::size_t(width_) + std::size_t(x));
    rgb_[i] = colour.r;
    rgb_[i + 1] = colour.g;
    rgb_[i + 2] = colour.b;
}

void Canvas::fill(int x0, int y0, int x1, int y1, Rgb8 colour) {
    for (int y = std::max(y0, 0); y < std::min(y1, height_); ++y)
        for (int x = std::max(x0, 0); x < std::min(x1, width_); ++x)
            set(x, y, colour);
}

void Canvas::line(double x0, double y0, double x1, double y1, int thickness, Rgb8 colour) {
    // A square brush stepped along the line at most a pixel apart.
    const int steps = int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
    const int lo = -(thickness - 1) / 2, hi = thickness / 2;
    for (int i = 0; i <= steps; ++i) {
        const double t = double(i) / steps;
        const int x = int(std::lround(x0 + t * (x1 - x0)));
        const int y = int(std::lround(y0 + t * (y1 - y0)));
        fill(x + lo, y + lo, x + hi + 1, y + hi + 1, colour);
    }
}

void Canvas::text(int x, int y, const std::string& text, int scale, Rgb8 colour) {
    std::string chars = text;                                  // stb_easy_font takes char*
    std::vector<FontVertex> quads(4 * 64 * (text.size() + 1)); // ≤ 64 quads a character
    const int count = stb_easy_font_print(0, 0, chars.data(), nullptr, quads.data(),
                                          int(quads.size() * sizeof(FontVertex)));
    for (int q = 0; q < count; ++q) {
        const FontVertex* v = &quads[4 * std::size_t(q)];
        fill(x + int(v[0].x) * scale, y + int(v[0].y) * scale, x + int(v[2].x) * scale,
             y + int(v[2].y) * scale, colour);
    }
}

int Canvas::text_width(const std::string& text, int scale) {
    std::string chars = text;
    return stb_easy_font_width(chars.data()) * scale;
}

int Canvas::text_height(int scale) {
    return 7 * scale; // the font's capitals and digits span 7 units
}

void Canvas::write_png(const std::string& path) const {
    write_png_rgb8(path, width_, height_, rgb_);
}

} // namespace penumbra::app
