#include "sim/membrane/crack/tearing.hpp"

#include "common/error.hpp"
#include "sim/membrane/crack/direction_search.hpp"
#include "sim/membrane/mesh/topology.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

namespace ligsim::membrane {
namespace {

Vec2 fiber_of(const MembraneMesh& mesh, int tri)
{
  return {std::cos(mesh.fiber_angle_rad[tri]), std::sin(mesh.fiber_angle_rad[tri])};
}

Vec2 centroid(const MembraneMesh& mesh, int tri)
{
  const Triangle& t = mesh.triangles[tri];
  return (mesh.rest[t[0]] + mesh.rest[t[1]] + mesh.rest[t[2]]) / 3.0;
}

/// A candidate event: a tip (index into the tips) or an element centre.
struct Candidate {
  double value = 0.0;
  Vec2 direction = Vec2::UnitX();
  int tip = -1;
  int element = -1;
};

} // namespace

void validate(const TearSettings& s, const char* where)
{
  const TearThresholds& t = s.thresholds;
  if (!(t.fiber_mpa > 0.0) || !(t.transverse_mpa > 0.0))
    fail("{}: the thresholds must be positive (fiber {} MPa, transverse {} MPa)", where,
         t.fiber_mpa, t.transverse_mpa);
  if (!(t.steepness > 0.0) || !std::isfinite(t.steepness))
    fail("{}: steepness alpha must be positive, got {}", where, t.steepness);
  if (!(t.max_turn_rad > 0.0) || t.max_turn_rad > M_PI + 1e-12)
    fail("{}: max_turn_deg must be in (0, 180], got {}", where, t.max_turn_rad * 180.0 / M_PI);
  if (!(s.propagation.min_angle_rad >= 0.0) || s.propagation.min_angle_rad >= M_PI / 6.0)
    fail("{}: min_angle_deg must be in [0, 30), got {}", where,
         s.propagation.min_angle_rad * 180.0 / M_PI);
  if (!(s.propagation.min_area_mm2 >= 0.0))
    fail("{}: min_area_mm2 must not be negative", where);
  if (s.max_events_per_step < 1)
    fail("{}: max_events_per_step must be at least 1, got {}", where, s.max_events_per_step);
}

void apply_edit(MembraneMesh& mesh, CorotationalElements& elements, const TopologyEdit& edit,
                double areal_density_t_per_mm2)
{
  for (std::size_t i = 0; i < edit.triangles.size(); ++i)
    elements.refresh(mesh, edit.triangles[i], edit.parents[i]);
  std::vector<int> nodes = edit.split_nodes;
  for (int tri : edit.triangles)
    nodes.insert(nodes.end(), mesh.triangles[tri].begin(), mesh.triangles[tri].end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  update_lumped_masses(mesh, build_incidence(mesh), areal_density_t_per_mm2, nodes);
}

int Tearing::add_tip(int node, const Vec2& previous)
{
  m_tips.push_back({node, previous.normalized(), m_next_tip_id});
  return m_next_tip_id++;
}

std::pair<Eigen::Vector3d, Vec2> Tearing::tip_state(const MembraneMesh& mesh,
                                                    const CorotationalElements& elements,
                                                    const NodeIncidence& incidence, int node) const
{
  Eigen::Vector3d stress = Eigen::Vector3d::Zero();
  Vec2 doubled = Vec2::Zero();
  double total = 0.0;
  for (const int* tri = incidence.begin(node); tri != incidence.end(node); ++tri) {
    const double area = rest_area(mesh, *tri);
    stress += area * elements.stress(*tri);
    const double angle = mesh.fiber_angle_rad[*tri];
    doubled += area * Vec2(std::cos(2.0 * angle), std::sin(2.0 * angle));
    total += area;
  }
  const double fiber_angle = 0.5 * std::atan2(doubled.y(), doubled.x());
  return {stress / total, Vec2(std::cos(fiber_angle), std::sin(fiber_angle))};
}

std::vector<double> Tearing::element_criterion(const MembraneMesh& mesh,
                                               const CorotationalElements& elements) const
{
  std::vector<double> values(mesh.triangle_count());
  for (int tri = 0; tri < mesh.triangle_count(); ++tri)
    values[tri] = best_tear_direction(m_settings.thresholds, elements.stress(tri),
                                      fiber_of(mesh, tri), std::nullopt)
                      .value;
  return values;
}

std::vector<TearEvent> Tearing::step(MembraneMesh& mesh, CorotationalElements& elements,
                                     double areal_density_t_per_mm2)
{
  const TearThresholds& thresholds = m_settings.thresholds;
  NodeIncidence incidence = build_incidence(mesh);
  std::vector<Candidate> candidates;
  for (int i = 0; i < static_cast<int>(m_tips.size()); ++i) {
    const auto [stress, fiber] = tip_state(mesh, elements, incidence, m_tips[i].node);
    const TearDirection best = best_tear_direction(thresholds, stress, fiber, m_tips[i].previous);
    if (best.value > 1.0)
      candidates.push_back({best.value, best.direction, i, -1});
  }
  if (m_settings.initiation) {
    std::vector<bool> on_crack(mesh.node_count(), false);
    for (int tri = 0; tri < mesh.triangle_count(); ++tri)
      for (int k = 0; k < 3; ++k)
        if (mesh.side_cut[tri][k]) {
          on_crack[mesh.triangles[tri][k]] = true;
          on_crack[mesh.triangles[tri][(k + 1) % 3]] = true;
        }
    // c <= largest principal stress / smallest threshold, then c on a coarse grid: only the
    // elements within 5 % of tearing get the full search, the best first, until the step's
    // events are found.
    const double lowest = std::min(thresholds.fiber_mpa, thresholds.transverse_mpa);
    const double clearance2 =
        m_settings.initiation_clearance_mm * m_settings.initiation_clearance_mm;
    std::vector<std::pair<double, int>> screened;
    for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
      const Triangle& t = mesh.triangles[tri];
      if (on_crack[t[0]] || on_crack[t[1]] || on_crack[t[2]])
        continue;
      if (largest_principal_stress(elements.stress(tri)).first <= lowest)
        continue;
      const Vec2 centre = centroid(mesh, tri);
      if (std::any_of(m_tips.begin(), m_tips.end(), [&](const CrackTip& tip) {
            return (mesh.rest[tip.node] - centre).squaredNorm() < clearance2;
          }))
        continue;
      const double estimate =
          screen_tear_value(thresholds, elements.stress(tri), fiber_of(mesh, tri));
      if (estimate > 0.95)
        screened.emplace_back(estimate, tri);
    }
    std::sort(screened.begin(), screened.end(), std::greater<>());
    int found = 0;
    for (const auto& [estimate, tri] : screened) {
      if (found >= m_settings.max_events_per_step)
        break;
      const TearDirection best =
          best_tear_direction(thresholds, elements.stress(tri), fiber_of(mesh, tri), std::nullopt);
      if (best.value > 1.0) {
        candidates.push_back({best.value, best.direction, -1, tri});
        ++found;
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.value > b.value; });

  std::vector<TearEvent> events;
  std::vector<CrackTip> new_tips;
  std::set<int> changed; // triangles rewritten this step: their stresses are stale
  bool initiated = false;
  for (const Candidate& candidate : candidates) {
    if (static_cast<int>(events.size()) >= m_settings.max_events_per_step)
      break;
    if (candidate.tip >= 0) {
      CrackTip& tip = m_tips[candidate.tip];
      if (!is_enclosed(mesh, build_incidence(mesh), tip.node)) {
        tip.node = -1; // an earlier event of this step reached this tip
        continue;
      }
      const auto advance =
          advance_crack(mesh, tip.node, candidate.direction, m_settings.propagation);
      if (!advance) {
        tip.node = -1; // the crack cannot go on from here
        continue;
      }
      apply_edit(mesh, elements, advance->edit, areal_density_t_per_mm2);
      changed.insert(advance->edit.triangles.begin(), advance->edit.triangles.end());
      events.push_back({false, tip.id, candidate.value, advance->from_rest, advance->to_rest,
                        advance->split_face});
      if (advance->continues)
        tip = {advance->to, (advance->to_rest - advance->from_rest).normalized(), tip.id};
      else
        tip.node = -1;
    } else {
      if (initiated || changed.count(candidate.element))
        continue;
      const auto advances =
          initiate_crack(mesh, candidate.element, candidate.direction, m_settings.propagation);
      if (advances.empty())
        continue;
      initiated = true;
      const int first_id = m_next_tip_id;
      for (const CrackAdvance& advance : advances) {
        apply_edit(mesh, elements, advance.edit, areal_density_t_per_mm2);
        changed.insert(advance.edit.triangles.begin(), advance.edit.triangles.end());
        if (advance.continues)
          new_tips.push_back(
              {advance.to, (advance.to_rest - advance.from_rest).normalized(), m_next_tip_id++});
      }
      // The new crack runs from the end of one advance to the end of the other.
      const Vec2 from = advances.size() > 1 ? advances.back().to_rest : advances.front().from_rest;
      events.push_back({true, first_id, candidate.value, from, advances.front().to_rest,
                        advances.front().split_face});
    }
  }

  // Keep the tips that are still inside the material (another crack may have reached one).
  m_tips.insert(m_tips.end(), new_tips.begin(), new_tips.end());
  incidence = build_incidence(mesh);
  m_tips.erase(std::remove_if(m_tips.begin(), m_tips.end(),
                              [&](const CrackTip& tip) {
                                return tip.node < 0 || !is_enclosed(mesh, incidence, tip.node);
                              }),
               m_tips.end());
  return events;
}

} // namespace ligsim::membrane
