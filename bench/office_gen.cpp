// office_gen: writes a generated office floor (office_scene.h) as a scene file, scene.json
// beside office.obj/office.mtl, for `penumbra validate` and `penumbra bake`. The mesher
// settings keep the input tessellation as far as the mesher allows (mesh_input_as_is): about
// 1.3 elements per input triangle and side.
//
//   office_gen -o DIR [--rooms-x N] [--rooms-y N] [--tessellation K]   explicit layout
//   office_gen -o DIR --triangles N                                      about N input triangles

#include "office_scene.h"
#include "scene_writer.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
    using namespace penumbra;
    CLI::App cli{"office_gen: writes a generated office floor as scene.json + office.obj/.mtl"};
    std::string output;
    std::int64_t triangles = 0;
    bench::OfficeParams p;
    cli.add_option("-o,--output", output, "output folder (created if missing)")->required();
    auto* tris = cli.add_option("--triangles", triangles,
                                "pick offices and tessellation for about N input triangles")
                     ->check(CLI::Range(std::int64_t(1), std::int64_t(1) << 40));
    cli.add_option("--rooms-x", p.rooms_x, "offices along x")
        ->check(CLI::PositiveNumber)
        ->excludes(tris);
    cli.add_option("--rooms-y", p.rooms_y, "offices along y")
        ->check(CLI::PositiveNumber)
        ->excludes(tris);
    cli.add_option("--tessellation", p.tessellation, "split every rectangle into K x K quads")
        ->check(CLI::PositiveNumber)
        ->excludes(tris);
    cli.add_option("--desks", p.desks_per_room, "desks per office")->check(CLI::Range(0, 4));
    cli.add_option("--cabinets", p.cabinets_per_room, "cabinets per office")
        ->check(CLI::Range(0, 2));
    cli.add_option("--windows", p.windows_per_room, "windows per office in each exterior wall")
        ->check(CLI::Range(0, 2));
    CLI11_PARSE(cli, argc, argv);
    try {
        if (triangles > 0)
            p = bench::office_params_for_triangles(triangles, p);
        Scene scene = bench::office_floor(p);
        bench::mesh_input_as_is(scene);
        bench::write_scene(scene, output, "office");
        std::printf("%s/scene.json: %d x %d offices, tessellation %d, %zu polygons, %lld input "
                    "triangles\n",
                    output.c_str(), p.rooms_x, p.rooms_y, p.tessellation, scene.polygons.size(),
                    static_cast<long long>(bench::input_triangle_count(scene)));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "office_gen: %s\n", e.what());
        return 1;
    }
    return 0;
}
