#include "common/output_files.h"

#include <fstream>
#include <sstream>

#include <png.h>

namespace penumbra::test {

std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');)
            cells.push_back(cell);
        rows.push_back(cells);
    }
    return rows;
}

Png read_png(const std::filesystem::path& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    Png png;
    if (!png_image_begin_read_from_file(&image, path.c_str()))
        return png;
    image.format = PNG_FORMAT_RGB;
    png.width = int(image.width), png.height = int(image.height);
    png.rgb.resize(PNG_IMAGE_SIZE(image));
    png_image_finish_read(&image, nullptr, png.rgb.data(), 0, nullptr);
    return png;
}

} // namespace penumbra::test
