#include "core/scene.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

namespace {

double cos_deg(double deg) {
    return std::cos(deg * k_pi / 180.0);
}

} // namespace

double PointLight::profile_cos(double cos_theta) const {
    if (!spot)
        return 1.0;
    const double cos_beam = cos_deg(spot->beam_deg), cos_cutoff = cos_deg(spot->cutoff_deg);
    if (cos_theta >= cos_beam)
        return 1.0;
    if (cos_theta <= cos_cutoff)
        return 0.0;
    const double t = (cos_theta - cos_cutoff) / (cos_beam - cos_cutoff);
    return t * t * (3.0 - 2.0 * t);
}

double PointLight::profile(const Vec3& unit_dir) const {
    return spot ? profile_cos(dot(unit_dir, spot->direction)) : 1.0;
}

double PointLight::profile_solid_angle() const {
    if (!spot)
        return 4.0 * k_pi;
    const double cos_beam = cos_deg(spot->beam_deg), cos_cutoff = cos_deg(spot->cutoff_deg);
    return 2.0 * k_pi * ((1.0 - cos_beam) + 0.5 * (cos_beam - cos_cutoff));
}

RgbD PointLight::power() const {
    return RgbD(intensity) * profile_solid_angle();
}

double Sun::angular_radius() const {
    return 0.5 * angular_diameter_deg * k_pi / 180.0;
}

Rgb Sun::unoccluded(const Vec3& n) const {
    return irradiance * float(std::max(0.0, dot(n, direction)));
}

BBox Scene::bounds() const {
    BBox box;
    for (const Polygon& poly : polygons)
        for (const Vec3& v : poly.vertices)
            box.extend(v);
    for (const PointLight& light : point_lights)
        box.extend(light.position);
    return box;
}

bool Scene::has_emitter() const {
    for (const PointLight& light : point_lights)
        if (!light.intensity.is_black())
            return true;
    if (sun && !sun->irradiance.is_black())
        return true;
    for (const Polygon& poly : polygons)
        if (!materials[poly.material].emission.is_black())
            return true;
    return false;
}

} // namespace penumbra
