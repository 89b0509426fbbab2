#pragma once
/// @brief How close the ligaments of a knee come to each other at one state (the ACL and PCL
/// cross): per pair the closest distance between their deformed surfaces and the surface nodes of
/// one that lie inside the other (generalized winding number), with the depth of the deepest.
/// The distances are node to triangle, both ways: an edge-edge approach closer than any node is
/// not seen.

#include "common/mesh.hpp"
#include "sim/flexion/knee_model.hpp"

#include <Eigen/Core>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace ligsim::sim {

struct LigamentPair {
  std::string first, second;
  double closest_mm = INFINITY; ///< 0 where they interpenetrate
  int nodes_inside = 0;         ///< surface nodes of either inside the other
  double deepest_mm = 0.0;      ///< of those, the farthest from the other's surface
};

/// One ligament at one state.
struct LigamentState {
  std::string name;
  const TetMesh* mesh = nullptr;      ///< rest mesh (its topology)
  const Eigen::VectorXd* x = nullptr; ///< positions, flat, mm
};

/// Every pair of `ligaments`, in order (0-1, 0-2, ..., 1-2, ...).
std::vector<LigamentPair> measure_pairs(const std::vector<LigamentState>& ligaments);

/// One pair at one angle of a sweep.
struct PairAtAngle {
  double angle_deg = 0.0;
  LigamentPair pair;
};

/// Per angle that every ligament reached (`states`: per angle, per ligament of `ligaments`, the
/// positions; an empty vector where one did not reach it): every pair, into `<out>/pairs.csv`
/// and the returned list, with a warning on stderr where two interpenetrate.
std::vector<PairAtAngle>
pairs_over_sweep(const std::vector<LigamentModel>& ligaments,
                 const std::map<double, std::vector<Eigen::VectorXd>>& states,
                 const std::filesystem::path& out);

} // namespace ligsim::sim
