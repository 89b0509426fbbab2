#pragma once
/// @brief A sparse regular voxel grid with isotropic spacing: the images of the model-building
/// stages. Values live in bricks of 8 x 8 x 8 voxels allocated where something is stored, so the
/// memory grows with the ligament's volume, not its bounding box.

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace ligsim {

/// Values at voxel centres; voxel (i, j, k) sits at origin + spacing * (i, j, k), mm.
/// A voxel whose brick is not allocated holds the background value. Linear voxel indices
/// (index(), ijk(), at()) are x-fastest over the whole box, as in VTK's image data. The bricks
/// line up with OpenVDB's leaf nodes (8^3 voxels at multiples of 8).
template <class T> class Grid {
public:
  static constexpr int kBrickBits = 3;
  static constexpr int kBrickEdge = 1 << kBrickBits; ///< voxels along a brick's edge
  static constexpr int kBrickVoxels = kBrickEdge * kBrickEdge * kBrickEdge;

  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(); ///< centre of voxel (0, 0, 0), mm
  double spacing = 1.0;                             ///< voxel edge, mm

  Grid() = default;
  Grid(const Eigen::Vector3i& dims_, const Eigen::Vector3d& origin_, double spacing_,
       T background = T{})
      : dims(dims_)
      , origin(origin_)
      , spacing(spacing_)
      , m_brick_dims((dims_.array() + kBrickEdge - 1) / kBrickEdge)
      , m_slot_of_brick(
            static_cast<std::size_t>(m_brick_dims.x()) * m_brick_dims.y() * m_brick_dims.z(), -1)
      , m_background(background)
  {
  }

  /// Same geometry as `other`, no brick allocated.
  template <class U> static Grid like(const Grid<U>& other, T background = T{})
  {
    return Grid(other.dims, other.origin, other.spacing, background);
  }
  /// Same geometry and the same bricks as `other`, filled with `background`: writes into them
  /// through find() are then safe from several threads.
  template <class U> static Grid with_bricks_of(const Grid<U>& other, T background = T{})
  {
    Grid grid = like(other, background);
    grid.reserve_bricks(other.brick_count());
    for (std::size_t b = 0; b < other.brick_count(); ++b)
      grid.allocate_brick(other.brick_origin(b));
    return grid;
  }

  /// A copy without the bricks that hold nothing but the background.
  Grid pruned() const
  {
    Grid result = like(*this, m_background);
    for (std::size_t b = 0; b < brick_count(); ++b) {
      const T* values = &m_values[b * kBrickVoxels];
      if (std::all_of(values, values + kBrickVoxels, [&](const T& v) { return v == m_background; }))
        continue;
      result.allocate_brick(m_brick_origin[b]);
      std::copy(values, values + kBrickVoxels, result.m_values.end() - kBrickVoxels);
    }
    return result;
  }

  const T& background() const { return m_background; }
  /// Voxels of the whole box (most of them are not stored).
  std::size_t voxel_count() const
  {
    return static_cast<std::size_t>(dims.x()) * dims.y() * dims.z();
  }
  std::size_t brick_count() const { return m_brick_origin.size(); }
  /// Bytes held: the stored bricks and the brick table.
  std::size_t memory_bytes() const
  {
    return m_values.capacity() * sizeof(T) + m_slot_of_brick.size() * sizeof(std::int32_t) +
           m_brick_origin.capacity() * sizeof(Eigen::Vector3i);
  }

  std::size_t index(int i, int j, int k) const
  {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims.x()) * (j + static_cast<std::size_t>(dims.y()) * k);
  }
  Eigen::Vector3i ijk(std::size_t index) const
  {
    const auto nx = static_cast<std::size_t>(dims.x());
    const auto ny = static_cast<std::size_t>(dims.y());
    return {static_cast<int>(index % nx), static_cast<int>((index / nx) % ny),
            static_cast<int>(index / (nx * ny))};
  }
  bool contains(int i, int j, int k) const
  {
    return i >= 0 && j >= 0 && k >= 0 && i < dims.x() && j < dims.y() && k < dims.z();
  }
  bool contains(const Eigen::Vector3i& v) const { return contains(v.x(), v.y(), v.z()); }
  Eigen::Vector3d point(int i, int j, int k) const
  {
    return origin + spacing * Eigen::Vector3d(i, j, k);
  }
  Eigen::Vector3d point(std::size_t index) const { return point_of(ijk(index)); }
  Eigen::Vector3d point_of(const Eigen::Vector3i& v) const { return point(v.x(), v.y(), v.z()); }
  /// Continuous voxel coordinates of a point (voxel centres at integers).
  Eigen::Vector3d voxel_coordinates(const Eigen::Vector3d& p) const
  {
    return (p - origin) / spacing;
  }

  /// The value of voxel (i, j, k), which must lie in the box.
  const T& operator()(int i, int j, int k) const
  {
    const std::int32_t slot = m_slot_of_brick[brick_cell(i, j, k)];
    return slot < 0 ? m_background : m_values[offset(slot, i, j, k)];
  }
  const T& operator()(const Eigen::Vector3i& v) const { return (*this)(v.x(), v.y(), v.z()); }
  /// The value at a linear index over the box.
  const T& at(std::size_t index) const
  {
    const Eigen::Vector3i v = ijk(index);
    return (*this)(v.x(), v.y(), v.z());
  }
  /// The stored value of voxel (i, j, k), or nullptr if its brick is not allocated.
  T* find(int i, int j, int k)
  {
    const std::int32_t slot = m_slot_of_brick[brick_cell(i, j, k)];
    return slot < 0 ? nullptr : &m_values[offset(slot, i, j, k)];
  }
  /// Stores a value, allocating its brick (not safe from several threads at once).
  void set(int i, int j, int k, const T& value)
  {
    allocate_brick({i, j, k});
    *find(i, j, k) = value;
  }

  void reserve_bricks(std::size_t count)
  {
    m_values.reserve(count * kBrickVoxels);
    m_brick_origin.reserve(count);
  }
  /// Allocates (filled with the background) the brick that holds voxel v, if not yet there.
  void allocate_brick(const Eigen::Vector3i& v)
  {
    std::int32_t& slot = m_slot_of_brick[brick_cell(v.x(), v.y(), v.z())];
    if (slot >= 0)
      return;
    slot = static_cast<std::int32_t>(m_brick_origin.size());
    m_brick_origin.push_back(
        Eigen::Vector3i(v.x() >> kBrickBits, v.y() >> kBrickBits, v.z() >> kBrickBits) *
        kBrickEdge);
    m_values.resize(m_values.size() + kBrickVoxels, m_background);
  }
  /// The first voxel of stored brick b (0 <= b < brick_count()).
  const Eigen::Vector3i& brick_origin(std::size_t b) const { return m_brick_origin[b]; }

  /// Calls visit(ijk, value) for every voxel of the stored bricks that lies in the box.
  template <class Visit> void for_each_stored(Visit&& visit) const
  {
    for (std::size_t b = 0; b < brick_count(); ++b)
      for_each_in_brick(b, visit);
  }
  /// Calls visit(ijk, value) for the voxels of stored brick b that lie in the box.
  template <class Visit> void for_each_in_brick(std::size_t b, Visit&& visit) const
  {
    const Eigen::Vector3i o = m_brick_origin[b];
    const T* values = &m_values[b * kBrickVoxels];
    for (int c = 0; c < kBrickEdge; ++c)
      for (int r = 0; r < kBrickEdge; ++r)
        for (int s = 0; s < kBrickEdge; ++s) {
          const Eigen::Vector3i v = o + Eigen::Vector3i(s, r, c);
          if (v.x() < dims.x() && v.y() < dims.y() && v.z() < dims.z())
            visit(v, values[s + kBrickEdge * (r + kBrickEdge * c)]);
        }
  }

private:
  std::size_t brick_cell(int i, int j, int k) const
  {
    return static_cast<std::size_t>(i >> kBrickBits) +
           static_cast<std::size_t>(m_brick_dims.x()) *
               (static_cast<std::size_t>(j >> kBrickBits) +
                static_cast<std::size_t>(m_brick_dims.y()) *
                    static_cast<std::size_t>(k >> kBrickBits));
  }
  static std::size_t offset(std::int32_t slot, int i, int j, int k)
  {
    constexpr int m = kBrickEdge - 1;
    return static_cast<std::size_t>(slot) * kBrickVoxels +
           static_cast<std::size_t>((i & m) + kBrickEdge * ((j & m) + kBrickEdge * (k & m)));
  }

  Eigen::Vector3i m_brick_dims = Eigen::Vector3i::Zero();
  std::vector<std::int32_t> m_slot_of_brick;   ///< per brick of the box: slot or -1
  std::vector<Eigen::Vector3i> m_brick_origin; ///< per slot
  std::vector<T> m_values;                     ///< kBrickVoxels per slot
  T m_background{};
};

using Mask = Grid<std::uint8_t>; ///< 1 inside the surface, 0 outside
using ScalarGrid = Grid<float>;

/// Voxels of `mask` that are inside (non-zero).
std::size_t inside_count(const Mask& mask);

/// The 26 neighbour offsets of a voxel.
const std::vector<Eigen::Vector3i>& neighbourhood_26();

} // namespace ligsim
