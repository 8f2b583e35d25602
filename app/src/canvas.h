#pragma once
// Private to penumbra_pipeline: an 8-bit sRGB picture to draw plans on, with filled
// rectangles, lines and text (stb_easy_font's segment font, scaled), written as PNG.

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::app {

/// An sRGB colour, 8 bits per channel.
struct Rgb8 {
    std::uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb8&) const = default;
};

/// A picture of width × height pixels, row-major from the top; drawing outside it is clipped.
class Canvas {
public:
    Canvas(int width, int height, Rgb8 background);

    int width() const { return width_; }
    int height() const { return height_; }
    Rgb8 at(int x, int y) const;
    void set(int x, int y, Rgb8 colour);
    /// \brief Fills the pixels x0 ≤ x < x1, y0 ≤ y < y1.
    void fill(int x0, int y0, int x1, int y1, Rgb8 colour);
    /// \brief A line of \p thickness pixels from (x0, y0) to (x1, y1), pixel centres.
    void line(double x0, double y0, double x1, double y1, int thickness, Rgb8 colour);
    /// \brief \p text with its top-left corner at (x, y), each font unit \p scale pixels.
    void text(int x, int y, const std::string& text, int scale, Rgb8 colour);
    /// \brief The width in pixels text() gives \p text at \p scale.
    static int text_width(const std::string& text, int scale);
    /// \brief The height in pixels of one line of text at \p scale.
    static int text_height(int scale);
    /// \brief Writes the picture as PNG, atomically.
    void write_png(const std::string& path) const;

private:
    int width_, height_;
    std::vector<std::uint8_t> rgb_;
};

} // namespace penumbra::app
