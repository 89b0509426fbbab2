#include "sim/contact/bone_level_set.hpp"

#include "common/atomic_file.hpp"
#include "common/content_hash.hpp"
#include "common/error.hpp"
#include "common/resources.hpp"
#include "common/vdb_file_id.hpp"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <chrono>
#include <cmath>
#include <mutex>

namespace ligsim::sim {

namespace {

/// Bumped whenever the grid's construction changes, so old caches are rebuilt.
constexpr const char* cache_version = "ligsim-bone-level-set-1";
constexpr const char* key_name = "ligsim_key";

void initialize_openvdb()
{
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::string cache_key(const TriangleSurface& surface, const LevelSetSettings& settings)
{
  ContentHash hash;
  hash.add(cache_version);
  hash.add(std::string_view(reinterpret_cast<const char*>(surface.V.data()),
                            sizeof(double) * static_cast<std::size_t>(surface.V.size())));
  hash.add(std::string_view(reinterpret_cast<const char*>(surface.F.data()),
                            sizeof(int) * static_cast<std::size_t>(surface.F.size())));
  hash.add(std::to_string(settings.voxel_mm)).add(std::to_string(settings.band_mm));
  return hash.hex();
}

/// Quadratic B-spline weights of the voxels -1, 0, +1 about the nearest one, and their first
/// and second derivatives, at offset f in [-0.5, 0.5] (voxel units).
struct Weights {
  double w[3], d[3], dd[3];
};

Weights bspline_weights(double f)
{
  return {{0.5 * (0.5 - f) * (0.5 - f), 0.75 - f * f, 0.5 * (0.5 + f) * (0.5 + f)},
          {f - 0.5, -2.0 * f, 0.5 + f},
          {1.0, -2.0, 1.0}};
}

} // namespace

struct BoneLevelSet::Grid {
  openvdb::FloatGrid::Ptr grid;
};

BoneLevelSet::BoneLevelSet(const TriangleSurface& surface, const LevelSetSettings& settings)
    : m_grid(std::make_unique<Grid>())
{
  const auto start = std::chrono::steady_clock::now();
  if (surface.V.rows() == 0 || surface.F.rows() == 0)
    fail("contact: the bone surface has no triangles");
  if (!(settings.voxel_mm > 0.0) || !(settings.band_mm >= settings.voxel_mm))
    fail("contact: voxel_mm must be positive and the band at least one voxel (voxel {} mm, band "
         "{} mm)",
         settings.voxel_mm, settings.band_mm);
  initialize_openvdb();
  std::vector<openvdb::Vec3s> points(static_cast<std::size_t>(surface.V.rows()));
  for (Eigen::Index i = 0; i < surface.V.rows(); ++i)
    points[static_cast<std::size_t>(i)] =
        openvdb::Vec3s(static_cast<float>(surface.V(i, 0)), static_cast<float>(surface.V(i, 1)),
                       static_cast<float>(surface.V(i, 2)));
  std::vector<openvdb::Vec3I> triangles(static_cast<std::size_t>(surface.F.rows()));
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    triangles[static_cast<std::size_t>(f)] = openvdb::Vec3I(static_cast<unsigned>(surface.F(f, 0)),
                                                            static_cast<unsigned>(surface.F(f, 1)),
                                                            static_cast<unsigned>(surface.F(f, 2)));
  const auto transform = openvdb::math::Transform::createLinearTransform(settings.voxel_mm);
  // Two voxels beyond the band so that the B-spline's stencil stays on exact values there.
  const float half_width = static_cast<float>(std::ceil(settings.band_mm / settings.voxel_mm) + 2);
  m_grid->grid =
      openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*transform, points, triangles, half_width);
  m_voxel_mm = settings.voxel_mm;
  m_band_mm = settings.band_mm;
  finish();
  m_figures.build_s = seconds_since(start);
}

BoneLevelSet::~BoneLevelSet() = default;
BoneLevelSet::BoneLevelSet(BoneLevelSet&&) noexcept = default;

void BoneLevelSet::finish()
{
  const openvdb::CoordBBox box = m_grid->grid->evalActiveVoxelBoundingBox();
  m_box = Eigen::AlignedBox3d(
      Eigen::Vector3d(box.min().x(), box.min().y(), box.min().z()) * m_voxel_mm,
      Eigen::Vector3d(box.max().x(), box.max().y(), box.max().z()) * m_voxel_mm);
  m_figures.active_voxels = static_cast<long>(m_grid->grid->activeVoxelCount());
  m_figures.memory_bytes = static_cast<std::size_t>(m_grid->grid->memUsage());
}

std::unique_ptr<BoneLevelSet> BoneLevelSet::cached(const TriangleSurface& surface,
                                                   const LevelSetSettings& settings,
                                                   const std::filesystem::path& cache_file)
{
  initialize_openvdb();
  const auto start = std::chrono::steady_clock::now();
  const std::string key = cache_key(surface, settings);
  if (std::filesystem::exists(cache_file)) {
    try {
      openvdb::io::File file(cache_file.string());
      file.open();
      const openvdb::MetaMap::Ptr meta = file.getMetadata();
      const bool same = meta && (*meta)[key_name] && meta->metaValue<std::string>(key_name) == key;
      if (same) {
        auto level_set = std::unique_ptr<BoneLevelSet>(new BoneLevelSet());
        level_set->m_grid = std::make_unique<Grid>();
        level_set->m_grid->grid =
            openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("distance"));
        file.close();
        if (level_set->m_grid->grid) {
          level_set->m_voxel_mm = settings.voxel_mm;
          level_set->m_band_mm = settings.band_mm;
          level_set->finish();
          level_set->m_figures.reused = true;
          level_set->m_figures.build_s = seconds_since(start);
          return level_set;
        }
      }
    } catch (const openvdb::Exception&) {
      // An unreadable cache is rebuilt below.
    }
  }
  auto level_set = std::make_unique<BoneLevelSet>(surface, settings);
  ensure_directory(cache_file.parent_path());
  AtomicFile out(cache_file);
  openvdb::GridPtrVec grids;
  level_set->m_grid->grid->setName("distance");
  grids.push_back(level_set->m_grid->grid);
  openvdb::MetaMap meta;
  meta.insertMeta(key_name, openvdb::StringMetadata(key));
  openvdb::io::File file(out.temp_path().string());
  file.write(grids, meta);
  file.close();
  make_vdb_file_id_reproducible(out.temp_path());
  out.commit();
  return level_set;
}

