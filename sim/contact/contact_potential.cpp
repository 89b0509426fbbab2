#include "sim/contact/contact_potential.hpp"

#include "common/error.hpp"
#include "sim/contact/barrier.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace ligsim::sim {

namespace {

/// A step may close at most this fraction of a node's gap (IPC's conservative advancement).
constexpr double closing_fraction = 0.8;
/// Nodes found inside an obstacle (or on it) after it moved are pushed out to `pushed_gap` d_hat.
/// Nodes still outside, however close, are left to the barrier: pushing them would only deform
/// elements that may already be thin.
constexpr double pushed_gap = 0.1;

void project_to_psd(Eigen::Matrix3d& block)
{
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(block);
  const Eigen::Vector3d values = eigen.eigenvalues().cwiseMax(0.0);
  block = eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
}

} // namespace

ContactPotential::ContactPotential(int node_count, const ContactSurface& surface,
                                   std::vector<ContactObstacle> obstacles,
                                   const ContactSettings& settings)
    : m_node_count(node_count)
    , m_obstacles(std::move(obstacles))
    , m_settings(settings)
    , m_faces(surface.faces)
{
  const std::vector<int>& nodes = surface.nodes;
  const Eigen::VectorXd& areas_mm2 = surface.areas_mm2;
  if (!(settings.d_hat_mm > 0.0) || !std::isfinite(settings.d_hat_mm))
    fail("contact: d_hat_mm must be positive, got {}", settings.d_hat_mm);
  if (!(settings.stiffness_mpa_per_mm > 0.0) || !std::isfinite(settings.stiffness_mpa_per_mm))
    fail("contact: stiffness_mpa_per_mm must be positive, got {}", settings.stiffness_mpa_per_mm);
  if (static_cast<Eigen::Index>(nodes.size()) != areas_mm2.size())
    fail("contact: {} nodes but {} areas", nodes.size(), areas_mm2.size());
  for (const ContactObstacle& obstacle : m_obstacles) {
    if (!obstacle.field)
      fail("contact: obstacle \"{}\" has no distance field", obstacle.name);
    if (!(obstacle.start_offset_mm >= 0.0) || !std::isfinite(obstacle.start_offset_mm))
      fail("contact: obstacle \"{}\" has a start offset of {} mm (must be >= 0)", obstacle.name,
           obstacle.start_offset_mm);
    std::vector<bool> excluded(static_cast<std::size_t>(node_count), false);
    for (int n : obstacle.excluded_nodes)
      if (n >= 0 && n < node_count)
        excluded[static_cast<std::size_t>(n)] = true;
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const int n = nodes[i];
      if (n < 0 || n >= node_count)
        fail("contact: node {} is not in the mesh ({} nodes)", n, node_count);
      if (!excluded[static_cast<std::size_t>(n)])
        pairs.push_back({n, areas_mm2(static_cast<Eigen::Index>(i))});
    }
    m_closeness.emplace_back(pairs.size());
    m_state.emplace_back(pairs.size());
    m_pairs.push_back(std::move(pairs));
  }
  // A pair is culled once its distance bound exceeds d_hat + slack; a grid's bound stops at its
  // band, so the slack must leave room below that or nothing would ever be culled.
  m_slack_mm = settings.d_hat_mm;
  for (const ContactObstacle& obstacle : m_obstacles) {
    const double room = obstacle.field->bound_limit_mm() - settings.d_hat_mm;
    if (!(room > 0.0))
      fail("contact: obstacle \"{}\": its distance band ({} mm) must reach beyond d_hat ({} mm)",
           obstacle.name, obstacle.field->bound_limit_mm(), settings.d_hat_mm);
    m_slack_mm = std::min(m_slack_mm, 0.9 * room);
  }
}

ContactPotential::Pose ContactPotential::pose(std::size_t o, double t) const
{
  Pose p;
  const std::optional<RigidMotion>& motion = m_obstacles[o].motion;
  if (!motion)
    return p;
  const Eigen::Isometry3d transform = motion->pose(t);
  p.rotation = transform.linear();
  p.shift = transform.translation();
  return p;
}

