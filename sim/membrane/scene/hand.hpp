#pragma once
/// @brief A hand holding a membrane, as a user's mouse or a script moves it: the nodes within a
/// radius (at rest) of the node picked follow the hand, each step, by a prescribed velocity (the
/// hand's own, at most its speed), and go free again when it lets go. Nodes a crack duplicates
/// from a held one are held too.

#include "sim/membrane/mesh/membrane_mesh.hpp"

#include <optional>
#include <vector>

namespace ligsim::membrane {

class Hand {
public:
  /// Picks the free node nearest `at_mm` (current positions) within `pick_mm` and holds every
  /// free node within `radius_mm` of it at rest. Empty when no free node is that near.
  static std::optional<Hand> grab(const MembraneMesh& mesh, const Vec2& at_mm, double radius_mm,
                                  double pick_mm, double speed_mm_per_s);

  /// Where the hand goes; it moves there at most at its speed.
  void move_to(const Vec2& target_mm) { m_target = target_mm; }
  /// Prescribes the held nodes' velocity for a step of `h` s: the hand's move over the step.
  void apply(MembraneMesh& mesh, double h);
  /// Sets the held nodes free.
  void release(MembraneMesh& mesh) const;

  const Vec2& position() const { return m_position; }
  const std::vector<int>& nodes() const { return m_nodes; }

private:
  std::vector<int> m_nodes;
  int m_known_nodes = 0; ///< the mesh's node count when the held set was last brought up to date
  Vec2 m_position = Vec2::Zero();
  Vec2 m_target = Vec2::Zero();
  double m_speed = 0.0;
};

} // namespace ligsim::membrane
