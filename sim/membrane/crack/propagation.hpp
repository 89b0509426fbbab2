#pragma once
/// @brief Crack propagation by one triangle (section 2.3): along the existing edge closest to
/// the direction (mode 1) or across the face, splitting it along the direction (mode 2), with
/// snapping to an existing edge wherever a split would make a triangle below the minimum angle
/// or area. Also the start of a crack inside an element and the scenes' initial cuts.

#include "sim/membrane/mesh/membrane_mesh.hpp"
#include "sim/membrane/mesh/topology.hpp"

#include <optional>
#include <vector>

namespace ligsim::membrane {

struct PropagationSettings {
  bool split_faces = true;                    ///< mode 2; false: along edges only (mode 1)
  double min_angle_rad = 10.0 * M_PI / 180.0; ///< no split makes a smaller triangle angle
  double min_area_mm2 = 1e-6;                 ///< no split makes a smaller triangle
};

/// One step of a crack: from node `from` to node `to` (rest positions kept, since the nodes
/// may be duplicated afterwards).
struct CrackAdvance {
  int from = -1;
  int to = -1;
  Vec2 from_rest = Vec2::Zero();
  Vec2 to_rest = Vec2::Zero();
  bool split_face = false; ///< mode 2 split a face (else the crack followed an edge)
  bool continues = false;  ///< `to` is an interior crack tip (not on a free boundary)
  TopologyEdit edit;
};

/// Extends a crack from node `tip` along the unit rest-frame direction `d` by one triangle;
/// duplicates the nodes whose fans the crack separates. Nothing if no uncut edge leaves the
/// tip within 90 degrees of d or d points out of the material.
std::optional<CrackAdvance> advance_crack(MembraneMesh& mesh, int tip, const Vec2& d,
                                          const PropagationSettings& settings);

/// Starts a crack in triangle `tri` along the line d: a node at the centroid (or, if that
/// split would break the quality bounds, the triangle's first vertex off the free boundary),
/// then one advance each way. Empty if neither is possible.
std::vector<CrackAdvance> initiate_crack(MembraneMesh& mesh, int tri, const Vec2& d,
                                         const PropagationSettings& settings);

/// A cut along a polyline (rest frame, mm), snapped to the mesh: from the node nearest the
/// first point, advancing towards each point in turn until within half an edge of it.
struct PolylineCut {
  std::vector<CrackAdvance> advances;
  int start_node = -1;                 ///< -1 if the cut starts on the free boundary
  int end_node = -1;                   ///< -1 if the cut ends on the free boundary
  Vec2 start_direction = Vec2::Zero(); ///< pointing out of the cut at its start
  Vec2 end_direction = Vec2::Zero();   ///< pointing out of the cut at its end
};
PolylineCut cut_polyline(MembraneMesh& mesh, const std::vector<Vec2>& points,
                         const PropagationSettings& settings);

} // namespace ligsim::membrane
