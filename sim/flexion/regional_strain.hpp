#pragma once
/// @brief A ligament's peak fiber strain over regions of a set size rather than single
/// elements. A footprint bound rigidly to its bone is a sharp corner of the problem: the strain
/// of the elements at its edge grows as the mesh is refined, so their maximum says more about the
/// mesh than about the ligament. Experiments measure strain over regions millimetres wide
/// (markers on the ligament's surface), and so does this: the volume-weighted mean of the
/// elements whose rest centroids lie within a radius, maximised over the ligament.

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace ligsim::sim {

class RegionalMean {
public:
  /// Regions of `radius_mm` about each element's centroid; `centroids` #T x 3 (mm, rest),
  /// `volumes` #T (mm^3, rest).
  RegionalMean(const Eigen::MatrixX3d& centroids, const Eigen::VectorXd& volumes, double radius_mm);

  double radius_mm() const { return m_radius_mm; }
  /// The volume-weighted mean of `per_element` (#T) over element e's region.
  double mean(const Eigen::VectorXd& per_element, Eigen::Index e) const;
  /// The largest regional mean of `per_element` over all elements.
  double max_mean(const Eigen::VectorXd& per_element) const;

private:
  double m_radius_mm;
  Eigen::MatrixX3d m_centroids;
  Eigen::VectorXd m_volumes;
  /// The elements in each grid cell of edge radius_mm (a region lies within 27 cells): found
  /// anew at each call, since a region list per element would take hundreds of entries each.
  std::unordered_map<std::int64_t, std::vector<int>> m_cells;
};

} // namespace ligsim::sim
