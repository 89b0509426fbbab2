#pragma once
/// @brief A bone surface as an OpenVDB narrow-band signed distance grid (tools::meshToLevelSet),
/// sampled by a quadratic B-spline over 3 x 3 x 3 voxels: C1 distance, exact gradient and
/// Hessian of the interpolant. OpenVDB stays inside bone_level_set.cpp.

#include "common/mesh.hpp"
#include "sim/contact/distance_field.hpp"

#include <filesystem>
#include <memory>

namespace ligsim::sim {

struct LevelSetSettings {
  double voxel_mm = 0.2;
  double band_mm = 1.0; ///< the exact distance is kept this far on each side of the surface
};

/// What building or reading a grid found.
struct LevelSetFigures {
  bool reused = false;    ///< read from the cache instead of built
  double build_s = 0.0;   ///< wall time of building or reading
  long active_voxels = 0; ///< voxels of the narrow band
  std::size_t memory_bytes = 0;
};

class BoneLevelSet final : public DistanceField {
public:
  /// Builds the grid of `surface` (mm). Throws InputError for an empty surface or bad settings.
  BoneLevelSet(const TriangleSurface& surface, const LevelSetSettings& settings);
  /// The grid of `surface` from `cache_file` when that was written for the same surface and
  /// settings, otherwise built and written there (atomically).
  static std::unique_ptr<BoneLevelSet> cached(const TriangleSurface& surface,
                                              const LevelSetSettings& settings,
                                              const std::filesystem::path& cache_file);
  ~BoneLevelSet() override;
  BoneLevelSet(BoneLevelSet&&) noexcept;

  DistanceSample sample(const Eigen::Vector3d& p_mm, bool with_hessian) const override;
  /// The value of the nearest voxel minus two voxels: a cheap lower bound of sample().
  double distance_bound(const Eigen::Vector3d& p_mm) const override;
  /// The grid's background (beyond its band) minus two voxels.
  double bound_limit_mm() const override;
  Eigen::AlignedBox3d near_box() const override { return m_box; }
  double band_mm() const { return m_band_mm; }
  const LevelSetFigures& figures() const { return m_figures; }

private:
  struct Grid;
  BoneLevelSet() = default;
  void finish();

  std::unique_ptr<Grid> m_grid;
  Eigen::AlignedBox3d m_box; ///< the band's bounding box, mm
  double m_voxel_mm = 0.0;
  double m_band_mm = 0.0;
  LevelSetFigures m_figures;
};

} // namespace ligsim::sim
