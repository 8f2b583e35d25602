#pragma once
// Readers of the files the app writes (CSV tables, PNG pictures), shared by the suites that
// check `penumbra bake`'s grid outputs and `penumbra annual`'s.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "canvas.h"

namespace penumbra::test {

/// \brief The cells of every line of a CSV file (no quoting: the app writes none).
std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path);

/// \brief An 8-bit RGB picture.
struct Png {
    int width = 0, height = 0; ///< 0 × 0 when the file could not be read
    std::vector<std::uint8_t> rgb;
    app::Rgb8 at(int x, int y) const {
        const std::size_t i = 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

/// \brief Reads \p path as RGB.
Png read_png(const std::filesystem::path& path);

} // namespace penumbra::test
