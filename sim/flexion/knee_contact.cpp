#include "sim/flexion/knee_contact.hpp"

#include "common/error.hpp"
#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/bone_penetration.hpp"
#include "sim/contact/contact_surface.hpp"
#include "sim/mesh/quadratic_tet.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <map>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

/// Edges used by one triangle only: the surface is open there.
int open_edges(const TriangleSurface& surface)
{
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      ++uses[std::minmax(surface.F(f, k), surface.F(f, (k + 1) % 3))];
  return static_cast<int>(
      std::count_if(uses.begin(), uses.end(), [](const auto& edge) { return edge.second == 1; }));
}

} // namespace

struct KneeContact::Bone {
  std::string name;
  std::unique_ptr<BoneLevelSet> grid;
  std::optional<RigidMotion> motion;
  std::vector<bool> bound;                      ///< per node: attached to this bone
  std::vector<bool> unchecked;                  ///< per node: left out of the penetration check
  std::unique_ptr<BonePenetration> penetration; ///< against the triangles, not the grid
};

KneeContact::KneeContact(const KneeModel& model, const BoundaryConditions& conditions,
                         const ContactConfig& config, const fs::path& cache_dir)
{
  validate(config);
  const std::vector<std::string> names = contact_bones(model, config.bones);
  const int node_count = static_cast<int>(model.mesh.V.rows());
  std::vector<ContactObstacle> obstacles;
  for (const std::string& name : names) {
    auto bone = std::make_unique<Bone>();
    bone->name = name;
    const TriangleSurface* triangles = bone_of(model, name);
    if (triangles == nullptr)
      fail("contact with the {}: the model has no {} surface", name, name);
    bone->grid = BoneLevelSet::cached(*triangles, config.grid, cache_dir / (name + ".vdb"));
    for (const ConstraintSet& set : conditions.constraints)
      if (set.name == name)
        bone->motion = set.rigid;
    // The fibula moves with the tibia (both fixed here: the femur carries the knee's motion).
    const std::vector<int>& attached = nodes_bound_to(model, name);
    bone->bound.assign(static_cast<std::size_t>(node_count), false);
    for (int n : attached)
      bone->bound[static_cast<std::size_t>(n)] = true;
    // A footprint's nodes may lie in the bone (the segmented ligament enters it), and so may
    // the middle of an edge from one of them to a free node: both are left out of the check.
    bone->unchecked = bone->bound;
    flag_mid_edge_nodes(model.tet10, bone->unchecked, FlaggedEnds::either);
    bone->penetration = std::make_unique<BonePenetration>(*triangles);
    m_figures.bones.push_back({name, cache_dir / (name + ".vdb"), bone->grid->figures(),
                               triangles->F.rows(), open_edges(*triangles)});
    obstacles.push_back({name, bone->grid.get(), bone->motion, attached});
    m_bones.push_back(std::move(bone));
  }
  m_surface = free_boundary_surface(model.mesh, conditions,
                                    model.tet10.rows() > 0 ? &model.tet10 : nullptr);
  m_node_count = node_count;
  m_potential = std::make_unique<ContactPotential>(node_count, m_surface, std::move(obstacles),
                                                   config.barrier);
  m_figures.surface_nodes = m_surface.nodes.size();
  m_figures.voxel_mm = config.grid.voxel_mm;
  m_figures.band_mm = config.grid.band_mm;
}

KneeContact::~KneeContact() = default;

std::vector<KneeContact::Gaps> KneeContact::gaps(const Eigen::VectorXd& x, double t) const
{
  const double d_hat = m_potential->settings().d_hat_mm;
  std::vector<Gaps> result;
  for (std::size_t b = 0; b < m_bones.size(); ++b) {
    Gaps gaps;
    gaps.bone = m_bones[b]->name;
    for (int n : m_surface.nodes) {
      if (m_bones[b]->bound[static_cast<std::size_t>(n)])
        continue;
      const double d = m_potential->distance(b, x.segment<3>(3 * n), t);
      gaps.min_gap_mm = std::min(gaps.min_gap_mm, d);
      if (d <= 0.0) {
        ++gaps.inside;
        gaps.inside_nodes.push_back(n);
      }
      gaps.within_d_hat += d < d_hat;
    }
    result.push_back(gaps);
  }
  return result;
}

std::unique_ptr<ContactPotential>
KneeContact::resting_bones_shrunk_by(const std::vector<double>& start_offsets_mm) const
{
  std::vector<ContactObstacle> obstacles = m_potential->obstacles();
  for (std::size_t b = 0; b < obstacles.size(); ++b) {
    obstacles[b].motion.reset();
    obstacles[b].start_offset_mm = b < start_offsets_mm.size() ? start_offsets_mm[b] : 0.0;
  }
  return std::make_unique<ContactPotential>(m_node_count, m_surface, std::move(obstacles),
                                            m_potential->settings());
}

std::vector<BoneContact> KneeContact::measure(const Eigen::VectorXd& x, double t, bool forces,
                                              Eigen::VectorXd& gap_mm,
                                              Eigen::VectorXd& pressure_mpa) const
{
  ContactMeasures measures = m_potential->measure(x, t);
  if (!forces) // a node inside a bone makes no sense of the barrier
    for (std::size_t b = 0; b < m_bones.size(); ++b) {
      measures.force_n[b].setZero();
      measures.area_mm2[b] = 0.0;
      measures.active_nodes[b] = 0;
      measures.pressure_mpa.setZero();
    }
  gap_mm = measures.gap_mm;
  pressure_mpa = measures.pressure_mpa;
  std::vector<BoneContact> result;
  for (std::size_t b = 0; b < m_bones.size(); ++b) {
    const Bone& bone = *m_bones[b];
    BoneContact contact;
    contact.bone = bone.name;
    contact.in_solve = forces;
    contact.force_n = measures.force_n[b];
    contact.area_mm2 = measures.area_mm2[b];
    contact.nodes = measures.active_nodes[b];
    contact.min_gap_mm = measures.min_gap_mm[b];
    // Back into the bone's rest frame, where its triangles are.
    const Eigen::Isometry3d to_rest =
        bone.motion ? bone.motion->pose(t).inverse() : Eigen::Isometry3d::Identity();
    for (Eigen::Index n = 0; n < x.size() / 3; ++n) {
      if (bone.unchecked[static_cast<std::size_t>(n)])
        continue;
      const Eigen::Vector3d p = to_rest * Eigen::Vector3d(x.segment<3>(3 * n));
      contact.penetration_mm = std::max(contact.penetration_mm, bone.penetration->depth_mm(p));
    }
    result.push_back(contact);
  }
  return result;
}

} // namespace ligsim::sim
