// The files of the light probes: probes.json for engines, probes.vtp for ParaView.

#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/probes.h"
#include "core/error.h"
#include "core/files.h"
#include "viewer/vtk_output.h"

namespace penumbra::app {

namespace {

namespace fs = std::filesystem;

const char* const k_convention =
    "real orthonormal spherical harmonics, bands 0-2, order Y00, Y1-1, Y10, Y11, Y2-2, Y2-1, "
    "Y20, Y21, Y22 (proportional to 1, y, z, x, xy, yz, 3z^2-1, xz, x^2-y^2 of a unit "
    "direction in the scene's axes; constants 0.282095, 0.488603, 1.092548, 0.315392, "
    "0.546274, no Condon-Shortley sign). Coefficients are of irradiance: "
    "E(n) = sum_k sh[k] Y_k(n) is the irradiance on a surface facing n, the radiance "
    "coefficients already multiplied by pi, 2pi/3, pi/4 per band (Ramamoorthi & Hanrahan "
    "2001); divide by them for radiance";

std::string probes_json(const Scene& scene, const ProbeResult& r) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["scene_file"] = scene.file;
    j["quantity"] = "irradiance (direct + indirect), spherical harmonics L2";
    j["units"] = "W/m2, linear RGB (the scene's radiometric channels)";
    j["convention"] = k_convention;
    j["rays_per_probe"] = r.rays_per_probe;
    j["seconds"] = r.seconds;
    nlohmann::json probes = nlohmann::json::array();
    for (const Probe& p : r.probes) {
        nlohmann::json sh = nlohmann::json::array();
        for (const RgbD& c : p.irradiance.c)
            sh.push_back({c.r, c.g, c.b});
        probes.push_back({{"position", {p.position.x, p.position.y, p.position.z}}, {"sh", sh}});
    }
    j["probes"] = probes;
    return j.dump(2) + "\n";
}

std::vector<viewer::PointArray> probe_arrays(const ProbeResult& r) {
    std::vector<viewer::PointArray> arrays;
    for (int k = 0; k < lightmap::k_sh_l2_count; ++k) {
        viewer::PointArray a{fmt::format("sh_{}", k), "W/m²", 3, {}};
        for (const Probe& p : r.probes) {
            const RgbD& c = p.irradiance.c[std::size_t(k)];
            a.values.insert(a.values.end(), {c.r, c.g, c.b});
        }
        arrays.push_back(std::move(a));
    }
    // The mean of E(n) over all directions n: the band-0 term alone.
    viewer::PointArray mean{"irradiance_mean", "W/m²", 3, {}};
    const double y00 = lightmap::sh_basis_l2(Vec3(0, 0, 1))[0];
    for (const Probe& p : r.probes) {
        const RgbD e = p.irradiance.c[0] * y00;
        mean.values.insert(mean.values.end(), {e.r, e.g, e.b});
    }
    arrays.push_back(std::move(mean));
    return arrays;
}

} // namespace

void write_probes(const std::string& dir, const Scene& scene, const ProbeResult& result) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
        throw ConfigError(fmt::format("cannot create output folder '{}': {}", dir, ec.message()));
    remove_stale_temp_files(dir, {"probes.json", "probes.vtp"});
    write_text_file((fs::path(dir) / "probes.json").string(), probes_json(scene, result));
    std::vector<Vec3> points;
    for (const Probe& p : result.probes)
        points.push_back(p.position);
    viewer::write_points_vtp((fs::path(dir) / "probes.vtp").string(), points, probe_arrays(result));
}

} // namespace penumbra::app
