#include "sim/contact/contact_surface.hpp"

#include "common/tet_faces.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <map>
#include <utility>

namespace ligsim::sim {

namespace {

/// Each face split into four at the mid-edge nodes of `tet10`, in the face's orientation.
std::vector<std::array<int, 3>> split_at_mid_edges(const std::vector<std::array<int, 3>>& faces,
                                                   const QuadraticTetrahedra& tet10)
{
  std::map<std::pair<int, int>, int> middle;
  for (Eigen::Index e = 0; e < tet10.rows(); ++e)
    for (int k = 0; k < 6; ++k) {
      const int a = tet10(e, kQuadraticTetEdges[static_cast<std::size_t>(k)][0]);
      const int b = tet10(e, kQuadraticTetEdges[static_cast<std::size_t>(k)][1]);
      middle[std::minmax(a, b)] = tet10(e, 4 + k);
    }
  std::vector<std::array<int, 3>> split;
  for (const auto& [a, b, c] : faces) {
    const int ab = middle.at(std::minmax(a, b));
    const int bc = middle.at(std::minmax(b, c));
    const int ca = middle.at(std::minmax(c, a));
    split.insert(split.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
  }
  return split;
}

} // namespace

ContactSurface boundary_surface(const TetMesh& mesh, const QuadraticTetrahedra* tet10)
{
  std::vector<std::array<int, 3>> boundary = tet_boundary_faces(mesh.T);
  if (tet10)
    boundary = split_at_mid_edges(boundary, *tet10);
  ContactSurface surface;
  std::vector<double> area(static_cast<std::size_t>(mesh.V.rows()), 0.0);
  for (const std::array<int, 3>& f : boundary) {
    const Eigen::Vector3d a = mesh.V.row(f[0]).transpose();
    const Eigen::Vector3d b = mesh.V.row(f[1]).transpose();
    const Eigen::Vector3d c = mesh.V.row(f[2]).transpose();
    const double third = 0.5 * (b - a).cross(c - a).norm() / 3.0;
    for (int n : f)
      area[static_cast<std::size_t>(n)] += third;
  }
  surface.faces.resize(static_cast<Eigen::Index>(boundary.size()), 3);
  for (std::size_t f = 0; f < boundary.size(); ++f)
    for (int i = 0; i < 3; ++i)
      surface.faces(static_cast<Eigen::Index>(f), i) = boundary[f][static_cast<std::size_t>(i)];
  std::vector<double> areas;
  for (std::size_t n = 0; n < area.size(); ++n)
    if (area[n] > 0.0) {
      surface.nodes.push_back(static_cast<int>(n));
      areas.push_back(area[n]);
    }
  surface.areas_mm2 =
      Eigen::Map<Eigen::VectorXd>(areas.data(), static_cast<Eigen::Index>(areas.size()));
  return surface;
}

ContactSurface free_boundary_surface(const TetMesh& mesh, const BoundaryConditions& conditions,
                                     const QuadraticTetrahedra* tet10)
{
  const ContactSurface all = boundary_surface(mesh, tet10);
  std::vector<bool> held(static_cast<std::size_t>(mesh.V.rows()), false);
  for (const ConstraintSet& set : conditions.constraints)
    if (set.components[0] && set.components[1] && set.components[2])
      for (int n : set.nodes)
        if (n >= 0 && n < mesh.V.rows())
          held[static_cast<std::size_t>(n)] = true;
  ContactSurface free;
  free.faces = all.faces;
  std::vector<double> areas;
  for (std::size_t i = 0; i < all.nodes.size(); ++i)
    if (!held[static_cast<std::size_t>(all.nodes[i])]) {
      free.nodes.push_back(all.nodes[i]);
      areas.push_back(all.areas_mm2(static_cast<Eigen::Index>(i)));
    }
  free.areas_mm2 =
      Eigen::Map<Eigen::VectorXd>(areas.data(), static_cast<Eigen::Index>(areas.size()));
  return free;
}

} // namespace ligsim::sim
