// Tregenza's and Reinhart's sky patches, laid out as Radiance's gendaymtx (rh_init) and
// reinsrc.cal lay them out, and the lookup of reinhart.cal (row from the altitude, column from
// the azimuth rounded to the nearest patch centre).

#include "annual/sky_patches.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/error.h"

namespace penumbra::annual {

namespace {

constexpr double k_deg = k_pi / 180;
constexpr int k_tregenza_rows = 7;
/// Patches per row in Tregenza's sky, from the horizon up (the cap above them).
constexpr std::array<int, k_tregenza_rows> k_tregenza_row_patches = {30, 30, 24, 24, 18, 12, 6};
constexpr int k_max_subdivision = 16;

double sin_deg(double a) {
    return std::sin(a * k_deg);
}

SkyPatch ground_patch(const Compass& compass) {
    SkyPatch ground;
    ground.altitude_min_deg = -90;
    ground.altitude_max_deg = 0;
    ground.azimuth_min_deg = 0;
    ground.azimuth_max_deg = 360;
    ground.centre = -compass.up;
    ground.solid_angle_sr = 2 * k_pi;
    return ground;
}

SkyPatch band_patch(const Compass& compass, double alt0, double alt1, double az0, double az1) {
    SkyPatch patch;
    patch.altitude_min_deg = alt0;
    patch.altitude_max_deg = alt1;
    patch.azimuth_min_deg = az0;
    patch.azimuth_max_deg = az1;
    patch.centre = compass.direction((alt0 + alt1) / 2, (az0 + az1) / 2);
    // dω = d(sin alt) dφ; the projected measure weighs it by sin alt.
    const double width = (az1 - az0) * k_deg;
    patch.solid_angle_sr = width * (sin_deg(alt1) - sin_deg(alt0));
    patch.horizontal_projected_solid_angle_sr =
        width * (sin_deg(alt1) * sin_deg(alt1) - sin_deg(alt0) * sin_deg(alt0)) / 2;
    return patch;
}

} // namespace

SkyPatches::SkyPatches(int subdivision, const Compass& compass)
    : subdivision_(subdivision), compass_(compass) {
    if (subdivision < 1 || subdivision > k_max_subdivision)
        throw ConfigError("sky subdivision (Reinhart's MF) " + std::to_string(subdivision) +
                          " is outside [1, " + std::to_string(k_max_subdivision) + "]");
    const int rows = k_tregenza_rows * subdivision;
    row_height_deg_ = 90.0 / (rows + 0.5);
    patches_.push_back(ground_patch(compass));
    for (int row = 0; row < rows; ++row) {
        row_first_.push_back(patches_.size());
        const int count = subdivision * k_tregenza_row_patches[std::size_t(row / subdivision)];
        const double width = 360.0 / count;
        const double alt0 = row * row_height_deg_, alt1 = (row + 1) * row_height_deg_;
        for (int column = 0; column < count; ++column)
            patches_.push_back(
                band_patch(compass, alt0, alt1, (column - 0.5) * width, (column + 0.5) * width));
    }
    row_first_.push_back(patches_.size());
    SkyPatch cap = band_patch(compass, rows * row_height_deg_, 90, 0, 360);
    cap.centre = compass.up;
    patches_.push_back(cap);
}

std::size_t SkyPatches::find(const Vec3& dir) const {
    const double up = dot(dir, compass_.up);
    if (up < 0)
        return ground;
    const double altitude = std::asin(std::min(1.0, up / length(dir))) / k_deg;
    const int rows = k_tregenza_rows * subdivision_;
    const int row = std::min(int(std::floor(altitude / row_height_deg_)), rows);
    const std::size_t first = row_first_[std::size_t(row)];
    if (row == rows)
        return first; // the cap
    const int count = int(row_first_[std::size_t(row) + 1] - first);
    double azimuth = std::atan2(dot(dir, compass_.east()), dot(dir, compass_.north)) / k_deg;
    if (azimuth < 0)
        azimuth += 360;
    const int column = int(std::floor(azimuth * count / 360 + 0.5)) % count;
    return first + std::size_t(column);
}

PatchWeights SkyPatches::interpolate(const Vec3& dir) const {
    PatchWeights out;
    const double up = dot(dir, compass_.up);
    if (up < 0) {
        out.patch[0] = ground;
        out.weight[0] = 1;
        out.count = 1;
        return out;
    }
    const double altitude = std::asin(std::min(1.0, up / length(dir))) / k_deg;
    double azimuth = std::atan2(dot(dir, compass_.east()), dot(dir, compass_.north)) / k_deg;
    if (azimuth < 0)
        azimuth += 360;
    const int rows = k_tregenza_rows * subdivision_;
    // Row r's centre is (r + 0.5) h; the cap's, the zenith.
    const auto centre = [&](int r) { return r == rows ? 90.0 : (r + 0.5) * row_height_deg_; };
    const auto add_row = [&](int r, double weight) {
        if (weight <= 0)
            return;
        const std::size_t first = row_first_[std::size_t(r)];
        if (r == rows) { // the cap
            out.patch[std::size_t(out.count)] = first;
            out.weight[std::size_t(out.count++)] = weight;
            return;
        }
        const int count = int(row_first_[std::size_t(r) + 1] - first);
        const double u = azimuth * count / 360; // patch centres at whole u (column 0: north)
        const int j = int(std::floor(u));
        const double f = u - j;
        for (const auto& [column, w] : {std::pair{j, 1 - f}, std::pair{j + 1, f}}) {
            if (w <= 0)
                continue;
            out.patch[std::size_t(out.count)] = first + std::size_t(column % count);
            out.weight[std::size_t(out.count++)] = weight * w;
        }
    };
    if (altitude <= centre(0)) {
        add_row(0, 1);
        return out;
    }
    int r = std::min(int(std::floor(altitude / row_height_deg_ - 0.5)), rows - 1);
    r = std::max(r, 0);
    const double t = std::clamp((altitude - centre(r)) / (centre(r + 1) - centre(r)), 0.0, 1.0);
    add_row(r, 1 - t);
    add_row(r + 1, t);
    return out;
}

} // namespace penumbra::annual
