#include "common/tile_stats.h"

#include <cmath>

namespace penumbra::test {

double luminance(const Rgb& c) {
    return 0.265 * c.r + 0.670 * c.g + 0.065 * c.b;
}

TileStats tile_stats(const std::vector<Image>& renders) {
    constexpr int k_tile = 16;
    const int tiles_x = renders[0].width / k_tile, tiles_y = renders[0].height / k_tile;
    TileStats stats;
    for (int ty = 0; ty < tiles_y; ++ty)
        for (int tx = 0; tx < tiles_x; ++tx) {
            std::vector<double> means;
            for (const Image& image : renders) {
                double sum = 0;
                for (int y = ty * k_tile; y < (ty + 1) * k_tile; ++y)
                    for (int x = tx * k_tile; x < (tx + 1) * k_tile; ++x)
                        sum += luminance(image.at(x, y));
                means.push_back(sum / (k_tile * k_tile));
            }
            double mean = 0, var = 0;
            for (double m : means)
                mean += m;
            mean /= double(means.size());
            for (double m : means)
                var += (m - mean) * (m - mean);
            var /= double(means.size() - 1);
            stats.mean.push_back(mean);
            stats.standard_error.push_back(std::sqrt(var / double(means.size())));
        }
    return stats;
}

} // namespace penumbra::test
