#include "sim/mesh/structured_mesh.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace ligsim::sim {

namespace {

double signed_volume(const Points& V, const std::array<int, 4>& tet)
{
  const Eigen::Vector3d a = V.row(tet[1]) - V.row(tet[0]);
  const Eigen::Vector3d b = V.row(tet[2]) - V.row(tet[0]);
  const Eigen::Vector3d c = V.row(tet[3]) - V.row(tet[0]);
  return a.dot(b.cross(c)) / 6.0;
}

/// Swaps two nodes of every negatively oriented tet.
void orient_positively(TetMesh& mesh)
{
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    const std::array<int, 4> tet = {mesh.T(e, 0), mesh.T(e, 1), mesh.T(e, 2), mesh.T(e, 3)};
    if (signed_volume(mesh.V, tet) < 0.0)
      std::swap(mesh.T(e, 2), mesh.T(e, 3));
  }
}

} // namespace

TetMesh structured_box_mesh(const Eigen::Vector3i& cells, const Eigen::Vector3d& size_mm)
{
  if ((cells.array() < 1).any())
    fail("a structured mesh needs at least one cell per axis, got {} x {} x {}", cells.x(),
         cells.y(), cells.z());
  if (!(size_mm.array() > 0.0).all())
    fail("a structured mesh needs a positive size, got {} x {} x {} mm", size_mm.x(), size_mm.y(),
         size_mm.z());
  const int nx = cells.x() + 1;
  const int ny = cells.y() + 1;
  const int nz = cells.z() + 1;
  auto index = [&](int i, int j, int k) { return i + nx * (j + ny * k); };

  TetMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(nx) * ny * nz, 3);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.V.row(index(i, j, k)) << size_mm.x() * i / cells.x(), size_mm.y() * j / cells.y(),
            size_mm.z() * k / cells.z();

  mesh.T.resize(5 * static_cast<Eigen::Index>(cells.prod()), 4);
  Eigen::Index e = 0;
  for (int k = 0; k < cells.z(); ++k)
    for (int j = 0; j < cells.y(); ++j)
      for (int i = 0; i < cells.x(); ++i) {
        auto corner = [&](int di, int dj, int dk) { return index(i + di, j + dj, k + dk); };
        const bool even = (i + j + k) % 2 == 0;
        // Corners of the central tet: those with even global parity. The four others each cut
        // off one corner of odd parity together with its three edge neighbours.
        std::array<std::array<int, 3>, 4> central;
        std::array<std::array<int, 3>, 4> cut;
        if (even) {
          central = {{{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}}};
          cut = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}};
        } else {
          central = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}};
          cut = {{{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}}};
        }
        for (int n = 0; n < 4; ++n)
          mesh.T(e, n) = corner(central[n][0], central[n][1], central[n][2]);
        ++e;
        for (const auto& c : cut) {
          mesh.T(e, 0) = corner(c[0], c[1], c[2]);
          mesh.T(e, 1) = corner(1 - c[0], c[1], c[2]);
          mesh.T(e, 2) = corner(c[0], 1 - c[1], c[2]);
          mesh.T(e, 3) = corner(c[0], c[1], 1 - c[2]);
          ++e;
        }
      }
  orient_positively(mesh);
  return mesh;
}

TetMesh structured_cube_mesh(int n, double edge_mm)
{
  return structured_box_mesh(Eigen::Vector3i::Constant(n), Eigen::Vector3d::Constant(edge_mm));
}

TetMesh bent_bar_mesh(const Eigen::Vector3i& cells, const Eigen::Vector3d& size_mm, double bend_deg)
{
  TetMesh mesh = structured_box_mesh(cells, size_mm);
  const double turn = bend_deg * M_PI / 180.0;
  if (std::abs(turn) > 1e-12) {
    // The bar's mid-surface z = thickness/2 becomes an arc of radius R = length / turn.
    const double radius = size_mm.x() / turn;
    for (Eigen::Index n = 0; n < mesh.V.rows(); ++n) {
      const double angle = mesh.V(n, 0) / radius;
      const double r = radius - (mesh.V(n, 2) - 0.5 * size_mm.z());
      mesh.V(n, 0) = r * std::sin(angle);
      mesh.V(n, 2) = radius - r * std::cos(angle);
    }
    orient_positively(mesh);
  }
  return mesh;
}

} // namespace ligsim::sim
