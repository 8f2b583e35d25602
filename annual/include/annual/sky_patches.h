#pragma once
// The sky cut into patches for daylight coefficients (issue #31): Tregenza's 145 patches
// (Tregenza 1987) and Reinhart's subdivisions of them (the MF of Radiance's reinhart.cal),
// numbered as Radiance's gendaymtx, reinhart.cal and reinsrc.cal number them: 0 the ground, then
// rows of patches from the horizon up, each row from north (its first patch centred on north)
// toward east, and last the zenith cap. docs/annual.md gives the geometry.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "core/sky.h"
#include "core/vec.h"

namespace penumbra::annual {

/// \brief One patch: a band of altitude and azimuth (the zenith cap: a disc; the ground: the
///        lower hemisphere). Angles in degrees, azimuth clockwise from north seen from above.
struct SkyPatch {
    double altitude_min_deg = 0, altitude_max_deg = 0;
    /// The first patch of each row is centred on north: its azimuths run from below 0 to
    /// above 0. The zenith cap and the ground span [0, 360].
    double azimuth_min_deg = 0, azimuth_max_deg = 0;
    /// Unit, in the compass's frame: the middle altitude and azimuth (Radiance's patch
    /// direction); the zenith for the cap, the nadir for the ground.
    Vec3 centre;
    double solid_angle_sr = 0;
    /// ∫ max(0, ω·up) dω over the patch: an unobstructed upward horizontal's irradiance per
    /// unit radiance of the patch (0 for the ground; the sky's patches sum to π).
    double horizontal_projected_solid_angle_sr = 0;
};

/// \brief A direction's shares of up to four patches (the weights sum to 1).
struct PatchWeights {
    std::array<std::size_t, 4> patch{};
    std::array<double, 4> weight{};
    int count = 0;
};

/// \brief Tregenza's or Reinhart's patches of the whole sphere: 144 MF² + 1 sky patches and
///        the ground, index 0. MF = 1 is Tregenza's 145: rows 12° high of 30, 30, 24, 24, 18,
///        12 and 6 patches and a cap above 84°. MF = n has 7n rows of height
///        90° / (7n + 0.5), row r with n × (Tregenza's count of row ⌊r / n⌋) patches, and one
///        cap of half a row's height (as Radiance: the cap is not subdivided).
class SkyPatches {
public:
    static constexpr std::size_t ground = 0;

    /// \throws ConfigError for \p subdivision (Reinhart's MF) outside [1, 16].
    explicit SkyPatches(int subdivision = 1, const Compass& compass = {});

    int subdivision() const { return subdivision_; }
    const Compass& compass() const { return compass_; }
    /// \brief Number of patches with the ground: 144 MF² + 2 (146 for Tregenza's).
    std::size_t size() const { return patches_.size(); }
    const SkyPatch& operator[](std::size_t index) const { return patches_[index]; }
    std::span<const SkyPatch> patches() const { return patches_; }
    /// \brief Height of a row of patches, degrees: 90 / (7 MF + 0.5).
    double row_height_deg() const { return row_height_deg_; }

    /// \brief The patch of the direction \p dir (any length > 0, in the compass's frame, away
    ///        from the scene): the ground below the horizon (dir·up < 0), else the sky patch
    ///        whose bounds contain it (a direction on a bound goes to the patch above or, in
    ///        azimuth, clockwise of it; as reinhart.cal).
    std::size_t find(const Vec3& dir) const;

    /// \brief The shares of \p dir in the patches around it: linear interpolation between
    ///        the centres of the two rows of patches its altitude lies between (the cap's
    ///        centre is the zenith; below the first row's centre, that row alone), and within
    ///        each row between the two patch centres its azimuth lies between. Sky values
    ///        given per patch then vary linearly between the patches' centres instead of
    ///        stepping at their bounds: daylight coefficients binned by these weights see a
    ///        sky's gradation within a patch (CIE 171's grazing views through a roof opening:
    ///        4.5 % → docs/annual.md). The ground (dir·up < 0) is one patch.
    PatchWeights interpolate(const Vec3& dir) const;

private:
    int subdivision_;
    Compass compass_;
    double row_height_deg_;
    std::vector<SkyPatch> patches_;
    std::vector<std::size_t> row_first_; ///< index of each row's first patch, then the cap's
};

} // namespace penumbra::annual
