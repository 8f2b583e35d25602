// Micro-benchmarks of the analytic form-factor kernels.

#include <benchmark/benchmark.h>

#include "kernels/form_factor.h"

namespace {

using namespace penumbra;

void BM_PointTriangleFormFactor(benchmark::State& state) {
    std::array<Vec3, 3> tri{Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1.2)};
    Vec3 x(0.2, 0.3, 0), n(0, 0, 1);
    for (auto _ : state) {
        benchmark::DoNotOptimize(solver::form_factor_point_triangle(x, n, tri));
        x.x += 1e-9;
    }
}
BENCHMARK(BM_PointTriangleFormFactor);

void BM_SolidAngleTriangle(benchmark::State& state) {
    std::array<Vec3, 3> tri{Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1.2)};
    Vec3 x(0.2, 0.3, 0);
    for (auto _ : state) {
        benchmark::DoNotOptimize(solver::solid_angle_triangle(x, tri));
        x.x += 1e-9;
    }
}
BENCHMARK(BM_SolidAngleTriangle);

} // namespace