DistanceSample BoneLevelSet::sample(const Eigen::Vector3d& p_mm, bool with_hessian) const
{
  // Not registered with the tree (no lock, no hash map): the grid never changes after it is
  // built.
  openvdb::tree::ValueAccessor<const openvdb::FloatTree, false> access(m_grid->grid->tree());
  const Eigen::Vector3d u = p_mm / m_voxel_mm; // voxel centres at integer coordinates
  int base[3];
  Weights weights[3];
  for (int a = 0; a < 3; ++a) {
    base[a] = static_cast<int>(std::lround(u(a)));
    weights[a] = bspline_weights(u(a) - base[a]);
  }
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double v =
            access.getValue(openvdb::Coord(base[0] + i - 1, base[1] + j - 1, base[2] + k - 1));
        const Weights& x = weights[0];
        const Weights& y = weights[1];
        const Weights& z = weights[2];
        value += x.w[i] * y.w[j] * z.w[k] * v;
        gradient += v * Eigen::Vector3d(x.d[i] * y.w[j] * z.w[k], x.w[i] * y.d[j] * z.w[k],
                                        x.w[i] * y.w[j] * z.d[k]);
        if (with_hessian) {
          hessian(0, 0) += v * x.dd[i] * y.w[j] * z.w[k];
          hessian(1, 1) += v * x.w[i] * y.dd[j] * z.w[k];
          hessian(2, 2) += v * x.w[i] * y.w[j] * z.dd[k];
          hessian(0, 1) += v * x.d[i] * y.d[j] * z.w[k];
          hessian(0, 2) += v * x.d[i] * y.w[j] * z.d[k];
          hessian(1, 2) += v * x.w[i] * y.d[j] * z.d[k];
        }
      }
  DistanceSample s;
  s.distance_mm = value;
  s.gradient = gradient / m_voxel_mm;
  if (with_hessian) {
    hessian(1, 0) = hessian(0, 1);
    hessian(2, 0) = hessian(0, 2);
    hessian(2, 1) = hessian(1, 2);
    s.hessian = hessian / (m_voxel_mm * m_voxel_mm);
  }
  return s;
}

double BoneLevelSet::distance_bound(const Eigen::Vector3d& p_mm) const
{
  const Eigen::Vector3d u = p_mm / m_voxel_mm;
  const openvdb::Coord nearest(static_cast<int>(std::lround(u(0))),
                               static_cast<int>(std::lround(u(1))),
                               static_cast<int>(std::lround(u(2))));
  return m_grid->grid->tree().getValue(nearest) - 2.0 * m_voxel_mm;
}

double BoneLevelSet::bound_limit_mm() const
{
  return m_grid->grid->background() - 2.0 * m_voxel_mm;
}

} // namespace ligsim::sim
