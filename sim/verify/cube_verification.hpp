#pragma once
/// @brief The paper's cube experiments (sec. 5.1) against FEBio: one static solve per case and
/// energy, node errors in percent of the edge, the table and verify.json.

#include "sim/solver/static_solver.hpp"
#include "sim/verify/febio_reference.hpp"

#include <string>
#include <vector>

namespace ligsim::sim {

/// Which energy a case is solved with.
enum class CubeEnergy {
  matched, ///< the case's own fiber convention and volumetric law, as FEBio ran it
  paper,   ///< the paper's: fiber convention "paper", K/2 (J - 1)^2
};

std::string to_string(CubeEnergy energy);

struct CubeCaseResult {
  std::string name;
  CubeEnergy energy = CubeEnergy::matched;
  std::string incompressibility;
  bool converged = false;
  std::string failure;
  /// Node position errors against FEBio in percent of the edge: top face, then all nodes.
  double avg_error_pct = 0.0;
  double max_error_pct = 0.0;
  double avg_error_all_pct = 0.0;
  double max_error_all_pct = 0.0;
  /// Volume-weighted mean of lambda - 1, lambda = J^-1/3 |F a| the deviatoric fiber stretch of
  /// eq. 6 (I4 = lambda^2), as the paper's tables report it.
  double avg_fiber_strain_pct = 0.0;
  double volume_change_pct = 0.0;
  double avg_top_uz_mm = 0.0;
  double wall_s = 0.0; ///< set-up and solve, excluding file reading
  double cpu_s = 0.0;  ///< process CPU time of the same (all threads)
  double febio_wall_s = 0.0;
  int newton_iterations = 0;
  int factorizations = 0;
  int cg_iterations = 0;
  int load_steps = 0;
  int projected_elements = 0;
  /// Equilibrium of the answer: |free-DOF residual| / |load| and |reactions + load| / |load|.
  double relative_residual = 0.0;
  double balance_error = 0.0;
  int substeps = 0;
  int cutbacks = 0;
  int saddle_iterations = 0;       ///< Newton iterations with an indefinite tangent
  bool converged_at_floor = false; ///< some step stopped at the round-off floor
  std::string floor;               ///< its figures
  /// Negative eigenvalues of the tangent at the answer (counted where a step met an
  /// indefinite stiffness): > 0 is an unstable equilibrium, described by `instability`.
  int negative_eigenvalues = 0;
  std::string instability;
};

/// Material of `c` for the chosen energy.
MaterialParameters cube_material(const FebioCase& c, CubeEnergy energy);

/// The case's boundary conditions on a cube mesh: `bottom` fixed in x, y, z, the case's force
/// on every `top` node.
BoundaryConditions cube_conditions(const FebioCase& c, const std::vector<int>& bottom,
                                   const std::vector<int>& top);

/// Solves one case on `mesh`; on a solver failure the result says so and has no errors.
/// `reference` holds FEBio's displacements on the same mesh (empty: errors are not computed).
/// `x_out` (optional) receives the final positions.
CubeCaseResult run_cube_case(const FebioMesh& mesh, const FebioCase& c, CubeEnergy energy,
                             const NewtonSettings& settings, const Points& reference,
                             double edge_mm, Eigen::VectorXd* x_out = nullptr);

/// Markdown table in the layout of the paper's Tables 1 and 2, with FEBio's wall time.
std::string cube_results_table(const std::vector<CubeCaseResult>& results);

/// Markdown table of cases without a reference: equilibrium figures and stability.
std::string cube_equilibrium_table(const std::vector<CubeCaseResult>& results);

} // namespace ligsim::sim
