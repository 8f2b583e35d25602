#pragma once
// Private to penumbra_core: turns Radiance primitives into Penumbra's scene data (issue #30):
// polygons with their materials, the sun, and the sky and ground hemispheres. Modifiers are
// remembered across all the files of one scene, in the order they are read.

#include <map>
#include <optional>
#include <string>

#include "core/light.h"
#include "core/sky.h"

#include "../geometry_import.h"
#include "modifiers.h"

namespace penumbra::radiance {

/// \brief The sun and the sky the Radiance files gave, each with the line that gave it.
struct Sources {
    std::optional<Sun> sun;
    std::optional<Sky> sky;
    SourceLine sun_where, sky_where;
};

class SceneBuilder {
public:
    explicit SceneBuilder(double metres_per_unit) : metres_per_unit_(metres_per_unit) {}

    /// \brief Adds \p p, moved by \p xf (and turned over if \p invert). Throws InputError at its
    ///        line for an unsupported type, a wrong argument count or an unknown modifier.
    void add(const Primitive& p, const Affine& xf, bool invert);
    /// \brief The polygons added since the last call, with the materials they use.
    ImportedGeometry take_geometry();
    /// \brief The sun and the sky (with its ground, if given). Throws InputError for a ground
    ///        hemisphere without a sky.
    Sources sources() const;

private:
    struct Definition {
        Modifier modifier;
        Primitive primitive;
    };
    struct Ground {
        double radiance = 0;
        SourceLine where;
    };

    void define(const Primitive& p, Modifier modifier);
    const Definition& modifier_of(const Primitive& p) const;
    void add_polygon(const Primitive& p, const Affine& xf, bool invert);
    void add_source(const Primitive& p, const Affine& xf);
    void add_sun(const Primitive& p, const Vec3& direction, const Material& light);
    void add_hemisphere(const Primitive& p, bool up, Sky sky, double ground_radiance);

    double metres_per_unit_;
    std::map<std::string, Definition> modifiers_;
    ImportedGeometry geometry_;
    std::map<std::string, std::uint32_t> geometry_materials_;
    Sources sources_;
    std::optional<Ground> ground_;
};

} // namespace penumbra::radiance
