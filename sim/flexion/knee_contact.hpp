#pragma once
/// @brief The knee model's bones as contact obstacles for the ligament: a level set per bone
/// (cached in <model>/contact/), the femur's moving with the femur's rigid motion, the barrier
/// on the ligament's free surface nodes, and an independent check of penetration against the
/// bone triangles themselves (winding number and distance: BonePenetration, not the grids).

#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/contact_config.hpp"
#include "sim/contact/contact_potential.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace ligsim::sim {

/// One bone's contact at one state.
struct BoneContact {
  std::string bone;
  bool in_solve = true; ///< false: contact off, only gaps and penetration measured
  Eigen::Vector3d force_n = Eigen::Vector3d::Zero(); ///< what the bone exerts on the ligament
  double area_mm2 = 0.0;       ///< surface triangles whose nodes are all within d_hat
  int nodes = 0;               ///< nodes within d_hat
  double min_gap_mm = 0.0;     ///< smallest grid distance of a contact node
  double penetration_mm = 0.0; ///< deepest node inside the triangles (independent), >= 0
};

/// One bone's contact grid as the sweep made it.
struct ContactGridFigures {
  std::string bone;
  std::filesystem::path cache; ///< the grid's file
  LevelSetFigures grid;        ///< reused or built, time, voxels, memory
  Eigen::Index triangles = 0;
  int open_edges = 0; ///< of the bone's surface
};

/// The bones' grids and the barrier's surface.
struct KneeContactFigures {
  std::vector<ContactGridFigures> bones;
  std::size_t surface_nodes = 0;
  double voxel_mm = 0.0;
  double band_mm = 0.0;
};

class KneeContact {
public:
  /// Grids of the bones `config.bones` names (empty: every bone of the model), read from or written
  /// to `cache_dir`; the femur follows the "femur" set's rigid motion of `conditions`.
  KneeContact(const KneeModel& model, const BoundaryConditions& conditions,
              const ContactConfig& config, const std::filesystem::path& cache_dir);
  ~KneeContact();

  const ContactPotential& potential() const { return *m_potential; }

  /// Per bone at positions x and load factor t: the smallest grid distance of a contact node
  /// (negative: inside), the nodes inside and the nodes within d_hat.
  struct Gaps {
    std::string bone;
    double min_gap_mm = INFINITY;
    int inside = 0;
    int within_d_hat = 0;
    std::vector<int> inside_nodes;
  };
  std::vector<Gaps> gaps(const Eigen::VectorXd& x, double t) const;

  /// The same barrier with the bones held in their rest pose, each grown from shrunk by
  /// `start_offsets_mm` (one per bone, >= 0) at load factor 0 to its surface at load factor 1.
  std::unique_ptr<ContactPotential>
  resting_bones_shrunk_by(const std::vector<double>& start_offsets_mm) const;
  /// Per bone: grid voxels, memory, build or read time, open edges of the surface.
  const KneeContactFigures& figures() const { return m_figures; }

  /// Per bone forces, areas, gaps and the independent penetration at positions x, load factor t;
  /// per node gap (mm) and pressure (MPa) into `gap_mm` and `pressure_mpa`. With `forces`
  /// false (contact off in the solve) only the gaps and the penetration.
  std::vector<BoneContact> measure(const Eigen::VectorXd& x, double t, bool forces,
                                   Eigen::VectorXd& gap_mm, Eigen::VectorXd& pressure_mpa) const;

private:
  struct Bone;
  std::vector<std::unique_ptr<Bone>> m_bones;
  std::unique_ptr<ContactPotential> m_potential;
  ContactSurface m_surface;
  int m_node_count = 0;
  KneeContactFigures m_figures;
};

} // namespace ligsim::sim
