#include "common/reference_tiles.h"

#include <cmath>
#include <cstdio>

#include "common/test_util.h"

namespace penumbra::test {

double tile_luminance(const Rgb& c) {
    return 0.265 * c.r + 0.670 * c.g + 0.065 * c.b;
}

TileStats tile_stats(const std::vector<Image>& renders) {
    const int tiles_x = renders[0].width / k_tile_px, tiles_y = renders[0].height / k_tile_px;
    TileStats stats;
    for (int ty = 0; ty < tiles_y; ++ty)
        for (int tx = 0; tx < tiles_x; ++tx) {
            std::vector<double> means;
            for (const Image& image : renders) {
                double sum = 0;
                for (int y = ty * k_tile_px; y < (ty + 1) * k_tile_px; ++y)
                    for (int x = tx * k_tile_px; x < (tx + 1) * k_tile_px; ++x)
                        sum += tile_luminance(image.at(x, y));
                means.push_back(sum / (k_tile_px * k_tile_px));
            }
            double mean = 0, var = 0;
            for (double m : means)
                mean += m;
            mean /= double(means.size());
            for (double m : means)
                var += (m - mean) * (m - mean);
            var = means.size() > 1 ? var / double(means.size() - 1) : 0.0;
            stats.mean.push_back(mean);
            stats.standard_error.push_back(std::sqrt(var / double(means.size())));
        }
    return stats;
}

std::vector<double> tile_standard_errors(const Image& stderr_image) {
    std::vector<double> out;
    for (int ty = 0; ty < stderr_image.height / k_tile_px; ++ty)
        for (int tx = 0; tx < stderr_image.width / k_tile_px; ++tx) {
            double var = 0;
            for (int y = ty * k_tile_px; y < (ty + 1) * k_tile_px; ++y)
                for (int x = tx * k_tile_px; x < (tx + 1) * k_tile_px; ++x)
                    var += std::pow(tile_luminance(stderr_image.at(x, y)), 2);
            out.push_back(std::sqrt(var) / (k_tile_px * k_tile_px));
        }
    return out;
}

int tiles_off_reference(const std::vector<Image>& renders, const std::string& reference_exr,
                        const std::string& stderr_exr, const std::string& label) {
    const Image ref = read_exr(source_path(reference_exr));
    const Image ref_stderr = read_exr(source_path(stderr_exr));
    const TileStats ours = tile_stats(renders), reference = tile_stats({ref});
    const std::vector<double> reference_se = tile_standard_errors(ref_stderr);
    const std::size_t tiles_x = std::size_t(ref.width / k_tile_px);
    int off = 0;
    for (std::size_t t = 0; t < ours.mean.size(); ++t) {
        const double se = std::hypot(ours.standard_error[t], reference_se[t]);
        const double delta = ours.mean[t] - reference.mean[t];
        if (std::abs(delta) > 3 * se + 0.005 * reference.mean[t]) {
            ++off;
            std::printf(
                "%s: tile (%zu, %zu): %.5f against the reference %.5f (%+.2f %%, %.1f SE)\n",
                label.c_str(), t % tiles_x, t / tiles_x, ours.mean[t], reference.mean[t],
                100 * delta / reference.mean[t], std::abs(delta) / se);
        }
    }
    return off;
}

ImageMoments green_moments(const Image& image) {
    ImageMoments m;
    for (const Rgb& p : image.pixels)
        m.mean += p.g;
    m.mean /= double(image.pixels.size());
    for (const Rgb& p : image.pixels)
        m.sd += (p.g - m.mean) * (p.g - m.mean);
    m.sd = std::sqrt(m.sd / double(image.pixels.size() - 1));
    return m;
}

} // namespace penumbra::test
