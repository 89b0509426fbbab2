// The independent penetration check of knee flexion (sim/contact/bone_penetration) per ligament
// node, against the check before it (VTK's vtkImplicitPolyDataDistance, signed by the nearest
// triangle's normal) and the exact winding number (every triangle). Bones: 0, the VHF tibia
// (60,362 triangles, data/vhf-right-knee) with the VHF MCL's vertices; 1, the HRA female tibia
// (3,490 triangles, data/hra-knee) with the HRA female MCL's. Nodes: the MCL's vertices and
// copies of them moved up to 3 mm, 5,000 in all, as a sweep checks at every angle.
// Run with --benchmark_repetitions=5 on a shared machine and compare medians.

#include "sim/contact/bone_penetration.hpp"
#include "stages/io/surface_reader.hpp"

#include <benchmark/benchmark.h>
#include <vtkCellArray.h>
#include <vtkImplicitPolyDataDistance.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <filesystem>
#include <random>

using namespace ligsim;
using namespace ligsim::sim;

namespace {

struct Case {
  TriangleSurface bone;
  std::vector<Eigen::Vector3d> nodes;
};

const Case& bench_case(int which)
{
  static const Case cases[2] = {
      [] {
        const std::filesystem::path dir = std::filesystem::path(LIGSIM_SOURCE_DIR) / "data";
        Case c{io::read_surface(dir / "vhf-right-knee/VHF_Right_Bone_Tibia_smooth.stl"), {}};
        const TriangleSurface mcl =
            io::read_surface(dir / "vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl");
        std::mt19937 random(1);
        std::uniform_real_distribution<double> jitter(-3.0, 3.0);
        while (c.nodes.size() < 5000)
          for (Eigen::Index v = 0; v < mcl.V.rows() && c.nodes.size() < 5000; ++v)
            c.nodes.push_back(mcl.V.row(v).transpose() +
                              Eigen::Vector3d(jitter(random), jitter(random), jitter(random)));
        return c;
      }(),
      [] {
        const std::filesystem::path dir = std::filesystem::path(LIGSIM_SOURCE_DIR) / "data";
        Case c{io::read_surface(dir / "hra-knee/VH_F_Knee_L.glb#VH_F_tibia_L"), {}};
        const TriangleSurface mcl = io::read_surface(
            dir / "hra-knee/VH_F_Ligaments_Knee_L.glb#VH_F_left_tibial_collateral_ligament");
        std::mt19937 random(1);
        std::uniform_real_distribution<double> jitter(-3.0, 3.0);
        while (c.nodes.size() < 5000)
          for (Eigen::Index v = 0; v < mcl.V.rows() && c.nodes.size() < 5000; ++v)
            c.nodes.push_back(mcl.V.row(v).transpose() +
                              Eigen::Vector3d(jitter(random), jitter(random), jitter(random)));
        return c;
      }()};
  return cases[which];
}

void BM_WindingNumberPenetration(benchmark::State& state)
{
  const Case& c = bench_case(static_cast<int>(state.range(0)));
  const BonePenetration check(c.bone);
  double deepest = 0.0;
  for (auto _ : state)
    for (const Eigen::Vector3d& p : c.nodes)
      deepest = std::max(deepest, check.depth_mm(p));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(c.nodes.size()));
  state.counters["triangles"] = static_cast<double>(c.bone.F.rows());
  state.counters["deepest_mm"] = deepest;
}
BENCHMARK(BM_WindingNumberPenetration)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_NormalSignPenetration(benchmark::State& state)
{
  const Case& c = bench_case(static_cast<int>(state.range(0)));
  auto points = vtkSmartPointer<vtkPoints>::New();
  for (Eigen::Index v = 0; v < c.bone.V.rows(); ++v)
    points->InsertNextPoint(c.bone.V(v, 0), c.bone.V(v, 1), c.bone.V(v, 2));
  auto triangles = vtkSmartPointer<vtkCellArray>::New();
  for (Eigen::Index f = 0; f < c.bone.F.rows(); ++f) {
    const vtkIdType corners[3] = {c.bone.F(f, 0), c.bone.F(f, 1), c.bone.F(f, 2)};
    triangles->InsertNextCell(3, corners);
  }
  auto polydata = vtkSmartPointer<vtkPolyData>::New();
  polydata->SetPoints(points);
  polydata->SetPolys(triangles);
  auto distance = vtkSmartPointer<vtkImplicitPolyDataDistance>::New();
  distance->SetInput(polydata);
  double deepest = 0.0;
  for (auto _ : state)
    for (const Eigen::Vector3d& p : c.nodes) {
      double xyz[3] = {p.x(), p.y(), p.z()};
      deepest = std::max(deepest, -distance->EvaluateFunction(xyz));
    }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(c.nodes.size()));
  state.counters["deepest_mm"] = deepest;
}
BENCHMARK(BM_NormalSignPenetration)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/// The winding number alone, hierarchical (accuracy 2) or over every triangle (the first 100
/// nodes only: items per second compare).
void BM_WindingNumber(benchmark::State& state)
{
  const Case& c = bench_case(static_cast<int>(state.range(0)));
  const bool exact = state.range(1) != 0;
  const WindingNumber w(c.bone);
  const std::size_t count = exact ? 100 : c.nodes.size();
  double sum = 0.0;
  for (auto _ : state)
    for (std::size_t i = 0; i < count; ++i)
      sum += exact ? w.exact(c.nodes[i]) : w(c.nodes[i]);
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations() * static_cast<long>(count));
}
BENCHMARK(BM_WindingNumber)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
