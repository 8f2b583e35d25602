// Daylight coefficients on one hierarchical system (see solver/daylight_coefficients.h).
//
// The system is built, and its links refined, under a uniform sky and ground: every patch
// lit at once, so the links resolve light from every direction. Each patch then becomes a
// set of sky links (each root's share of the sky integral that falls in the patch) and one
// solve on the fixed links; the sensors gather its B − E through weights computed once.

#include "solver/daylight_coefficients.h"

#include "core/parallel.h"
#include "hierarchical_system.h"
#include "hierarchy/leaf_mesh.h"
#include "output/point_gather.h"
#include "sources/sky_light.h"
#include "sources/sun_light.h"

namespace penumbra::solver {

namespace {

// Σ weight of \p samples per patch into row \p row of \p out. Sums in sample order: the same
// for every thread count.
void bin_samples(const std::vector<SkySample>& samples, const PatchBinning& patches,
                 Eigen::MatrixXf& out, Eigen::Index row) {
    std::vector<double> sum(patches.count, 0.0);
    for (const SkySample& s : samples)
        patches.add(s.direction, s.weight * s.radiance.g, sum);
    for (std::size_t p = 0; p < patches.count; ++p)
        out(row, Eigen::Index(p)) = float(sum[p]);
}

// Per root of the system: the sky integral at its centroid binned by patch (as its sky link
// integrates it: the same point, quadrature and stream). Panes take none.
Eigen::MatrixXf root_coefficients(const HierarchicalSystem& sys, const Scene& lit,
                                  const VisibilityQuery& visibility, const PatchBinning& patches,
                                  const Context& ctx) {
    const Hierarchy& h = sys.h;
    Eigen::MatrixXf out =
        Eigen::MatrixXf::Zero(Eigen::Index(h.root_count), Eigen::Index(patches.count));
    parallel_for_index(h.root_count, 16, [&](std::size_t r) {
        if (!h.opaque[r])
            return;
        const Vec3 from = h.centroid(std::uint32_t(r)) + h.normal[r] * sys.settings.offset;
        Pcg32 rng = Pcg32::for_stream(RngPurpose::sky_visibility, r, 0, 0, ctx.seed);
        std::vector<SkySample> samples;
        sky_point_samples(*lit.sky, from, h.normal[r], h.diagonal, visibility,
                          k_sky_element_quadrature, rng, samples);
        bin_samples(samples, patches, out, Eigen::Index(r));
    });
    return out;
}

// The sensors' own view of each patch: each patch's part of the sky integral gathers from
// all the cells it overlaps, so its error is that of the cells along its edges; 4× the
// cells of k_sky_point_quadrature halve it (docs/annual.md), for a few sensors' rays.
constexpr SkyQuadrature k_sky_coefficient_quadrature{64, 5};

// The sensors' own view of each patch (as gather_direct integrates the sky at a sensor).
Eigen::MatrixXf sensor_direct(const Scene& scene, const Sky& sky, const ElementGeometry& geo,
                              const VisibilityQuery& visibility, const PatchBinning& patches,
                              const Context& ctx) {
    Eigen::MatrixXf out =
        Eigen::MatrixXf::Zero(Eigen::Index(scene.sensors.size()), Eigen::Index(patches.count));
    parallel_for_index(scene.sensors.size(), 1, [&](std::size_t s) {
        const Sensor& sensor = scene.sensors[s];
        Pcg32 rng = Pcg32::for_stream(RngPurpose::sky_visibility, s, 3,
                                      std::uint64_t(RngPurpose::sensor_visibility), ctx.seed);
        std::vector<SkySample> samples;
        sky_point_samples(sky, sensor.position + sensor.normal * geo.offset, sensor.normal,
                          geo.diagonal, visibility, k_sky_coefficient_quadrature, rng, samples);
        bin_samples(samples, patches, out, Eigen::Index(s));
    });
    return out;
}

// Each sensor's weights of the leaf elements that can send light on (they reflect or pass
// it): B − E at the sensor is then a dot product per patch.
std::vector<std::vector<ElementWeight>>
sensor_weights(const Scene& scene, const RadiosityMesh& leaf_mesh, const ElementGeometry& geo,
               const VisibilityQuery& visibility, const Context& ctx) {
    std::vector<std::uint8_t> candidate(geo.size(), 0);
    for (std::size_t e = 0; e < geo.size(); ++e) {
        const Patch& p = leaf_mesh.patch_of(std::uint32_t(e));
        candidate[e] = (!p.reflectance.is_black() || !p.diffuse_transmittance.is_black()) ? 1 : 0;
    }
    std::vector<std::vector<ElementWeight>> out(scene.sensors.size());
    parallel_for_index(scene.sensors.size(), 1, [&](std::size_t s) {
        const Sensor& sensor = scene.sensors[s];
        const GatherPoint p{sensor.position, sensor.normal, s, RngPurpose::sensor_visibility};
        out[s] =
            element_weights(geo, candidate, visibility, p, scene.solver.visibility_rays, ctx.seed);
    });
    return out;
}

// A sun of unit normal irradiance in \p direction: its links to the leaves facing it (the
// sun's patch of light is sharper than the sky's, and the links were not refined for it).
SourceTerms sun_sources(const HierarchicalSystem& sys, const std::vector<std::uint32_t>& leaves,
                        const VisibilityQuery& visibility, const Vec3& direction,
                        double diameter_deg) {
    const Hierarchy& h = sys.h;
    Sun sun;
    sun.direction = direction;
    sun.irradiance = Rgb(1.0f);
    sun.angular_diameter_deg = diameter_deg;
    std::vector<LightLink> made(leaves.size());
    parallel_for_index(leaves.size(), 64, [&](std::size_t k) {
        const std::uint32_t n = leaves[k];
        const SunIrradiance s =
            sun_triangle_irradiance(sun, {h.triangle[n], h.normal[n]}, sys.settings.offset,
                                    h.diagonal, n, 1, visibility, sys.settings.rows);
        made[k] = {n, LightId(SunSource{}), s.irradiance, 0, 0};
    });
    SourceTerms terms;
    terms.emission.assign(h.root_count, Rgb{});
    for (const LightLink& l : made)
        if (!l.irradiance.is_black())
            terms.light_links.push_back(l);
    return terms;
}

// The luminous part of \p c as the sensors' coefficients take it (to_photometric's weights, as
// the grey sky vectors and the suns' illuminance multiply it).
float luminous(const RgbD& c) {
    return float(to_photometric(c) / k_luminous_efficacy_lm_per_w);
}

// What the solution of \p sources (solved before) brings each sensor, into column \p column.
void gather_sensors(const HierarchicalSystem& sys, const LeafMesh& leaf,
                    const std::vector<std::vector<ElementWeight>>& weights, Eigen::MatrixXf& out,
                    Eigen::Index column) {
    const std::vector<Rgb>& b = sys.values.b;
    for (std::size_t s = 0; s < weights.size(); ++s) {
        RgbD sum;
        for (const ElementWeight& w : weights[s])
            sum += RgbD(b[leaf.element_node[w.element]]) * w.weight;
        out(Eigen::Index(s), column) = luminous(sum);
    }
}

// Each leaf element's irradiance of the solution, direct and reflected, into column \p column.
void gather_element_totals(const HierarchicalSystem& sys, const LeafMesh& leaf,
                           Eigen::MatrixXf& out, Eigen::Index column) {
    const NodeValues& v = sys.values;
    for (std::size_t e = 0; e < leaf.element_node.size(); ++e) {
        const std::uint32_t node = leaf.element_node[e];
        out(Eigen::Index(e), column) = luminous(RgbD(v.h_direct[node]) + RgbD(v.h_indirect[node]));
    }
}

// Each leaf element's direct and reflected irradiance of the solution apart.
void gather_element_parts(const HierarchicalSystem& sys, const LeafMesh& leaf,
                          Eigen::MatrixXf& direct, Eigen::MatrixXf& indirect, Eigen::Index column) {
    const NodeValues& v = sys.values;
    for (std::size_t e = 0; e < leaf.element_node.size(); ++e) {
        const std::uint32_t node = leaf.element_node[e];
        direct(Eigen::Index(e), column) = luminous(RgbD(v.h_direct[node]));
        indirect(Eigen::Index(e), column) = luminous(RgbD(v.h_indirect[node]));
    }
}

// Patch p's sources: each root's share of the unit sky in p, through sky links.
SourceTerms patch_sources(const Eigen::MatrixXf& roots, std::size_t p) {
    SourceTerms s;
    s.emission.assign(std::size_t(roots.rows()), Rgb{});
    for (Eigen::Index r = 0; r < roots.rows(); ++r)
        if (const float e = roots(r, Eigen::Index(p)); e > 0)
            s.light_links.push_back({std::uint32_t(r), LightId(SkySource{}), Rgb(e), 0, 0});
    return s;
}

} // namespace

Scene coefficient_scene(const Scene& scene) {
    Scene lit = scene;
    lit.sun.reset();
    lit.point_lights.clear();
    Sky sky; // radiance 1: each sample's weight is then its share T cos θ Δω of the integral
    sky.model = UniformSky{};
    if (scene.sky)
        sky.compass = scene.sky->compass;
    sky.zenith_radiance = 1.0;
    sky.ground_radiance = 1.0;
    lit.sky = sky;
    return lit;
}

DaylightCoefficients daylight_coefficients(const Scene& scene, const RadiosityMesh& mesh,
                                           const VisibilityQuery& visibility,
                                           const PatchBinning& patches,
                                           std::span<const Vec3> sun_directions,
                                           double sun_angular_diameter_deg, const Context& ctx,
                                           CoefficientTargets targets) {
    return run_in_arena(ctx, [&] {
        const Scene lit = coefficient_scene(scene);
        SweepLog log{mesh, nullptr, nullptr};
        std::unique_ptr<HierarchicalSystem> sys;
        {
            ProgressStage progress(ctx, "daylight links");
            sys = build_hierarchical(lit, mesh, visibility, ctx, progress, log, nullptr);
        }
        DaylightCoefficients dc;
        dc.nodes = sys->h.size();
        dc.links = sys->links.link_count();
        const Eigen::MatrixXf roots = root_coefficients(*sys, lit, visibility, patches, ctx);
        const LeafMesh leaf = leaf_elements(mesh, sys->h);
        const ElementGeometry geo(leaf.of(mesh));
        dc.direct = sensor_direct(scene, *lit.sky, geo, visibility, patches, ctx);
        const auto weights = sensor_weights(scene, leaf.of(mesh), geo, visibility, ctx);
        const auto sensors = Eigen::Index(scene.sensors.size());
        const auto suns = Eigen::Index(sun_directions.size());
        dc.indirect = Eigen::MatrixXf::Zero(sensors, Eigen::Index(patches.count));
        dc.sun_indirect = Eigen::MatrixXf::Zero(sensors, suns);
        if (targets == CoefficientTargets::with_elements) {
            const auto elements = Eigen::Index(leaf.element_node.size());
            dc.elements = ElementCoefficients{
                leaf.of(mesh), Eigen::MatrixXf(elements, Eigen::Index(patches.count)),
                Eigen::MatrixXf(elements, suns), Eigen::MatrixXf(elements, suns)};
        }
        ProgressStage progress(ctx, "daylight coefficients");
        const double solves = double(patches.count + sun_directions.size());
        const std::vector<std::uint32_t> leaves = sys->h.leaves();
        for (std::size_t p = 0; p < patches.count; ++p) {
            solve_sources(*sys, patch_sources(roots, p), scene.solver, log);
            gather_sensors(*sys, leaf, weights, dc.indirect, Eigen::Index(p));
            if (dc.elements)
                gather_element_totals(*sys, leaf, dc.elements->sky, Eigen::Index(p));
            progress.update(double(p + 1) / solves);
        }
        for (std::size_t k = 0; k < sun_directions.size(); ++k) {
            solve_sources(
                *sys,
                sun_sources(*sys, leaves, visibility, sun_directions[k], sun_angular_diameter_deg),
                scene.solver, log);
            gather_sensors(*sys, leaf, weights, dc.sun_indirect, Eigen::Index(k));
            if (dc.elements)
                gather_element_parts(*sys, leaf, dc.elements->sun_direct, dc.elements->sun_indirect,
                                     Eigen::Index(k));
            progress.update(double(patches.count + k + 1) / solves);
        }
        return dc;
    });
}

Eigen::MatrixXf sun_direct_irradiance(const Scene& scene, const RadiosityMesh& mesh,
                                      const VisibilityQuery& visibility,
                                      std::span<const Vec3> sun_directions,
                                      double angular_diameter_deg, const Context& ctx) {
    return run_in_arena(ctx, [&] {
        const ElementGeometry geo(mesh);
        Eigen::MatrixXf out = Eigen::MatrixXf::Zero(Eigen::Index(scene.sensors.size()),
                                                    Eigen::Index(sun_directions.size()));
        ProgressStage progress(ctx, "direct sun");
        parallel_for_index(sun_directions.size(), 4, [&](std::size_t k) {
            Sun sun;
            sun.direction = sun_directions[k];
            sun.irradiance = Rgb(1.0f);
            sun.angular_diameter_deg = angular_diameter_deg;
            for (std::size_t s = 0; s < scene.sensors.size(); ++s) {
                const Sensor& sensor = scene.sensors[s];
                const double cos_theta = dot(sensor.normal, sun.direction);
                if (cos_theta <= 0)
                    continue;
                Pcg32 rng =
                    Pcg32::for_stream(RngPurpose::sun_visibility, s, k,
                                      std::uint64_t(RngPurpose::sensor_visibility), ctx.seed);
                const double v = sun_point_visibility(
                    sun, sensor.position + sensor.normal * geo.offset, geo.diagonal,
                    scene.solver.visibility_rays, visibility, rng);
                out(Eigen::Index(s), Eigen::Index(k)) = float(cos_theta * v);
            }
        });
        progress.update(1.0);
        return out;
    });
}

} // namespace penumbra::solver
