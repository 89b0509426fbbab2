#include "sim/flexion/ligament_pairs.hpp"

#include "common/atomic_file.hpp"
#include "common/progress.hpp"
#include "sim/contact/contact_surface.hpp"
#include "sim/contact/triangle_distance.hpp"
#include "sim/contact/winding_number.hpp"
#include "sim/flexion/flexion_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>

namespace ligsim::sim {

namespace {

/// A ligament's deformed boundary: its nodes and the queries against its triangles.
struct Boundary {
  std::vector<Eigen::Vector3d> nodes;
  std::unique_ptr<WindingNumber> winding;
  std::unique_ptr<TriangleDistance> distance;
};

Boundary boundary_of(const LigamentState& ligament)
{
  const ContactSurface surface = boundary_surface(*ligament.mesh);
  const Eigen::VectorXd& x = *ligament.x;
  TriangleSurface triangles;
  triangles.V.resize(x.size() / 3, 3);
  for (Eigen::Index n = 0; n < triangles.V.rows(); ++n)
    triangles.V.row(n) = x.segment<3>(3 * n).transpose();
  triangles.F = surface.faces;

  Boundary boundary;
  for (int n : surface.nodes)
    boundary.nodes.push_back(x.segment<3>(3 * n));
  boundary.winding = std::make_unique<WindingNumber>(triangles);
  boundary.distance = std::make_unique<TriangleDistance>(triangles);
  return boundary;
}

/// The nodes of `from` against the triangles of `to`.
void measure_into(const Boundary& from, const Boundary& to, LigamentPair& pair)
{
  for (const Eigen::Vector3d& p : from.nodes) {
    const double distance = (*to.distance)(p);
    const bool inside = to.winding->bounds().contains(p) && std::abs((*to.winding)(p)) >= 0.5;
    if (inside) {
      ++pair.nodes_inside;
      pair.deepest_mm = std::max(pair.deepest_mm, distance);
      pair.closest_mm = 0.0;
    } else {
      pair.closest_mm = std::min(pair.closest_mm, distance);
    }
  }
}

} // namespace

std::vector<LigamentPair> measure_pairs(const std::vector<LigamentState>& ligaments)
{
  std::vector<Boundary> boundaries;
  for (const LigamentState& ligament : ligaments)
    boundaries.push_back(boundary_of(ligament));
  std::vector<LigamentPair> pairs;
  for (std::size_t a = 0; a < ligaments.size(); ++a)
    for (std::size_t b = a + 1; b < ligaments.size(); ++b) {
      LigamentPair pair;
      pair.first = ligaments[a].name;
      pair.second = ligaments[b].name;
      measure_into(boundaries[a], boundaries[b], pair);
      measure_into(boundaries[b], boundaries[a], pair);
      pairs.push_back(pair);
    }
  return pairs;
}

std::vector<PairAtAngle>
pairs_over_sweep(const std::vector<LigamentModel>& ligaments,
                 const std::map<double, std::vector<Eigen::VectorXd>>& states,
                 const std::filesystem::path& out)
{
  std::vector<PairAtAngle> found;
  std::string csv = "angle_deg,first,second,closest_mm,nodes_inside,deepest_mm\n";
  for (const auto& [angle, x] : states) {
    if (x.size() != ligaments.size() ||
        std::any_of(x.begin(), x.end(), [](const Eigen::VectorXd& v) { return v.size() == 0; }))
      continue;
    std::vector<LigamentState> at_angle;
    for (std::size_t l = 0; l < ligaments.size(); ++l)
      at_angle.push_back({ligaments[l].name, &ligaments[l].model.mesh, &x[l]});
    for (const LigamentPair& pair : measure_pairs(at_angle)) {
      found.push_back({angle, pair});
      csv += fmt::format("{:g},{},{},{:.6g},{},{:.6g}\n", angle, pair.first, pair.second,
                         pair.closest_mm, pair.nodes_inside, pair.deepest_mm);
      if (pair.nodes_inside > 0)
        log_info(fmt::format("warning at {} deg: the {} and the {} interpenetrate ({} surface "
                             "nodes of one inside the other, up to {:.2f} mm deep; the "
                             "ligaments do not touch each other in the solve)",
                             angle_label(angle), pair.first, pair.second, pair.nodes_inside,
                             pair.deepest_mm));
    }
  }
  write_text_atomically(out / "pairs.csv", csv);
  return found;
}

} // namespace ligsim::sim
