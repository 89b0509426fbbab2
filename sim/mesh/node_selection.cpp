#include "sim/mesh/node_selection.hpp"

#include <cmath>

namespace ligsim::sim {

std::vector<int> nodes_on_plane(const Points& V, int axis, double value_mm, double tolerance_mm)
{
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < V.rows(); ++n)
    if (std::abs(V(n, axis) - value_mm) <= tolerance_mm)
      nodes.push_back(static_cast<int>(n));
  return nodes;
}

std::vector<int> nodes_in_box(const Points& V, const Eigen::Vector3d& min_mm,
                              const Eigen::Vector3d& max_mm)
{
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < V.rows(); ++n) {
    const Eigen::Vector3d p = V.row(n).transpose();
    if ((p.array() >= min_mm.array()).all() && (p.array() <= max_mm.array()).all())
      nodes.push_back(static_cast<int>(n));
  }
  return nodes;
}

} // namespace ligsim::sim
