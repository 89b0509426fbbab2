#pragma once
/// @brief A built knee model as `ligsim build` leaves it in its output folder: the ligament's
/// tets with per-tet fiber directions and attachment flags (model.vtu), the femur and tibia
/// surfaces (femur.vtp, tibia.vtp); or a knee of several ligaments (knee.json: one such folder
/// per ligament, the bones once).

#include "common/knee_anatomy.hpp"
#include "common/knee_manifest.hpp"
#include "common/mesh.hpp"
#include "sim/material/material_parameters.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "sim/solver/hyperelastic_body.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ligsim::sim {

/// A bone's triangles (mm), shared by the ligaments of a knee; null where the model has none.
using BoneSurface = std::shared_ptr<const TriangleSurface>;

struct KneeModel {
  /// The ligament's tets; with `tet10`, their corners, and V holds the mid-edge nodes too.
  TetMesh mesh;
  /// The ligament's 10-node tets over mesh.V (corners first), when not empty.
  QuadraticTetrahedra tet10;
  Eigen::MatrixX3d fiber_directions; ///< unit, one row per tet
  /// With `tet10`: unit, one row per point of the rule of kQuadraticTetRuleDegree of every tet
  /// (element-major), sampled there by the build; empty: fiber_directions throughout each tet.
  Eigen::MatrixX3d fiber_directions_at_points;
  std::vector<int> femur_nodes; ///< move rigidly with the femur
  std::vector<int> tibia_nodes; ///< stay with the (fixed) distal bone: tibia or fibula
  BoneSurface femur;
  BoneSurface tibia;
  BoneSurface fibula;                ///< null when the knee has none; moves with the tibia
  std::string distal_bone = "tibia"; ///< the bone `tibia_nodes` are bound to
  KneeAnatomy anatomy; ///< anatomy.json of the folder (empty for models built without it)
  Points centerline;   ///< centerline.vtp of the folder, #P x 3 mm (0 rows without it)
};

/// The model with 10-node tets: a node at the middle of every edge of its tets (after its
/// nodes), bound to a bone where both ends of its edge are.
KneeModel with_quadratic_tets(const KneeModel& model);

/// The model of 10-node tets as linear tets on their corners (the mid-edge nodes dropped, the
/// corners renumbered in order, the tets' own fibers); a model of linear tets as it is. The
/// interactive sweep runs these: implicit Euler needs a positive lumped mass.
KneeModel with_linear_tets(const KneeModel& model);

/// The model's ligament as a body of `material`: its linear tets, or its 10-node tets with the
/// 4-point rule (kQuadraticTetRuleDegree, FEBio's TET10G4); its fibers (at the points where the
/// model has them) with the in-situ pre-stretch (unit direction times 1 + in_situ_strain).
HyperelasticBody ligament_body(const KneeModel& model, const MaterialParameters& material,
                               double in_situ_strain);

/// Reads the model folder, of linear or 10-node tets. Throws InputError naming the file and what
/// is missing: the folder, model.vtu, its "fiber" cell array (and for 10-node tets its fibers at
/// the points, when it has them, one per point) or attachment flags, an empty or overlapping
/// attachment set, a bone surface, a fiber of zero length.
KneeModel load_knee_model(const std::filesystem::path& dir);

/// What a one-ligament model was built with: its scene.toml's material and the in-situ strain
/// its fibers carry (the build config's [material] and [model] in_situ_strain).
struct BuiltMaterial {
  MaterialParameters material;
  double in_situ_strain = 0.0;
};

/// One ligament of a model folder, with what the knee says of it.
struct LigamentModel {
  std::string name;
  KneeModel model;                      ///< its mesh, with the knee's bones and anatomy
  std::filesystem::path folder;         ///< its model folder
  std::optional<KneeLigament> manifest; ///< knee.json's entry; none for a one-ligament model
  std::optional<BuiltMaterial> built;   ///< a one-ligament model's, from its scene.toml
};

/// For one ligament's folder of a knee model: the knee's folder and knee.json's entry of it.
std::optional<std::pair<std::filesystem::path, KneeLigament>>
knee_of_ligament_folder(const std::filesystem::path& dir);

/// The material and in-situ strain of the model folder's scene.toml, none when it has none.
/// Throws InputError naming the file where it cannot be read.
std::optional<BuiltMaterial> read_built_material(const std::filesystem::path& dir);

/// A model folder's ligaments: those knee.json lists (each loaded from its folder, with the
/// knee's bones, anatomy.json and, for the ones bound to it, the fibula); for one ligament's
/// folder of a knee, that ligament as the knee has it; else the folder's one ligament called
/// `single_name`. Throws InputError as load_knee_model does, or naming knee.json
/// and the file it lacks.
std::vector<LigamentModel> load_knee(const std::filesystem::path& dir,
                                     const std::string& single_name);

/// The one ligament of `dir` as load_knee loads it: a one-ligament model, or one ligament's
/// folder of a knee with the knee's bones (its fibula too), distal bone and anatomy. Throws
/// InputError as load_knee does, and for a knee's own folder of several ligaments, naming them
/// (`job` names the command).
LigamentModel load_ligament(const std::filesystem::path& dir, const std::string& single_name,
                            const std::string& job);

/// The bone called `name` ("femur", "tibia" or "fibula") of the model, null if it has none.
const TriangleSurface* bone_of(const KneeModel& model, const std::string& name);

/// The ligament's nodes bound to the bone called `bone`: the femoral footprint's to the femur,
/// the distal one's to model.distal_bone, none to another bone.
const std::vector<int>& nodes_bound_to(const KneeModel& model, const std::string& bone);

/// The bones the ligament takes contact with: those `chosen` names (a config's [contact]
/// bones), or, when it names none, every bone the model has.
std::vector<std::string> contact_bones(const KneeModel& model,
                                       const std::vector<std::string>& chosen);

/// The ligaments' names, joined by ", " (for messages).
std::string ligament_names(const std::vector<LigamentModel>& ligaments);

/// Up the leg: from the tibia's mean vertex to the femur's (a hint for the axis fit and the
/// pictures' up direction, not an anatomical axis).
Eigen::Vector3d proximal_direction(const KneeModel& model);

} // namespace ligsim::sim
