#pragma once
/// @brief Stage 7: the simulation model: tets, fibers with in-situ strain, nodes bound to bones.

#include "common/mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace ligsim::model {

struct Parameters {
  /// In-situ strain c of paper section 2.7: the fiber vector is scaled to (1 + c) a, so the
  /// fibers are under strain c in the rest shape. 2.9 % for the MCL (section 4.2).
  double in_situ_strain = 0.029;
};

struct Model {
  TetMesh mesh;
  Eigen::MatrixX3d fibers;       ///< #T x 3, length 1 + in-situ strain
  std::vector<bool> femur_nodes; ///< #V: nodes bound to the femur (moved with it)
  std::vector<bool> tibia_nodes; ///< #V: nodes bound to the tibia (fixed)
  int boundary_nodes = 0;        ///< nodes on the mesh surface
  int femur_nodes_unbound = 0;   ///< nodes the rule bound that no bound face supports
  int tibia_nodes_unbound = 0;
  double femur_area_mm2 = 0; ///< the mesh's boundary faces bound to the femur
  double tibia_area_mm2 = 0;
};

/// How boundary nodes are bound to a bone's attachment area.
enum class FootprintRule {
  /// A boundary node whose nearest ligament-surface triangle has at least two corners in the
  /// area, then freed unless it is a corner of a boundary face so bound
  /// (free_unsupported_nodes): each mesh draws the rim a little differently.
  nearest_triangle,
  /// The corners of every boundary face whose centroid's nearest point on the ligament's surface
  /// lies inside the area's rim (attachments::footprint_share above 0.5): on a mesh that keeps
  /// the rims as edges (attachments::footprint_rims) every mesh binds the same area.
  faces_inside_rim,
};

/// The nodes on the boundary of a tet mesh (on a face that belongs to one tet only).
std::vector<bool> boundary_nodes(const TetMesh& mesh);

/// A footprint is an area. A bound node that is not a corner of a boundary face (`faces`) whose
/// three corners are all bound is held alone or in a line: a point constraint, beside which the
/// fiber strain is singular (one such node on the female HRA MCL's femoral footprint carried
/// elements at 67 % fiber strain at 90 degrees of flexion). Frees those nodes, repeatedly, until
/// every bound node has a bound face; returns how many it freed.
int free_unsupported_nodes(const std::vector<std::array<int, 3>>& faces, std::vector<bool>& bound);

/// Builds the model, binding boundary nodes to each bone's attachment area (`femur_area`,
/// `tibia_area`: sorted ligament-surface vertex indices) by `rule`. A footprint so bound is an
/// area of faces, never a node alone or a line (a point constraint, beside which the fiber strain
/// is singular). Throws InputError if either bone binds no node, or if `directions` does not hold
/// one unit vector per tet.
Model assemble(const TetMesh& mesh, const Eigen::MatrixX3d& directions,
               const TriangleSurface& ligament, const std::vector<int>& femur_area,
               const std::vector<int>& tibia_area, const Parameters& parameters,
               FootprintRule rule = FootprintRule::nearest_triangle);

/// What close_footprints_in_bones did, per bone.
struct FootprintClosing {
  int femur_nodes = 0; ///< nodes added to the femoral footprint
  int tibia_nodes = 0; ///< nodes added to the tibial footprint
};

/// A segmented ligament overlaps its bones where it inserts, and a footprint made of boundary
/// nodes leaves the nodes among them free: interior nodes, and surface nodes the rule missed.
/// Held in place by their bound neighbours, those that lie inside the bone stay there however
/// the ligament settles. They are the insertion: a node inside a bone (ray parity against
/// `femur`, `tibia`; either may be null) that shares tets with more nodes bound to that bone than
/// free ones joins its footprint, repeated until none does; then every interior node inside the
/// bone that shares a tet with the footprint, and ring by ring deeper ones with no free surface
/// node beside them (contact holds the ligament's surface out of the bones, not its interior).
/// It does not spread along a ligament that merely lies in the bone beside its footprint, whose
/// nodes have free neighbours.
FootprintClosing close_footprints_in_bones(Model& model, const TriangleSurface* femur,
                                           const TriangleSurface* tibia);

/// A line: a point on it and a unit direction.
struct Axis {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;
};

/// The default knee flexion axis for a collateral ligament: through the femoral attachment
/// (the MCL's femoral insertion lies at the medial epicondyle, on the transepicondylar axis),
/// along the ligament's thinnest principal direction (a collateral ligament is a band lying
/// against the side of the knee, so its thickness runs mediolaterally). Oriented with x >= 0.
Axis default_flexion_axis(const TriangleSurface& ligament,
                          const Eigen::Vector3d& femoral_attachment);

} // namespace ligsim::model
