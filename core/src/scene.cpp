#include "core/scene.h"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"

namespace penumbra {

std::array<int, 3> ProbeGrid::counts() const {
    // A point is lost only to rounding below 10⁻⁹ of a spacing: a 2 m box at 0.5 m holds 5.
    std::array<int, 3> n{};
    for (std::size_t a = 0; a < 3; ++a)
        n[a] = int(std::floor((max[a] - min[a]) / spacing_m + 1e-9)) + 1;
    return n;
}

std::vector<Vec3> ProbeGrid::points() const {
    const std::array<int, 3> n = counts();
    Vec3 start;
    for (std::size_t a = 0; a < 3; ++a)
        start[a] = 0.5 * (min[a] + max[a] - spacing_m * (n[a] - 1));
    std::vector<Vec3> out;
    out.reserve(std::size_t(n[0]) * std::size_t(n[1]) * std::size_t(n[2]));
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                out.push_back(start + Vec3(i, j, k) * spacing_m);
    return out;
}

std::vector<Vec3> ProbeSettings::positions() const {
    std::vector<Vec3> out = points;
    if (grid) {
        const std::vector<Vec3> lattice = grid->points();
        out.insert(out.end(), lattice.begin(), lattice.end());
    }
    return out;
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
    if (sky && (sky->zenith_radiance > 0 || sky->ground_radiance.value_or(0) > 0))
        return true;
    for (const Polygon& poly : polygons)
        if (!materials[poly.material].emission.is_black())
            return true;
    return false;
}

void Scene::select_camera(const std::string& camera_name) {
    std::vector<std::string> names;
    for (const NamedCamera& named : cameras) {
        if (named.name == camera_name) {
            camera = named.camera;
            return;
        }
        names.push_back(named.name);
    }
    throw InputError(file, "cameras",
                     names.empty() ? fmt::format("no camera named '{}': the scene has no "
                                                 "'cameras'",
                                                 camera_name)
                                   : fmt::format("no camera named '{}' (known: {})", camera_name,
                                                 fmt::join(names, ", ")));
}

} // namespace penumbra
