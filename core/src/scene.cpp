#include "core/scene.h"

#include "core/error.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace penumbra {

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
