#pragma once
/// @brief Topological edits of a tearing membrane: splitting sides, inserting a vertex,
/// cutting an edge, duplicating nodes whose fans a crack separates; and the manifold check.
///
/// Edits keep every triangle counter-clockwise and partition split triangles exactly, so the
/// total rest area is conserved. A split triangle's children inherit its fiber angle and the
/// flags of the sides they inherit; new nodes interpolate positions, velocities and
/// constraints. Callers rebuild the incidence after an edit (build_incidence is O(#triangles)).

#include "sim/membrane/mesh/membrane_mesh.hpp"

#include <optional>
#include <string>
#include <vector>

namespace ligsim::membrane {

/// Side `side` (0..2) of triangle `triangle`: the edge (v_side, v_side+1).
struct SideRef {
  int triangle = -1;
  int side = -1;
};

/// What an edit changed: triangles created or rewritten (each with the triangle it came from,
/// itself if rewritten in place), nodes created, and nodes that lost triangles to a copy.
struct TopologyEdit {
  std::vector<int> triangles;
  std::vector<int> parents;
  std::vector<int> new_nodes;
  std::vector<int> split_nodes;

  void touch(int triangle, int parent)
  {
    triangles.push_back(triangle);
    parents.push_back(parent);
  }
};

/// The side of another triangle with the same two nodes, if any (crack faces that have not
/// opened yet still share their nodes).
std::optional<SideRef> opposite_side(const MembraneMesh& mesh, const NodeIncidence& incidence,
                                     SideRef side);

/// True if the triangles around `node` surround it (their rest angles there sum to 360
/// degrees): an interior node or a crack tip, not a node of the outer boundary or of a crack
/// face behind the tip.
bool is_enclosed(const MembraneMesh& mesh, const NodeIncidence& incidence, int node);

/// True if the edge (a, b) exists, has a triangle on each side and is not cut.
bool is_cuttable_edge(const MembraneMesh& mesh, const NodeIncidence& incidence, int a, int b);

/// Smallest angle (rad) and smallest area (mm^2) of the triangles an edit would create.
struct SplitQuality {
  double min_angle_rad = 0.0;
  double min_area_mm2 = 0.0;
};

/// Quality of split_side(mesh, incidence, side, t) without doing it.
SplitQuality side_split_quality(const MembraneMesh& mesh, const NodeIncidence& incidence,
                                SideRef side, double t);

/// Inserts a node on the side at parameter t (0 at v_side) and splits the triangle and its
/// neighbour across the side, if any, in two each. Returns the new node.
int split_side(MembraneMesh& mesh, const NodeIncidence& incidence, SideRef side, double t,
               TopologyEdit& edit);

/// Quality of insert_centroid(mesh, tri) without doing it.
SplitQuality centroid_quality(const MembraneMesh& mesh, int tri);

/// Inserts a node at the centroid of `tri` and splits it in three. Returns the new node.
int insert_centroid(MembraneMesh& mesh, int tri, TopologyEdit& edit);

/// Flags the edge (a, b) as cut on both its triangles. Requires is_cuttable_edge.
void cut_edge(MembraneMesh& mesh, const NodeIncidence& incidence, int a, int b);

/// Groups the triangles around `node` into fans connected through uncut shared sides and gives
/// every fan but the first a copy of the node. Returns the copies (empty if one fan).
std::vector<int> split_fans(MembraneMesh& mesh, const NodeIncidence& incidence, int node,
                            TopologyEdit& edit);

/// Empty if the mesh is a valid oriented 2-manifold with boundary: positive rest areas, every
/// edge in one triangle or in two with opposite orientations, every node in at least one
/// triangle with a single fan (its link a path or a cycle), cut flags equal on both sides of a
/// shared edge. Otherwise the first problem found, in words.
std::string manifold_problem(const MembraneMesh& mesh);

} // namespace ligsim::membrane
