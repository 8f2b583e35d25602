#include "mesher/test_scenes.h"

#include "common/test_util.h"

namespace penumbra::test {

Scene two_rooms(double gap) {
    Scene scene;
    auto white = add_material(scene, "white", Rgb(0.5f));
    auto lamp = add_material(scene, "lamp", Rgb(0.0f), Rgb(10.0f), false);
    add_room(scene, {0, 0, 0}, {8, 4, 3}, white);
    add_rect(scene, "partition", white, {4.1, 0, gap}, {0, 0, 3 - gap}, {0, 4, 0}); // faces -x
    add_rect(scene, "lamp", lamp, {1.5, 1.5, 2.99}, {0, 1, 0}, {1, 0, 0});          // faces down
    scene.mesher.max_edge_length = 0.5;
    return scene;
}

BoxUnderLight box_under_light(double max_edge) {
    BoxUnderLight b;
    Scene& s = b.scene;
    auto white = add_material(s, "white", Rgb(0.5f));
    b.radiance = 5.0;
    auto lamp = add_material(s, "lamp", Rgb(0.0f), Rgb(float(b.radiance)), false);
    b.floor = std::uint32_t(s.polygons.size());
    add_rect(s, "floor", white, {0, 0, 0}, {4, 0, 0}, {0, 4, 0});
    const double x0 = 1.5, x1 = 2.4, y0 = 1.6, y1 = 2.3, h = 0.8;
    b.footprint = {x0, y0, x1, y1};
    add_rect(s, "box_top", white, {x0, y0, h}, {x1 - x0, 0, 0}, {0, y1 - y0, 0});
    add_rect(s, "box_s0", white, {x0, y0, 0}, {x1 - x0, 0, 0}, {0, 0, h});
    add_rect(s, "box_s1", white, {x1, y0, 0}, {0, y1 - y0, 0}, {0, 0, h});
    add_rect(s, "box_s2", white, {x1, y1, 0}, {x0 - x1, 0, 0}, {0, 0, h});
    add_rect(s, "box_s3", white, {x0, y1, 0}, {0, y0 - y1, 0}, {0, 0, h});
    b.light = std::uint32_t(s.polygons.size());
    add_rect(s, "light", lamp, {1.9, 1.75, 2.5}, {0, 0.6, 0}, {0.6, 0, 0}); // faces down
    b.light_vertices = s.polygons[b.light].vertices;
    for (double z : {0.0, h})
        for (double x : {x0, x1})
            for (double y : {y0, y1})
                b.box_vertices.emplace_back(x, y, z);
    s.mesher.max_edge_length = max_edge;
    return b;
}

} // namespace penumbra::test