bool ContactPotential::surely_farther(std::size_t o, const Eigen::Vector3d& p, double far) const
{
  const DistanceField& field = *m_obstacles[o].field;
  const Eigen::AlignedBox3d box = field.near_box();
  if (!box.isEmpty() && box.exteriorDistance(p) > far)
    return true;
  return field.distance_bound(p) > far;
}

bool ContactPotential::maybe_near(std::size_t o, std::size_t i, const Eigen::Vector3d& p) const
{
  Closeness& state = m_closeness[o][i];
  if ((p - state.p0).squaredNorm() > 0.25 * m_slack_mm * m_slack_mm) {
    state.p0 = p;
    state.near = !surely_farther(o, p, m_settings.d_hat_mm + m_slack_mm);
  }
  return state.near;
}

bool ContactPotential::surely_beyond(std::size_t o, std::size_t i, const Eigen::Vector3d& p,
                                     double offset_mm, double distance_mm) const
{
  PairState& state = m_state[o][i];
  if (p != state.bounded_at) {
    state.bound_mm = m_obstacles[o].field->distance_bound(p);
    state.bounded_at = p;
  }
  return state.bound_mm + offset_mm > distance_mm;
}

const DistanceSample& ContactPotential::pair_sample(std::size_t o, std::size_t i,
                                                    const Eigen::Vector3d& p) const
{
  PairState& state = m_state[o][i];
  if (p != state.sampled_at) {
    state.sample = m_obstacles[o].field->sample(p, true);
    state.sampled_at = p;
  }
  return state.sample;
}

double ContactPotential::distance(std::size_t o, const Eigen::Vector3d& p, double t) const
{
  return m_obstacles[o].field->sample(pose(o, t).to_local(p), false).distance_mm + offset(o, t);
}

template <class Visit>
bool ContactPotential::for_each_near_pair(const Eigen::VectorXd& x, double t, Visit&& visit,
                                          std::size_t only) const
{
  for (std::size_t o = 0; o < m_obstacles.size(); ++o) {
    if (only != static_cast<std::size_t>(-1) && o != only)
      continue;
    const Pose at = pose(o, t);
    const double off = offset(o, t);
    for (std::size_t i = 0; i < m_pairs[o].size(); ++i) {
      const Pair& pair = m_pairs[o][i];
      const Eigen::Vector3d p = at.to_local(x.segment<3>(3 * pair.node));
      // The near test is on the field itself: an offset (>= 0) only moves nodes farther.
      // The barrier is zero from d_hat on.
      if (!maybe_near(o, i, p) || surely_beyond(o, i, p, off, m_settings.d_hat_mm))
        continue;
      const DistanceSample& s = pair_sample(o, i, p);
      if (!visit(pair, at, s, ipc_barrier(s.distance_mm + off, m_settings.d_hat_mm)))
        return false;
    }
  }
  return true;
}

double ContactPotential::energy(const Eigen::VectorXd& x, double t, Eigen::VectorXd* gradient) const
{
  const double kappa = m_settings.stiffness_mpa_per_mm;
  double total = 0.0;
  const bool finite = for_each_near_pair(
      x, t, [&](const Pair& pair, const Pose& at, const DistanceSample& s, const BarrierValue& b) {
        if (!std::isfinite(b.value))
          return false;
        total += kappa * pair.area * b.value;
        if (gradient && b.first != 0.0)
          gradient->segment<3>(3 * pair.node) +=
              kappa * pair.area * b.first * (at.rotation * s.gradient);
        return true;
      });
  return finite ? total : INFINITY;
}

