#include "sim/membrane/scene/tear_simulation.hpp"

#include "common/error.hpp"
#include "sim/membrane/mesh/generate.hpp"
#include "sim/membrane/mesh/topology.hpp"
#include "sim/membrane/scene/tear_metrics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace ligsim::membrane {
namespace {

MembraneMesh generate(const MeshSpec& spec)
{
  if (spec.shape == MeshSpec::Shape::rectangle)
    return rectangle_mesh(spec.width_mm, spec.height_mm, spec.element_size_mm, spec.jitter,
                          spec.seed);
  return disc_mesh(spec.radius_mm, spec.element_size_mm, spec.jitter, spec.seed);
}

void assign_fibers(const Scene& scene, MembraneMesh& mesh)
{
  const FiberSpec& fibers = scene.fibers;
  if (fibers.kind == FiberSpec::Kind::per_element &&
      static_cast<int>(fibers.angles_rad.size()) != mesh.triangle_count())
    fail("{}: the fiber file holds {} angles but the mesh has {} triangles", scene.source.string(),
         fibers.angles_rad.size(), mesh.triangle_count());
  for (int tri = 0; tri < mesh.triangle_count(); ++tri) {
    const Triangle& t = mesh.triangles[tri];
    const Vec2 centre = (mesh.rest[t[0]] + mesh.rest[t[1]] + mesh.rest[t[2]]) / 3.0;
    switch (fibers.kind) {
    case FiberSpec::Kind::uniform:
      mesh.fiber_angle_rad[tri] = fibers.angle_rad;
      break;
    case FiberSpec::Kind::concentric: {
      const Vec2 radial = centre - fibers.centre_mm;
      mesh.fiber_angle_rad[tri] = std::atan2(radial.y(), radial.x()) + M_PI / 2.0;
      break;
    }
    case FiberSpec::Kind::per_element:
      mesh.fiber_angle_rad[tri] = fibers.angles_rad[tri];
      break;
    }
  }
}

double areal_density(const MembraneMaterial& material)
{
  return material.density_t_per_mm3 * material.thickness_mm;
}

} // namespace

