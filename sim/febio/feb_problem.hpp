#pragma once
/// @brief Everything a FEBio 4 input of a ligament between rigid bones holds, independent of
/// where it came from: the ligament's tets and fibers, its material and in-situ strain, the
/// bones as rigid bodies with their attachment nodes and their poses per step, contact, and the
/// solver settings. `write_feb` turns it into a .feb file (docs/export.md).

#include "common/mesh.hpp"
#include "sim/material/material_parameters.hpp"
#include "sim/mesh/quadratic_tet.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace ligsim::sim {

/// A bone as a FEBio rigid body (a shell of its surface triangles).
struct FebRigidBody {
  std::string name;        ///< its material's name in the file ("femur", "tibia")
  TriangleSurface surface; ///< the shell, mm (outward normals, for contact)
  /// The point its rotations turn about (FEBio's center of mass of the rigid body), mm.
  Eigen::Vector3d center_mm = Eigen::Vector3d::Zero();
  std::vector<int> attached_nodes; ///< ligament nodes bound to it, 0-based
  /// Its pose at the end of each step, relative to the rest pose (model frame). Empty: held
  /// fixed in all six degrees of freedom.
  std::vector<Eigen::Isometry3d> poses;
  bool contact = false; ///< the ligament's free surface slides on it
  /// Contact: the bone's surface starts shrunk by this much (FEBio's contact offset) and grows
  /// linearly back to its true surface over the first step, so that a ligament segmented into
  /// the bone is pushed out gradually, as ligsim's pre-push does (>= 0, mm; 0: no ramp).
  double contact_start_offset_mm = 0.0;
};

/// FEBio's sliding-elastic contact (frictionless, penalty).
struct FebContactSettings {
  /// Scale of FEBio's automatic penalty; the penetration it allows falls as it grows (docs/knee.md,
  /// "FEBio cross-check on the HRA knee", measures 1 and 10 on the HRA MCL).
  double penalty = 10.0;
  double search_tol = 0.01; ///< FEBio's projection tolerance (fraction of the facet)
};

/// FEBio's nonlinear solver: full Newton (a stiffness reformation every iteration) with its
/// convergence tolerances, and the automatic time stepper's cut-backs.
struct FebSolverSettings {
  double displacement_tolerance = 1e-6; ///< dtol
  double energy_tolerance = 1e-6;       ///< etol
  double residual_tolerance = 1e-8;     ///< rtol
  int max_reformations = 50;            ///< max_refs: Newton iterations per time step
  int max_retries = 10;                 ///< cut-backs of a time step
  double min_step = 1e-3;               ///< dtmin, as a fraction of one step
};

struct FebProblem {
  std::vector<std::string> notes; ///< comment lines at the top of the file
  TetMesh ligament;               ///< mm, positively oriented
  /// The ligament's 10-node tets, when not empty: `ligament.T` holds their corners and
  /// `ligament.V` their mid-edge nodes too. Written as FEBio's TET10G4, the 4-point rule that
  /// ligsim's rule of degree 2 is.
  QuadraticTetrahedra ligament_tet10;
  Eigen::MatrixX3d fiber_directions; ///< unit, one row per tet
  MaterialParameters material;       ///< with fibers
  double in_situ_strain = 0.0;       ///< fiber pre-strain of the reference state
  std::vector<FebRigidBody> bones;
  /// Steps at the bones' rest poses before the labelled ones, where the in-situ prestrain settles
  /// alone (as ligsim's sweep settles it at the built pose): 1 when the first labelled pose is not
  /// the rest pose (a found path's first angle), else 0.
  int settle_steps = 0;
  /// The steps' labels (the flexion angles, deg): step k ends at time settle_steps + k + 1.
  std::vector<double> step_labels;
  bool contact = false; ///< sliding contact with the bones marked `contact`
  FebContactSettings contact_settings;
  FebSolverSettings solver;
};

/// The data records of the .log, in this order (FEBio numbers them from 1).
enum class FebLogRecord {
  ligament_nodes = 1, ///< x;y;z of every ligament node
  rigid_bodies = 2,   ///< x;y;z;qx;qy;qz;qw;Fx;Fy;Fz;Mx;My;Mz of every rigid body
  strain_energy = 3,  ///< sed of every tet
};

/// FEBio material id of bone b (the ligament is 1).
inline int feb_material_id_of_bone(std::size_t b)
{
  return 2 + static_cast<int>(b);
}

} // namespace ligsim::sim