std::vector<ContactPotential::NodeTerm>
ContactPotential::node_terms(std::size_t o, const Eigen::VectorXd& x, double t) const
{
  const double kappa = m_settings.stiffness_mpa_per_mm;
  std::vector<NodeTerm> terms;
  for_each_near_pair(
      x, t,
      [&](const Pair& pair, const Pose& at, const DistanceSample& s, const BarrierValue& b) {
        if (b.second == 0.0 && b.first == 0.0)
          return true;
        const Eigen::Vector3d g = at.rotation * s.gradient;
        NodeTerm term;
        term.node = pair.node;
        term.gradient = kappa * pair.area * b.first * g;
        term.hessian = kappa * pair.area *
                       (b.second * g * g.transpose() +
                        b.first * (at.rotation * s.hessian * at.rotation.transpose()));
        term.local_mm = at.to_local(x.segment<3>(3 * pair.node));
        terms.push_back(term);
        return true;
      },
      o);
  return terms;
}

void ContactPotential::hessian_blocks(const Eigen::VectorXd& x, double t, bool projected,
                                      std::vector<NodeBlock>& blocks) const
{
  const double kappa = m_settings.stiffness_mpa_per_mm;
  for_each_near_pair(
      x, t, [&](const Pair& pair, const Pose& at, const DistanceSample& s, const BarrierValue& b) {
        if (b.second == 0.0 && b.first == 0.0)
          return true;
        const Eigen::Vector3d g = at.rotation * s.gradient;
        NodeBlock block;
        block.node = pair.node;
        block.block = kappa * pair.area *
                      (b.second * g * g.transpose() +
                       b.first * (at.rotation * s.hessian * at.rotation.transpose()));
        if (projected)
          project_to_psd(block.block);
        blocks.push_back(block);
        return true;
      });
}

double ContactPotential::max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx,
                                  double t) const
{
  double bound = 1.0;
  for (std::size_t o = 0; o < m_obstacles.size(); ++o) {
    const Pose at = pose(o, t);
    const double off = offset(o, t);
    const DistanceField& field = *m_obstacles[o].field;
    const double lipschitz = field.lipschitz();
    // A pair that is not near is at least d_hat + slack / 2 away.
    const double far_gap = m_settings.d_hat_mm + 0.5 * m_slack_mm;
    for (std::size_t i = 0; i < m_pairs[o].size(); ++i) {
      const Pair& pair = m_pairs[o][i];
      const Eigen::Vector3d move = at.rotation.transpose() * dx.segment<3>(3 * pair.node);
      const double length = lipschitz * move.norm();
      if (length == 0.0)
        continue;
      const Eigen::Vector3d p0 = at.to_local(x.segment<3>(3 * pair.node));
      // Far enough to move the whole step: no sample needed.
      if (length <= closing_fraction * far_gap && !maybe_near(o, i, p0))
        continue;
      if (surely_beyond(o, i, p0, 0.0, length / closing_fraction) ||
          surely_farther(o, p0, length / closing_fraction))
        continue;
      const double d0 = pair_sample(o, i, p0).distance_mm + off;
      const double keep = (1.0 - closing_fraction) * d0; // the gap never closes below this
      // Conservative advancement: a field with |grad| <= L lets the node move (d - keep) / L.
      double alpha = 0.0;
      double d = d0;
      for (int k = 0; k < 50 && alpha < bound; ++k) {
        const double step = (d - keep) / length;
        if (d - keep <= 1e-6 * d0) // no room left to move
          break;
        double next = std::min(bound, alpha + step);
        double d_next = field.sample(p0 + next * move, false).distance_mm + off;
        // The grid's slope may exceed L slightly: back off rather than overshoot.
        for (int halving = 0; d_next < keep && halving < 20; ++halving) {
          next = alpha + 0.5 * (next - alpha);
          d_next = field.sample(p0 + next * move, false).distance_mm + off;
        }
        if (d_next < keep)
          break;
        alpha = next;
        d = d_next;
      }
      bound = std::min(bound, alpha);
    }
  }
  return bound;
}

