// Kernels of the IGA module (iga/): basis tabulation per element, element residual + tangent by
// degree p = 1..4 for both formulations, and the material update at one quadrature point.
// Run: build/<dir>/bench/bench_iga [--benchmark_filter=...]. Times are per element (tabulation,
// kernels) or per point (material update).
#include <benchmark/benchmark.h>

#include <cmath>

#include "geometry/knot_vector.hpp"
#include "geometry/nurbs_volume.hpp"
#include "geometry/refinement.hpp"
#include "iga/element_kernels.hpp"
#include "iga/fibre_directions.hpp"
#include "iga/pressure_space.hpp"
#include "iga/space.hpp"
#include "materials/material_factory.hpp"

namespace {

using namespace isomuscle;

// A 1 cm block of degree p with n^3 elements, interior control points moved slightly and weights
// varied (a rational, non-affine map like a real muscle solid).
geometry::NurbsVolume block(int p, int n) {
  std::array<geometry::KnotVector, 3> kv = {geometry::KnotVector::clamped(1, {}),
                                            geometry::KnotVector::clamped(1, {}),
                                            geometry::KnotVector::clamped(1, {})};
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) {
        pts.emplace_back(0.01 * i, 0.01 * j, 0.01 * k);
      }
    }
  }
  geometry::NurbsVolume v(kv, pts, std::vector<double>(8, 1.0));
  v = geometry::elevate_to(v, {p, p, p});
  v = geometry::refine_uniform(v, {n - 1, n - 1, n - 1});
  std::vector<Eigen::Vector3d> moved = v.points();
  std::vector<double> w = v.weights();
  for (std::size_t i = 0; i < moved.size(); ++i) {
    moved[i] += 2e-5 * Eigen::Vector3d(std::sin(1.3 * i), std::cos(0.7 * i), std::sin(0.4 * i));
    w[i] = 1.0 + 0.1 * std::sin(0.9 * i);
  }
  return geometry::NurbsVolume(v.all_knots(), moved, w);
}

// Tabulation of R, dR/dX, dV, J, X per element (Space construction / element count).
void BM_BasisTabulation(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const geometry::NurbsVolume v = block(p, 4);
  int elements = 0;
  for (auto _ : state) {
    const iga::Space space(v);
    elements = space.num_elements();
    benchmark::DoNotOptimize(space.dv(0, 0));
  }
  state.SetItemsProcessed(state.iterations() * elements);
  state.counters["us_per_element"] = benchmark::Counter(
      static_cast<double>(elements),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_BasisTabulation)->DenseRange(1, 4)->Unit(benchmark::kMillisecond);

// One element's residual and tangent: range(0) = p, range(1) = 0 displacement / 1 mixed,
// range(2) = 0 neo_hookean / 1 tang2009 (active).
void BM_ElementResidualTangent(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const bool mixed = state.range(1) == 1;
  const bool muscle = state.range(2) == 1;
  const geometry::NurbsVolume v = block(p, 1);
  const iga::Space space(v);
  const auto law =
      muscle ? materials::make_material("tang2009") : materials::make_material("neo_hookean");
  const std::vector<Eigen::Vector3d> fibres =
      iga::fibre_directions(space, iga::FibreSpec::isocurve(0));
  const int nqp = space.points_per_element();
  const int hs = law->history_size();
  std::vector<double> committed(static_cast<std::size_t>(nqp) * hs), trial(committed.size());
  for (int q = 0; q < nqp; ++q) {
    law->initial_history(std::span<double>(committed.data() + q * hs, hs));
  }
  iga::PressureSpace pressure(space, 0);
  iga::ElementWorkspace ws(space.functions_per_element(), nqp, 1);
  for (int a = 0; a < space.functions_per_element(); ++a) {
    ws.ue.col(a) = 1e-4 * Eigen::Vector3d(std::sin(a), std::cos(2.0 * a), 0.5 * std::sin(3.0 * a));
  }
  iga::MaterialContext ctx;
  ctx.law = law.get();
  ctx.fibres = fibres.data();
  ctx.time = 0.05;
  ctx.dt = 0.01;
  ctx.history_committed = hs > 0 ? committed.data() : nullptr;
  ctx.history_trial = hs > 0 ? trial.data() : nullptr;
  const iga::ElementView view = iga::element_view(space, 0);
  for (auto _ : state) {
    const iga::KernelStatus s = mixed ? iga::mixed_kernel(view, ctx, pressure, 0, nullptr, true, ws)
                                      : iga::displacement_kernel(view, ctx, true, ws);
    if (!s.ok()) {
      state.SkipWithError("kernel failed");
      break;
    }
    benchmark::DoNotOptimize(ws.ke.data());
  }
  state.counters["dofs"] = 3.0 * space.functions_per_element();
  state.counters["points"] = nqp;
}
BENCHMARK(BM_ElementResidualTangent)
    ->ArgsProduct({{1, 2, 3, 4}, {0, 1}, {0, 1}})
    ->ArgNames({"p", "mixed", "muscle"})
    ->Unit(benchmark::kMicrosecond);

// One material point: S and tangent (range 0: 0 neo_hookean, 1 tang2009, 2 lu2010; both Hill laws
// active with a stretched fibre).
void BM_MaterialUpdate(benchmark::State& state) {
  const char* names[3] = {"neo_hookean", "tang2009", "lu2010"};
  const auto law = materials::make_material(names[state.range(0)]);
  std::vector<double> committed(law->history_size()), trial(law->history_size());
  law->initial_history(committed);
  materials::PointInput in;
  in.F << 1.04, 0.01, 0.0, 0.0, 0.98, 0.005, 0.0, 0.0, 0.985;
  in.fibre = Eigen::Vector3d::UnitX();
  in.time = 0.05;
  in.dt = 0.01;
  in.history = committed;
  materials::PointResult out;
  out.history = trial;
  for (auto _ : state) {
    benchmark::DoNotOptimize(law->evaluate(in, out, true));
    benchmark::DoNotOptimize(out.tangent.data());
  }
  state.SetLabel(names[state.range(0)]);
}
BENCHMARK(BM_MaterialUpdate)->DenseRange(0, 2)->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
