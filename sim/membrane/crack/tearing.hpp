#pragma once
/// @brief The tearing loop of one time step: where the criterion exceeds 1 (at crack tips and
/// at element centres away from any crack), advance the crack along the best direction.
///
/// Tip stress and fiber: the area-weighted mean of the stresses and (as axes, by doubled
/// angles) of the fiber directions of the triangles around the tip node, so the elements whose
/// stress best represents the tip's neighbourhood count in proportion to their size.
/// Per step, candidates are taken in decreasing criterion order, at most `max_events_per_step`
/// of them, each tip at most once and at most one initiation, so a step's cost stays bounded.

#include "sim/membrane/crack/criterion.hpp"
#include "sim/membrane/crack/propagation.hpp"
#include "sim/membrane/mesh/membrane_mesh.hpp"
#include "sim/membrane/model/corotational_elements.hpp"

#include <Eigen/Core>

#include <vector>

namespace ligsim::membrane {

struct TearSettings {
  TearThresholds thresholds;
  PropagationSettings propagation;
  bool initiation = true;               ///< new cracks may start at element centres
  double initiation_clearance_mm = 0.0; ///< ... but not within this distance of a crack tip
  int max_events_per_step = 2;
};

/// Throws InputError naming `where` for thresholds <= 0, alpha <= 0, theta_P outside
/// (0, 180] degrees, a minimum angle outside [0, 30) degrees or fewer than one event per step.
void validate(const TearSettings& settings, const char* where);

struct CrackTip {
  int node = -1;
  Vec2 previous = Vec2::UnitX(); ///< unit direction of the crack's last advance, rest frame
  int id = -1;                   ///< the same for all advances of one crack end
};

/// One advance of a crack, as recorded for the outputs and the measurements.
struct TearEvent {
  bool initiation = false;
  int tip_id = -1;        ///< the tip that advanced (initiation: the first of the new tips)
  double criterion = 0.0; ///< c of the chosen direction, > 1
  Vec2 from_rest = Vec2::Zero();
  Vec2 to_rest = Vec2::Zero();
  bool split_face = false;
};

class Tearing {
public:
  explicit Tearing(const TearSettings& settings)
      : m_settings(settings)
  {
  }

  /// Adds a crack tip (from a scene's cut); returns its id.
  int add_tip(int node, const Vec2& previous);
  const std::vector<CrackTip>& tips() const { return m_tips; }
  const TearSettings& settings() const { return m_settings; }

  /// Evaluates the criterion with the elements' current stresses and applies the events of
  /// this step; refreshes the elements and masses of every changed triangle and node.
  std::vector<TearEvent> step(MembraneMesh& mesh, CorotationalElements& elements,
                              double areal_density_t_per_mm2);

  /// Area-weighted stress (MPa) and fiber direction (unit) around `node`.
  std::pair<Eigen::Vector3d, Vec2> tip_state(const MembraneMesh& mesh,
                                             const CorotationalElements& elements,
                                             const NodeIncidence& incidence, int node) const;

  /// Largest criterion value over all directions at each element's centre (for display).
  std::vector<double> element_criterion(const MembraneMesh& mesh,
                                        const CorotationalElements& elements) const;

private:
  TearSettings m_settings;
  std::vector<CrackTip> m_tips;
  int m_next_tip_id = 0;
};

/// Refreshes element data and lumped masses after a topology edit.
void apply_edit(MembraneMesh& mesh, CorotationalElements& elements, const TopologyEdit& edit,
                double areal_density_t_per_mm2);

} // namespace ligsim::membrane
