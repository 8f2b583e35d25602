// The annual metrics on the leaf elements (annual_mesh.h), a block of elements at a time.

#include "annual_mesh.h"

#include <algorithm>

#include "core/parallel.h"
#include "core/rgb.h"

namespace penumbra::app {

namespace {

// Elements per block: 256 × 8 760 hours × 2 matrices of floats, 18 MB per thread.
constexpr std::size_t k_block = 256;

struct BlockYear {
    Eigen::MatrixXf illuminance_lx, direct_sun_lx; ///< block elements × hours
};

BlockYear block_year(const solver::ElementCoefficients& c, const annual::SkyMatrix& matrix,
                     const SunBins& suns, Eigen::Index first, Eigen::Index count) {
    BlockYear y;
    y.illuminance_lx =
        c.sky.middleRows(first, count) * matrix.radiance * float(k_luminous_efficacy_lm_per_w);
    y.direct_sun_lx = Eigen::MatrixXf::Zero(count, matrix.radiance.cols());
    for (std::size_t h = 0; h < suns.bin.size(); ++h) {
        if (!suns.bin[h])
            continue;
        const auto bin = Eigen::Index(*suns.bin[h]);
        const auto normal_lx = float(matrix.suns[h].normal_lx);
        const auto col = Eigen::Index(h);
        y.direct_sun_lx.col(col) = c.sun_direct.col(bin).segment(first, count) * normal_lx;
        y.illuminance_lx.col(col) +=
            y.direct_sun_lx.col(col) + c.sun_indirect.col(bin).segment(first, count) * normal_lx;
    }
    return y;
}

} // namespace

MeshMetrics mesh_metrics(const solver::ElementCoefficients& coefficients,
                         const annual::SkyMatrix& matrix, const SunBins& suns,
                         const std::vector<bool>& occupied,
                         const annual::MetricThresholds& thresholds, const Context& ctx) {
    MeshMetrics out;
    out.mesh = coefficients.mesh;
    const std::size_t n = std::size_t(coefficients.sky.rows());
    out.elements.resize(n);
    out.mean_illuminance_lx.resize(n);
    const double occupied_hours = double(std::count(occupied.begin(), occupied.end(), true));
    run_in_arena(ctx, [&] {
        parallel_for_index((n + k_block - 1) / k_block, 1, [&](std::size_t b) {
            const std::size_t first = b * k_block, count = std::min(k_block, n - first);
            const BlockYear y =
                block_year(coefficients, matrix, suns, Eigen::Index(first), Eigen::Index(count));
            const std::vector<annual::SensorMetrics> m =
                annual::sensor_metrics(y.illuminance_lx, y.direct_sun_lx, occupied, thresholds);
            for (std::size_t k = 0; k < count; ++k) {
                out.elements[first + k] = m[k];
                double sum = 0;
                for (Eigen::Index h = 0; h < y.illuminance_lx.cols(); ++h)
                    if (occupied[std::size_t(h)])
                        sum += y.illuminance_lx(Eigen::Index(k), h);
                out.mean_illuminance_lx[first + k] = float(sum / occupied_hours);
            }
        });
    });
    return out;
}

} // namespace penumbra::app
