#include "sim/membrane/scene/hand.hpp"

#include <algorithm>

namespace ligsim::membrane {

std::optional<Hand> Hand::grab(const MembraneMesh& mesh, const Vec2& at_mm, double radius_mm,
                               double pick_mm, double speed_mm_per_s)
{
  int picked = -1;
  double nearest = pick_mm;
  for (int v = 0; v < mesh.node_count(); ++v) {
    const double distance = (mesh.position[v] - at_mm).norm();
    if (mesh.constraint[v] == NodeConstraint::free && distance <= nearest) {
      nearest = distance;
      picked = v;
    }
  }
  if (picked < 0)
    return std::nullopt;
  Hand hand;
  for (int v = 0; v < mesh.node_count(); ++v)
    if (mesh.constraint[v] == NodeConstraint::free &&
        (mesh.rest[v] - mesh.rest[picked]).norm() <= radius_mm)
      hand.m_nodes.push_back(v);
  hand.m_known_nodes = mesh.node_count();
  hand.m_position = hand.m_target = mesh.position[picked];
  hand.m_speed = speed_mm_per_s;
  return hand;
}

void Hand::apply(MembraneMesh& mesh, double h)
{
  // A crack's copy of a held node sits where it was at rest.
  const std::size_t held = m_nodes.size();
  for (int v = m_known_nodes; v < mesh.node_count(); ++v)
    for (std::size_t k = 0; k < held; ++k)
      if (mesh.rest[v] == mesh.rest[m_nodes[k]]) {
        m_nodes.push_back(v);
        break;
      }
  m_known_nodes = mesh.node_count();
  Vec2 move = m_target - m_position;
  const double longest = m_speed * h;
  if (move.norm() > longest)
    move *= longest / move.norm();
  m_position += move;
  for (int v : m_nodes) {
    mesh.constraint[v] = NodeConstraint::prescribed;
    mesh.prescribed_velocity[v] = move / h;
  }
}

void Hand::release(MembraneMesh& mesh) const
{
  for (int v : m_nodes) {
    mesh.constraint[v] = NodeConstraint::free;
    mesh.prescribed_velocity[v] = Vec2::Zero();
  }
}

} // namespace ligsim::membrane
