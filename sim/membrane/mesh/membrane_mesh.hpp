#pragma once
/// @brief A planar membrane mesh whose topology changes while it tears: nodes with their
/// dynamic state, triangles with their fiber angle and the flags of their sides.
///
/// Triangles are counter-clockwise in the rest configuration. Side k of a triangle is the edge
/// (v_k, v_{k+1 mod 3}). A crack is a set of sides flagged `cut`; where the cut sides around a
/// node separate its triangles into several fans, the node is duplicated (see topology.hpp),
/// so an open crack has two faces with distinct nodes. Two triangles are neighbours when they
/// share a node pair.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace ligsim::membrane {

using Vec2 = Eigen::Vector2d;
using Triangle = std::array<int, 3>;

/// A node is free or has a prescribed velocity (zero for a fixed node).
enum class NodeConstraint : std::uint8_t { free, prescribed };

struct MembraneMesh {
  // Nodes.
  std::vector<Vec2> rest;                 ///< rest position, mm
  std::vector<Vec2> position;             ///< current position, mm
  std::vector<Vec2> velocity;             ///< mm/s
  std::vector<Vec2> last_velocity_change; ///< the last step's solve, warm start of the next, mm/s
  std::vector<double> mass;               ///< lumped mass, t
  std::vector<NodeConstraint> constraint;
  std::vector<Vec2> prescribed_velocity; ///< mm/s, used where constraint is prescribed

  // Triangles.
  std::vector<Triangle> triangles;
  std::vector<double> fiber_angle_rad;       ///< fiber direction from the rest x axis
  std::vector<std::array<bool, 3>> side_cut; ///< side k is a crack face
  /// Load group of side k (0: none). Only sides of the original boundary carry one.
  std::vector<std::array<std::uint8_t, 3>> side_load;

  int node_count() const { return static_cast<int>(rest.size()); }
  int triangle_count() const { return static_cast<int>(triangles.size()); }

  /// Appends a free node at rest, without velocity; returns its index.
  int add_node(const Vec2& rest_position);
  /// Appends a node on the segment (b, c) at parameter t (0 at b): positions, velocities
  /// interpolated; prescribed only where both ends are (with the interpolated velocity).
  int add_node_between(int b, int c, double t);
  /// Appends a node at the centroid of triangle `tri`, prescribed only if all three are.
  int add_node_at_centroid(int tri);
  /// Appends a copy of node v (a crack duplicates nodes); returns its index.
  int add_node_copy(int v);

  /// Appends a triangle with the fiber angle and side flags given; returns its index.
  int add_triangle(const Triangle& nodes, double fiber_angle, const std::array<bool, 3>& cut,
                   const std::array<std::uint8_t, 3>& load);
};

/// Triangles around each node, in compressed rows: triangles of node v are
/// triangle[offset[v] .. offset[v+1]).
struct NodeIncidence {
  std::vector<int> offset;
  std::vector<int> triangle;

  int count(int node) const { return offset[node + 1] - offset[node]; }
  const int* begin(int node) const { return triangle.data() + offset[node]; }
  const int* end(int node) const { return triangle.data() + offset[node + 1]; }
};

NodeIncidence build_incidence(const MembraneMesh& mesh);

/// Rest area of triangle `tri`, mm^2 (positive for counter-clockwise).
double rest_area(const MembraneMesh& mesh, int tri);
/// Signed area of the triangle (a, b, c), mm^2.
double signed_area(const Vec2& a, const Vec2& b, const Vec2& c);
/// Smallest interior angle of the triangle (a, b, c), radians.
double min_angle(const Vec2& a, const Vec2& b, const Vec2& c);
/// Smallest interior angle over the mesh, radians (rest configuration).
double min_rest_angle(const MembraneMesh& mesh);

/// The crack faces: pairs of node indices of the sides flagged cut, each side once.
std::vector<std::array<int, 2>> crack_edges(const MembraneMesh& mesh);
/// Recomputes the lumped mass of `nodes` from their triangles: rho h A / 3 each.
void update_lumped_masses(MembraneMesh& mesh, const NodeIncidence& incidence,
                          double areal_density_t_per_mm2, const std::vector<int>& nodes);

/// The local index (0..2) of node v in the triangle, or -1.
inline int local_index(const Triangle& t, int v)
{
  return t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : -1;
}

/// 2-D cross product (z component).
inline double cross(const Vec2& a, const Vec2& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

} // namespace ligsim::membrane
