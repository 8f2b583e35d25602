#include "core/scene.h"

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

} // namespace penumbra