TearSimulation::TearSimulation(const Scene& scene)
    : m_scene(scene)
    , m_mesh(generate(scene.mesh))
    , m_elements(scene.material)
    , m_solver(scene.solver)
    , m_tearing(scene.tearing)
{
  const std::string where = scene.source.string();
  assign_fibers(scene, m_mesh);

  const double smallest = min_rest_angle(m_mesh);
  if (smallest < scene.tearing.propagation.min_angle_rad)
    fail("{}: the generated mesh has a {:.1f} degree angle, below min_angle_deg {:.1f}; use a "
         "smaller jitter or min_angle_deg",
         where, smallest * 180.0 / M_PI, scene.tearing.propagation.min_angle_rad * 180.0 / M_PI);

  for (std::size_t i = 0; i < scene.fixed.size(); ++i) {
    int count = 0;
    for (int v = 0; v < m_mesh.node_count(); ++v)
      if (scene.fixed[i].region.contains(m_mesh.rest[v])) {
        m_mesh.constraint[v] = NodeConstraint::prescribed;
        m_mesh.prescribed_velocity[v] = scene.fixed[i].velocity_mm_per_s;
        ++count;
      }
    if (count == 0)
      fail("{}: [[fixed]] #{} contains no node", where, i + 1);
  }

  const NodeIncidence incidence = build_incidence(m_mesh);
  m_traction_length_mm.assign(scene.tractions.size(), 0.0);
  for (std::size_t i = 0; i < scene.tractions.size(); ++i) {
    const Region& region = scene.tractions[i].region;
    for (int tri = 0; tri < m_mesh.triangle_count(); ++tri)
      for (int k = 0; k < 3; ++k) {
        const Vec2& a = m_mesh.rest[m_mesh.triangles[tri][k]];
        const Vec2& b = m_mesh.rest[m_mesh.triangles[tri][(k + 1) % 3]];
        if (region.contains(a) && region.contains(b) &&
            !opposite_side(m_mesh, incidence, {tri, k})) {
          m_mesh.side_load[tri][k] = static_cast<std::uint8_t>(i + 1);
          m_traction_length_mm[i] += (b - a).norm();
        }
      }
    if (m_traction_length_mm[i] == 0.0)
      fail("{}: [[traction]] #{} contains no boundary side", where, i + 1);
  }

  m_elements.rebuild(m_mesh);
  std::vector<int> all(m_mesh.node_count());
  for (int v = 0; v < m_mesh.node_count(); ++v)
    all[v] = v;
  update_lumped_masses(m_mesh, incidence, areal_density(scene.material), all);

  for (const CutSpec& spec : scene.cuts) {
    const PolylineCut cut = cut_polyline(m_mesh, spec.points_mm, scene.tearing.propagation);
    for (const CrackAdvance& advance : cut.advances)
      apply_edit(m_mesh, m_elements, advance.edit, areal_density(scene.material));
    if (spec.tear_from_end && cut.end_node >= 0) {
      const int id = m_tearing.add_tip(cut.end_node, cut.end_direction);
      if (m_lead_tip < 0)
        m_lead_tip = id;
    }
    if (spec.tear_from_start && cut.start_node >= 0) {
      const int id = m_tearing.add_tip(cut.start_node, cut.start_direction);
      if (m_lead_tip < 0)
        m_lead_tip = id;
    }
  }
  if (scene.grasp && m_lead_tip < 0)
    fail("{}: [grasp] needs a [[cut]] whose end is a crack tip", where);
  m_metrics.initial_elements = m_mesh.triangle_count();
  m_metrics.min_angle_rad = min_rest_angle(m_mesh);
}

double TearSimulation::current_load_n() const
{
  if (m_scene.grasp)
    return std::min(m_scene.grasp->force_rate_n_per_s * m_time_s, m_scene.grasp->max_force_n);
  if (m_scene.tractions.empty())
    return 0.0;
  const TractionSpec& traction = m_scene.tractions.front();
  return std::min(traction.rate_n_per_mm_per_s * m_time_s, traction.max_n_per_mm) *
         m_traction_length_mm.front();
}

void TearSimulation::add_grasp_force(std::vector<Vec2>& forces) const
{
  const auto& tips = m_tearing.tips();
  const auto lead = std::find_if(tips.begin(), tips.end(),
                                 [&](const CrackTip& tip) { return tip.id == m_lead_tip; });
  if (lead == tips.end())
    return;
  const GraspSpec& grasp = *m_scene.grasp;
  const Vec2 tip = m_mesh.rest[lead->node];
  const double tip_radius = (tip - grasp.centre_mm).norm();
  // The flap: triangles behind the tip, on the inner side, within the grasp radius.
  std::vector<int> flap;
  double flap_area = 0.0;
  for (int tri = 0; tri < m_mesh.triangle_count(); ++tri) {
    const Triangle& t = m_mesh.triangles[tri];
    const Vec2 centre = (m_mesh.rest[t[0]] + m_mesh.rest[t[1]] + m_mesh.rest[t[2]]) / 3.0;
    if ((centre - tip).norm() <= grasp.radius_mm && (centre - tip).dot(lead->previous) < 0.0 &&
        (centre - grasp.centre_mm).norm() < tip_radius) {
      flap.push_back(tri);
      flap_area += rest_area(m_mesh, tri);
    }
  }
  if (flap.empty())
    return;
  // The tear direction turned towards the centre by the inward angle.
  Vec2 inward = grasp.centre_mm - tip;
  inward -= inward.dot(lead->previous) * lead->previous;
  const Vec2 side = inward.norm() > 0.0 ? inward.normalized() : Vec2::Zero();
  const Vec2 direction =
      std::cos(grasp.inward_rad) * lead->previous + std::sin(grasp.inward_rad) * side;
  const Vec2 force = current_load_n() * direction;
  for (int tri : flap) {
    const Vec2 share = force * rest_area(m_mesh, tri) / (3.0 * flap_area);
    for (int v : m_mesh.triangles[tri])
      forces[v] += share;
  }
}

