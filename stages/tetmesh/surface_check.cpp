#include "stages/tetmesh/surface_check.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace ligsim::tetmesh {
namespace {

std::uint64_t edge_key(int low, int high)
{
  return (static_cast<std::uint64_t>(low) << 32) | static_cast<std::uint32_t>(high);
}

std::string edge_location(const TriangleSurface& surface, std::uint64_t key)
{
  const int low = static_cast<int>(key >> 32);
  const int high = static_cast<int>(key & 0xffffffffu);
  const Eigen::RowVector3d mid = 0.5 * (surface.V.row(low) + surface.V.row(high));
  return fmt::format("vertices {} and {}, at ({:.3f}, {:.3f}, {:.3f}) mm", low, high, mid.x(),
                     mid.y(), mid.z());
}

void check_indices_and_coordinates(const TriangleSurface& surface)
{
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    if (!surface.V.row(v).allFinite())
      fail("surface vertex {} has a non-finite coordinate", v);
  const auto vertex_count = static_cast<int>(surface.V.rows());
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k)
      if (surface.F(f, k) < 0 || surface.F(f, k) >= vertex_count)
        fail("surface triangle {} has vertex index {} outside 0..{}", f, surface.F(f, k),
             vertex_count - 1);
    if (surface.F(f, 0) == surface.F(f, 1) || surface.F(f, 1) == surface.F(f, 2) ||
        surface.F(f, 2) == surface.F(f, 0))
      fail("surface triangle {} repeats a vertex ({}, {}, {})", f, surface.F(f, 0), surface.F(f, 1),
           surface.F(f, 2));
  }
}

} // namespace

void check_closed_surface(const TriangleSurface& surface)
{
  if (surface.F.rows() == 0 || surface.V.rows() == 0)
    fail("surface is empty ({} vertices, {} triangles): nothing to mesh", surface.V.rows(),
         surface.F.rows());
  check_indices_and_coordinates(surface);

  // Per undirected edge {low, high}: how many triangles traverse it as low->high and as
  // high->low. A closed, consistently oriented, edge-manifold surface has exactly one of each.
  struct EdgeUse {
    int forward = 0;
    int backward = 0;
    bool judged = false;
  };
  std::unordered_map<std::uint64_t, EdgeUse> uses;
  uses.reserve(static_cast<std::size_t>(2 * surface.F.rows()));
  const auto key_of = [&](Eigen::Index f, int k) {
    const int from = surface.F(f, k), to = surface.F(f, (k + 1) % 3);
    return std::pair{edge_key(std::min(from, to), std::max(from, to)), from < to};
  };
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto [key, forward] = key_of(f, k);
      ++(forward ? uses[key].forward : uses[key].backward);
    }

  // Judged in triangle order, so that "first" names the same edge on every run.
  int boundary = 0, non_manifold = 0, flipped = 0;
  std::uint64_t first_boundary = 0, first_non_manifold = 0, first_flipped = 0;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t key = key_of(f, k).first;
      EdgeUse& use = uses.at(key);
      if (use.judged)
        continue;
      use.judged = true;
      const int total = use.forward + use.backward;
      if (total == 1) {
        if (boundary++ == 0)
          first_boundary = key;
      } else if (total > 2) {
        if (non_manifold++ == 0)
          first_non_manifold = key;
      } else if (use.forward != 1) {
        if (flipped++ == 0)
          first_flipped = key;
      }
    }

  if (boundary > 0)
    fail("surface is open: {} boundary edges (used by one triangle only), the first between {}",
         boundary, edge_location(surface, first_boundary));
  if (non_manifold > 0)
    fail(
        "surface is non-manifold: {} edges shared by more than two triangles, the first between {}",
        non_manifold, edge_location(surface, first_non_manifold));
  if (flipped > 0)
    fail("surface is inconsistently oriented: {} edges where two triangles face opposite ways, "
         "the first between {}",
         flipped, edge_location(surface, first_flipped));
}

double signed_enclosed_volume_mm3(const TriangleSurface& surface)
{
  double six_volume = 0;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0));
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1));
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double surface_area_mm2(const TriangleSurface& surface)
{
  double twice_area = 0;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0));
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1));
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2));
    twice_area += (b - a).cross(c - a).norm();
  }
  return twice_area / 2.0;
}

} // namespace ligsim::tetmesh
