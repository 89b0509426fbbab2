#pragma once
/// @brief A ligament's peak fiber strain over regions of a set size rather than single
/// elements. A footprint bound rigidly to its bone is a sharp corner of the problem: the strain
/// of the elements at its edge grows as the mesh is refined, so their maximum says more about the
/// mesh than about the ligament. Experiments measure strain over regions millimetres wide
/// (markers on the ligament's surface), and so does this: the volume-weighted mean of the
/// elements whose rest centroids lie within a radius, maximised over the ligament.

#include <Eigen/Core>

#include <cstdint>
#include <optional>
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
  /// Calls visit(e, candidates) for every element with the elements of the 27 cells about its
  /// own; stops when visit returns false.
  template <class Visit> void for_each_region(Visit&& visit) const;
  void list_regions() const;

  double m_radius_mm;
  Eigen::MatrixX3d m_centroids;
  Eigen::VectorXd m_volumes;
  /// The elements in each grid cell of edge radius_mm (a region lies within 27 cells).
  std::unordered_map<std::int64_t, std::vector<int>> m_cells;
  /// Each element's region, listed at the first max_mean() where the lists stay under
  /// kMaxListed entries (a live view asks every frame); a fine mesh's regions hold thousands of
  /// elements each, and are found anew at each call instead.
  struct Regions {
    std::vector<int> start; ///< element e's region is members[start[e] .. start[e + 1])
    std::vector<int> members;
    Eigen::VectorXd volume; ///< each region's volume
  };
  mutable std::optional<Regions> m_regions;
  mutable bool m_too_many = false;
};

} // namespace ligsim::sim