std::vector<Vec2> TearSimulation::external_forces() const
{
  std::vector<Vec2> forces(m_mesh.node_count(), Vec2::Zero());
  for (int tri = 0; tri < m_mesh.triangle_count(); ++tri)
    for (int k = 0; k < 3; ++k) {
      const int group = m_mesh.side_load[tri][k];
      if (group == 0)
        continue;
      const TractionSpec& traction = m_scene.tractions[group - 1];
      const double per_length =
          std::min(traction.rate_n_per_mm_per_s * m_time_s, traction.max_n_per_mm);
      const int a = m_mesh.triangles[tri][k], b = m_mesh.triangles[tri][(k + 1) % 3];
      const Vec2 half =
          0.5 * per_length * (m_mesh.rest[b] - m_mesh.rest[a]).norm() * traction.direction;
      forces[a] += half;
      forces[b] += half;
    }
  if (m_scene.grasp)
    add_grasp_force(forces);
  return forces;
}

void TearSimulation::step()
{
  const auto start = std::chrono::steady_clock::now();
  m_time_s += m_scene.solver.time_step_s;
  if (m_hand)
    m_hand->apply(m_mesh, m_scene.solver.time_step_s);
  const SolveReport solve = m_solver.step(m_mesh, m_elements, external_forces());
  const std::vector<TearEvent> events =
      m_tearing.step(m_mesh, m_elements, areal_density(m_scene.material));
  const auto stop = std::chrono::steady_clock::now();

  ++m_metrics.steps;
  m_metrics.step_ms.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
  m_metrics.cg_iterations.push_back(solve.iterations);
  for (const TearEvent& event : events) {
    const RecordedEvent recorded{event, m_metrics.steps, current_load_n()};
    if (!m_metrics.onset)
      m_metrics.onset = recorded;
    m_metrics.events.push_back(recorded);
    ++m_metrics.propagation_events;
    m_metrics.initiations += event.initiation;
    m_metrics.face_splits += event.split_face;
    if (event.tip_id == m_lead_tip && !event.initiation && m_scene.run.centre_mm) {
      const Vec2 from = event.from_rest - *m_scene.run.centre_mm;
      const Vec2 to = event.to_rest - *m_scene.run.centre_mm;
      m_metrics.turned_rad += std::atan2(cross(from, to), from.dot(to));
    }
  }
  if (!events.empty()) {
    m_metrics.min_angle_rad = std::min(m_metrics.min_angle_rad, min_rest_angle(m_mesh));
    m_metrics.separated = component_count(m_mesh) > 1;
  }
}

bool TearSimulation::grab(const Vec2& at_mm, double radius_mm, double pick_mm,
                          double speed_mm_per_s)
{
  release();
  m_hand = Hand::grab(m_mesh, at_mm, radius_mm, pick_mm, speed_mm_per_s);
  return m_hand.has_value();
}

void TearSimulation::move_hand(const Vec2& target_mm)
{
  if (m_hand)
    m_hand->move_to(target_mm);
}

void TearSimulation::release()
{
  if (m_hand)
    m_hand->release(m_mesh);
  m_hand.reset();
}

bool TearSimulation::finished() const
{
  if (m_metrics.steps >= m_scene.run.max_steps)
    return true;
  if (m_scene.run.stop_when_separated && m_metrics.separated)
    return true;
  return m_scene.run.stop_after_turn_rad > 0.0 &&
         std::abs(m_metrics.turned_rad) >= m_scene.run.stop_after_turn_rad;
}

} // namespace ligsim::membrane
