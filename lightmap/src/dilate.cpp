// Dilation of a filled atlas into its padding: uncovered texels copy the nearest covered
// texel, so that bilinear lookups and mip levels at chart edges blend chart values only.

#include <limits>

#include "core/error.h"
#include "lightmap/texels.h"

namespace penumbra::lightmap {

void dilate(Image& image, const std::vector<std::uint8_t>& covered, int radius) {
    const auto w = std::size_t(image.width), h = std::size_t(image.height);
    if (covered.size() != w * h)
        throw InternalError("lightmap: dilate: the coverage mask does not match the image");
    const Image source = image;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            if (covered[std::size_t(y) * w + std::size_t(x)])
                continue;
            int best_d2 = std::numeric_limits<int>::max();
            for (int yy = std::max(0, y - radius); yy <= std::min(image.height - 1, y + radius);
                 ++yy)
                for (int xx = std::max(0, x - radius); xx <= std::min(image.width - 1, x + radius);
                     ++xx) {
                    const int d2 = (xx - x) * (xx - x) + (yy - y) * (yy - y);
                    if (covered[std::size_t(yy) * w + std::size_t(xx)] && d2 < best_d2) {
                        best_d2 = d2;
                        image.at(x, y) = source.at(xx, yy);
                    }
                }
        }
}

} // namespace penumbra::lightmap
