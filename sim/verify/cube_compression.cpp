#include "sim/verify/cube_compression.hpp"

#include "common/error.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <fmt/format.h>

#include <cmath>

namespace ligsim::sim {

std::vector<double> cube_compression_loads_n()
{
  return {0.02, 0.05, 0.10, 0.20};
}

std::vector<FebioCase> cube_compression_cases(const FebioReference& reference)
{
  const FebioCase* base[2] = {nullptr, nullptr}; // lnj, jm1
  for (const FebioCase& c : reference.cases)
    if (c.incompressibility == "penalty")
      base[c.material.volumetric == VolumetricLaw::lnj ? 0 : 1] = &c;
  if (!base[0] || !base[1])
    fail("{}: compression cases need a penalty case with each volumetric law (lnj and jm1)",
         (reference.directory / "cases.json").string());
  std::vector<FebioCase> cases;
  for (const char* direction : {"along", "across"})
    for (double load : cube_compression_loads_n())
      for (const FebioCase* b : base) {
        FebioCase c = *b;
        const bool lnj = c.material.volumetric == VolumetricLaw::lnj;
        c.name = fmt::format("cmp_{}_{:03d}_{}", direction,
                             static_cast<int>(std::lround(100 * load)), lnj ? "lnj" : "jm1");
        c.fiber =
            std::string(direction) == "along" ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
        c.force_per_top_node_n = Eigen::Vector3d(0, 0, -load);
        c.displacements.clear();
        c.febio = {};
        cases.push_back(c);
      }
  return cases;
}

FebioMesh structured_cube(int cells, double edge_mm)
{
  FebioMesh mesh;
  mesh.mesh = structured_cube_mesh(cells, edge_mm);
  const double tolerance = 1e-9 * edge_mm;
  mesh.bottom_nodes = nodes_on_plane(mesh.mesh.V, 2, 0.0, tolerance);
  mesh.top_nodes = nodes_on_plane(mesh.mesh.V, 2, edge_mm, tolerance);
  return mesh;
}

} // namespace ligsim::sim