int ContactPotential::make_admissible(Eigen::VectorXd& x, double t) const
{
  const double d_hat = m_settings.d_hat_mm;
  int moved = 0;
  for (std::size_t o = 0; o < m_obstacles.size(); ++o) {
    const Pose at = pose(o, t);
    const double off = offset(o, t);
    const DistanceField& field = *m_obstacles[o].field;
    for (std::size_t i = 0; i < m_pairs[o].size(); ++i) {
      const Pair& pair = m_pairs[o][i];
      Eigen::Vector3d p = at.to_local(x.segment<3>(3 * pair.node));
      if (!maybe_near(o, i, p) || surely_beyond(o, i, p, off, 0.0))
        continue;
      DistanceSample s = pair_sample(o, i, p);
      if (s.distance_mm + off > 0.0)
        continue;
      // Newton on d(p) + offset = pushed_gap d_hat along the gradient.
      for (int k = 0; k < 10 && s.distance_mm + off < 0.5 * pushed_gap * d_hat; ++k) {
        const double slope2 = s.gradient.squaredNorm();
        if (!(slope2 > 1e-12))
          break; // deep inside, beyond the band: no direction out
        p += (pushed_gap * d_hat - s.distance_mm - off) * s.gradient / slope2;
        s = field.sample(p, false);
      }
      if (s.distance_mm + off > 0.0) {
        x.segment<3>(3 * pair.node) = at.rotation * p + at.shift;
        ++moved;
      }
    }
  }
  return moved;
}

ContactMeasures ContactPotential::measure(const Eigen::VectorXd& x, double t) const
{
  const double d_hat = m_settings.d_hat_mm;
  const double kappa = m_settings.stiffness_mpa_per_mm;
  ContactMeasures m;
  m.gap_mm = Eigen::VectorXd::Constant(m_node_count, INFINITY);
  m.pressure_mpa = Eigen::VectorXd::Zero(m_node_count);
  Eigen::VectorXd force_norm = Eigen::VectorXd::Zero(m_node_count);
  Eigen::VectorXd area = Eigen::VectorXd::Zero(m_node_count);
  for (std::size_t o = 0; o < m_obstacles.size(); ++o) {
    const Pose at = pose(o, t);
    const double off = offset(o, t);
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    double node_area = 0.0;
    std::vector<bool> active_node(static_cast<std::size_t>(m_node_count), false);
    double min_gap = INFINITY;
    int active = 0;
    for (int n = 0; n < m_node_count; ++n) {
      const Eigen::Vector3d p = at.to_local(x.segment<3>(3 * n));
      m.gap_mm(n) = std::min(m.gap_mm(n), m_obstacles[o].field->sample(p, false).distance_mm + off);
    }
    for (const Pair& pair : m_pairs[o]) {
      const Eigen::Vector3d p = at.to_local(x.segment<3>(3 * pair.node));
      DistanceSample s = m_obstacles[o].field->sample(p, false);
      s.distance_mm += off;
      min_gap = std::min(min_gap, s.distance_mm);
      const BarrierValue b = ipc_barrier(s.distance_mm, d_hat);
      if (s.distance_mm >= d_hat)
        continue;
      const Eigen::Vector3d f = -kappa * pair.area * b.first * (at.rotation * s.gradient);
      force += f;
      node_area += pair.area;
      active_node[static_cast<std::size_t>(pair.node)] = true;
      ++active;
      force_norm(pair.node) += f.norm();
      area(pair.node) = pair.area;
    }
    m.force_n.push_back(force);
    double face_area = 0.0;
    for (Eigen::Index f = 0; f < m_faces.rows(); ++f) {
      if (!active_node[static_cast<std::size_t>(m_faces(f, 0))] ||
          !active_node[static_cast<std::size_t>(m_faces(f, 1))] ||
          !active_node[static_cast<std::size_t>(m_faces(f, 2))])
        continue;
      const Eigen::Vector3d a = x.segment<3>(3 * m_faces(f, 0));
      face_area +=
          0.5 *
          (x.segment<3>(3 * m_faces(f, 1)) - a).cross(x.segment<3>(3 * m_faces(f, 2)) - a).norm();
    }
    m.area_mm2.push_back(m_faces.rows() > 0 ? face_area : node_area);
    m.min_gap_mm.push_back(min_gap);
    m.active_nodes.push_back(active);
  }
  for (int n = 0; n < m_node_count; ++n)
    if (area(n) > 0.0)
      m.pressure_mpa(n) = force_norm(n) / area(n);
  return m;
}

} // namespace ligsim::sim
