#pragma once
/// @brief A segmented ligament touches or slightly overlaps its bones as segmented: before the
/// knee moves, the nodes inside a bone are pushed out. The bones are held in their rest pose
/// and grown from shrunk (by the deepest overlap plus half of d_hat) back to their surfaces while
/// the pre-stretched ligament settles in equilibrium with them, so no node is moved alone and no
/// element is inverted by a jump.

#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/knee_contact.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/solver/boundary_conditions.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ligsim::sim {

struct OverlapReport {
  std::vector<KneeContact::Gaps> before; ///< per bone, at the segmented shape
  std::vector<KneeContact::Gaps> after;  ///< per bone, after the push (empty if none was needed)
  bool pushed = false;
  bool reshaped = false; ///< the pushed shape became the rest shape (not a deformation)
  std::vector<double> start_offsets_mm; ///< how far each bone was shrunk to start
  double max_node_move_mm = 0.0;        ///< largest displacement of a node by the push
  double mean_surface_move_mm = 0.0;    ///< mean displacement of the nodes that started inside
  int newton_iterations = 0;
};

/// Resolves the overlap of the state `x` (flat positions, mm) with the bones of `contact`, in
/// place. Does nothing (pushed = false) when no free node is inside a bone. Throws SolverError
/// naming the bone when the push does not converge.
OverlapReport resolve_initial_overlap(const HyperelasticBody& body,
                                      const BoundaryConditions& conditions,
                                      const KneeContact& contact, const NewtonSettings& newton,
                                      Eigen::VectorXd& x);

/// The push read as a correction of the segmented shape (ContactConfig::reshape_overlap): the
/// pre-stretched `body` is pushed without its in-situ strain, so that the pushed shape `x` can
/// become its stress-free rest shape (with_rest_shape). `reshaped` is set when it was pushed.
OverlapReport reshape_initial_overlap(const HyperelasticBody& body,
                                      const MaterialParameters& material,
                                      const BoundaryConditions& conditions,
                                      const KneeContact& contact, const NewtonSettings& newton,
                                      Eigen::VectorXd& x);

/// `model` with its ligament's rest shape pushed out of the bones as `ligsim flexion` reshapes it,
/// for programs that take the model's shape as it is (the FEBio export): fibers and footprints
/// unchanged; `model` itself when no free node is inside a bone. `report` (if given) says what
/// the push did.
KneeModel with_overlap_reshaped(const KneeModel& model, const FlexionSettings& settings,
                                const BoundaryConditions& conditions, const KneeContact& contact,
                                OverlapReport* report = nullptr);

/// `body` with unit fibers: its material without the in-situ pre-stretch the fibers' length
/// carries (ligament_body).
HyperelasticBody with_unit_fibers(const HyperelasticBody& body, const MaterialParameters& material);

/// `body` (its material, fibers and their pre-stretch) at rest in the shape `x` (flat, mm): the
/// push read as a correction of the segmented shape. The fibers keep their directions (the push
/// moves nodes by a fraction of a millimetre).
HyperelasticBody with_rest_shape(const HyperelasticBody& body, const MaterialParameters& material,
                                 const Eigen::VectorXd& x);

} // namespace ligsim::sim
