#pragma once
/// @brief Dynamics by implicit Euler (Baraff and Witkin 1998), each step the minimum of its
/// incremental potential (inertia, strain energy, loads, contact and Rayleigh damping) found by
/// the solids' one Newton engine: Baraff and Witkin's linearised solve is its first iteration,
/// more follow while the step's equation is off. Lumped masses, prescribed DOFs filtered out of
/// the solve; a frame whose result would invert an element is redone in halved sub-steps.

#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/extra_potential.hpp"
#include "sim/solver/hyperelastic_body.hpp"
#include "sim/solver/linear_solver.hpp"
#include "sim/solver/newton_engine.hpp"
#include "sim/solver/stiffness_matrix.hpp"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct DynamicsSettings {
  double time_step_s = 1e-3;
  int frames = 100; ///< frames to run (a maximum when until_converged)
  /// Stop as soon as the body is at rest in equilibrium (relative residual and inertial force
  /// below convergence_tolerance) after the ramp.
  bool until_converged = false;
  double convergence_tolerance = 1e-6;
  int ramp_frames = 1; ///< frames over which loads and prescribed motions reach full value
  double density_kg_m3 = 1000.0;
  double mass_damping_per_s = 0.0;  ///< Rayleigh alpha (velocity damping)
  double stiffness_damping_s = 0.0; ///< Rayleigh beta
  LinearSolverKind linear_solver = LinearSolverKind::pcg;
  PcgSettings pcg;
  PsdProjection projection = PsdProjection::automatic;
  int max_halvings = 10; ///< sub-step halvings of one frame before giving up
  /// Linearised solves of one (sub-)step at most. The first is Baraff and Witkin's; Newton
  /// iterations on the implicit Euler equation follow while a contact surface cut the move short
  /// or the equation's residual exceeds `iteration_tolerance` of the supports' force at the
  /// last frame. With 1 the
  /// error of each frame's single solve is left in the state, and on a soft, near-incompressible
  /// ligament driven at its footprint it builds up over frames (the HRA MCL's elements beside the
  /// femoral footprint squeezed to J = 0.1 and 2.8 kN on the femur, where the quasi-static sweep
  /// gives J = 0.95 and 20 N).
  int max_iterations = 1;
  double iteration_tolerance = 0.03;
};

struct FrameReport : SolveCosts {
  int frame = 0; ///< 1-based
  double time_s = 0.0;
  double load_factor = 0.0;
  double relative_residual = 0.0; ///< ||f_int - f_ext|| on free DOFs over the force scale
  double relative_inertia = 0.0;  ///< ||M v|| / h over the force scale
  double kinetic_energy_mj = 0.0;
  double strain_energy_mj = 0.0;
  double min_j = 1.0;
  int min_j_element = -1;
  int substeps = 1;
  /// Whether each sub-step's implicit Euler equation held to iteration_tolerance when it ended
  /// (false only where max_iterations solves ran out first).
  bool equation_met = true;
  double wall_s = 0.0;
};

struct DynamicResult : SolveCosts {
  bool completed = false; ///< ran all its frames (or reached equilibrium) without failure
  bool reached_equilibrium = false;
  std::string failure;
  int frames = 0;
  int substeps = 0;
  double wall_s = 0.0;
};

class ImplicitEuler {
public:
  /// Called after every frame with positions and the residual dE/dx - f_ext.
  using FrameCallback = std::function<void(const FrameReport&, const Eigen::VectorXd& x,
                                           const Eigen::VectorXd& residual)>;

  ImplicitEuler(const HyperelasticBody& body, const BoundaryConditions& conditions,
                const DynamicsSettings& settings);

  /// Runs from positions `x` at rest (zero velocity). Never throws on divergence.
  DynamicResult run(Eigen::VectorXd& x, const FrameCallback& on_frame = {});

  /// Frame by frame, where the load is moved as the frames go (a live view): start() at the
  /// first state, then frame() to report.load_factor from `t_before` with velocity `v`; fills
  /// the report and the residual dE/dx - f_ext. False, with (x, v) as they were and failure()
  /// saying why, when max_halvings could not make the frame.
  void start(const Eigen::VectorXd& x);
  bool frame(Eigen::VectorXd& x, Eigen::VectorXd& v, double t_before, FrameReport& report,
             Eigen::VectorXd& residual);
  const std::string& failure() const { return m_failure; }

  /// Adds `potential` (not owned; null: none) to the energy: its gradient and Hessian blocks enter
  /// each frame's solve, and the frame's move is shortened (velocity with it) so that no node
  /// crosses a contact surface.
  void set_extra_potential(const ExtraPotential* potential);

  /// Lumped nodal masses per DOF (flat), tonnes (mm, N, s units).
  const Eigen::VectorXd& masses() const { return m_mass; }

private:
  /// One implicit Euler step of length h to load factor t; false on failure.
  bool step(Eigen::VectorXd& x, Eigen::VectorXd& v, double h, double t, FrameReport& report);
  /// The norm of the body's forces on the prescribed DOFs at x, N (0 if an element is inverted).
  double support_force(const Eigen::VectorXd& x) const;

  const HyperelasticBody& m_body;
  const BoundaryConditions& m_conditions;
  DynamicsSettings m_settings;
  DofPartition m_dofs;
  Eigen::VectorXd m_external;  ///< at load factor 1
  Eigen::VectorXd m_mass;      ///< per DOF
  Eigen::VectorXd m_free_mass; ///< per free DOF
  StiffnessSolver m_linear;
  NewtonEngine m_engine;
  InertiaTerm m_inertia;
  DampingTerm m_damping;
  std::unique_ptr<StiffnessMatrix> m_damping_stiffness; ///< K_s, made where beta > 0
  /// The state at the end of the last step: the body's energy, and its gradient less the loads
  /// plus the extra potential's.
  std::optional<NewtonEngine::Evaluation> m_end;
  /// The supports' force (norm over the prescribed DOFs) at the start or the last accepted
  /// frame: the scale of the steps' convergence test, N.
  double m_support_force = 0.0;
  bool m_step_met = true;      ///< the last step's equation held to iteration_tolerance
  bool m_last_halving = false; ///< the frame's sub-steps cannot be halved again
  std::string m_failure;
};

} // namespace ligsim::sim
