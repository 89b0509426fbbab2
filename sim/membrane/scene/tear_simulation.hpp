#pragma once
/// @brief A tearing scene in motion: the mesh built from the scene, loads and constraints
/// applied, one implicit step then the tearing events per time step, and the measurements.

#include "sim/membrane/crack/tearing.hpp"
#include "sim/membrane/mesh/membrane_mesh.hpp"
#include "sim/membrane/model/corotational_elements.hpp"
#include "sim/membrane/model/implicit_euler.hpp"
#include "sim/membrane/scene/hand.hpp"
#include "sim/membrane/scene/scene.hpp"

#include <optional>
#include <vector>

namespace ligsim::membrane {

/// An event with the step it happened in and the load at that time.
struct RecordedEvent {
  TearEvent event;
  int step = 0;
  double load_n = 0.0;
};

struct TearMetrics {
  int steps = 0;
  std::vector<double> step_ms;    ///< wall time of each step (solve and tearing)
  std::vector<int> cg_iterations; ///< per step
  int propagation_events = 0;     ///< every advance of a crack and every initiation
  int initiations = 0;
  int face_splits = 0; ///< advances that split a face (mode 2)
  int initial_elements = 0;
  double min_angle_rad = 0.0;         ///< smallest triangle angle ever (rest configuration)
  std::optional<RecordedEvent> onset; ///< the first event
  bool separated = false;
  double turned_rad = 0.0; ///< signed turn of the lead tip around the run's centre
  std::vector<RecordedEvent> events;
};

class TearSimulation {
public:
  /// Builds the mesh, fibers, constraints, loads and initial cuts of `scene`. Throws
  /// InputError if the scene does not fit its mesh (a region that selects nothing, a fiber
  /// file of the wrong length, a mesh angle below the minimum angle).
  explicit TearSimulation(const Scene& scene);

  /// One time step: the implicit solve, then the tearing events.
  void step();
  /// True once the run's stop condition or its step limit is reached.
  bool finished() const;

  /// A hand takes the membrane at `at_mm` (the free node nearest it, within `pick_mm`): the free
  /// nodes within `radius_mm` of that node at rest follow the hand at most at `speed_mm_per_s`
  /// from the next step on. False (and no hand) when no free node is that near; a hand already
  /// holding lets go first.
  bool grab(const Vec2& at_mm, double radius_mm, double pick_mm, double speed_mm_per_s);
  /// Where the hand goes (nothing without a hand).
  void move_hand(const Vec2& target_mm);
  /// The hand lets go: its nodes are free again.
  void release();
  const std::optional<Hand>& hand() const { return m_hand; }

  /// The load now: the grasp's force, else the total force on the first traction's sides, N.
  double current_load_n() const;

  const Scene& scene() const { return m_scene; }
  const MembraneMesh& mesh() const { return m_mesh; }
  const CorotationalElements& elements() const { return m_elements; }
  const Tearing& tearing() const { return m_tearing; }
  const TearMetrics& metrics() const { return m_metrics; }
  double time_s() const { return m_time_s; }

private:
  std::vector<Vec2> external_forces() const;
  void add_grasp_force(std::vector<Vec2>& forces) const;

  Scene m_scene;
  MembraneMesh m_mesh;
  CorotationalElements m_elements;
  ImplicitEuler m_solver;
  Tearing m_tearing;
  TearMetrics m_metrics;
  std::vector<double> m_traction_length_mm; ///< rest length of each traction's sides
  double m_time_s = 0.0;
  int m_lead_tip = -1; ///< the tip the grasp follows and whose turn is measured
  std::optional<Hand> m_hand;
};

} // namespace ligsim::membrane
