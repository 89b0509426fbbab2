#include "sim/flexion/knee_contact.hpp"

#include "common/error.hpp"
#include "sim/contact/bone_level_set.hpp"
#include "sim/contact/bone_penetration.hpp"
#include "sim/contact/contact_surface.hpp"

#include <Eigen/Geometry>
#include <vtkPolyData.h>

#include <algorithm>
#include <map>

namespace ligsim::sim {

namespace fs = std::filesystem;

namespace {

/// Edges used by one triangle only: the surface is open there.
long open_edges(const TriangleSurface& surface)
{
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      ++uses[std::minmax(surface.F(f, k), surface.F(f, (k + 1) % 3))];
  return std::count_if(uses.begin(), uses.end(), [](const auto& edge) { return edge.second == 1; });
}

} // namespace

struct KneeContact::Bone {
  std::string name;
  std::unique_ptr<BoneLevelSet> grid;
  std::optional<RigidMotion> motion;
  std::vector<bool> bound;                      ///< per node: attached to this bone
  std::unique_ptr<BonePenetration> penetration; ///< against the triangles, not the grid
};

KneeContact::KneeContact(const KneeModel& model, const BoundaryConditions& conditions,
                         const ContactConfig& config, const fs::path& cache_dir)
{
  validate(config);
  const std::vector<std::string> names =
      config.bones.empty() ? std::vector<std::string>{"femur", "tibia"} : config.bones;
  const int node_count = static_cast<int>(model.mesh.V.rows());
  std::vector<ContactObstacle> obstacles;
  for (const std::string& name : names) {
    auto bone = std::make_unique<Bone>();
    bone->name = name;
    vtkPolyData* surface = name == "femur" ? model.femur : model.tibia;
    const TriangleSurface triangles = triangle_surface(surface, name + ".vtp");
    bone->grid = BoneLevelSet::cached(triangles, config.grid, cache_dir / (name + ".vdb"));
    for (const ConstraintSet& set : conditions.constraints)
      if (set.name == name)
        bone->motion = set.rigid;
    const std::vector<int>& attached = name == "femur" ? model.femur_nodes : model.tibia_nodes;
    bone->bound.assign(static_cast<std::size_t>(node_count), false);
    for (int n : attached)
      bone->bound[static_cast<std::size_t>(n)] = true;
    bone->penetration = std::make_unique<BonePenetration>(triangles);
    const LevelSetFigures& grid = bone->grid->figures();
    m_figures[name] = {{"cache", (cache_dir / (name + ".vdb")).string()},
                       {"reused", grid.reused},
                       {"build_s", grid.build_s},
                       {"active_voxels", grid.active_voxels},
                       {"memory_mib", grid.memory_bytes / 1048576.0},
                       {"triangles", triangles.F.rows()},
                       {"open_edges", open_edges(triangles)}};
    obstacles.push_back({name, bone->grid.get(), bone->motion, attached});
    m_bones.push_back(std::move(bone));
  }
  const ContactSurface surface = free_boundary_surface(model.mesh, conditions);
  m_potential =
      std::make_unique<ContactPotential>(node_count, surface, std::move(obstacles), config.barrier);
  m_figures["surface_nodes"] = surface.nodes.size();
  m_figures["voxel_mm"] = config.grid.voxel_mm;
  m_figures["band_mm"] = config.grid.band_mm;
}

KneeContact::~KneeContact() = default;

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
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Vector3d shift = Eigen::Vector3d::Zero();
    if (bone.motion) {
      rotation =
          Eigen::AngleAxisd(t * bone.motion->angle_rad, bone.motion->axis).toRotationMatrix();
      origin = bone.motion->point_mm;
      shift = t * bone.motion->translation_mm;
    }
    for (Eigen::Index n = 0; n < x.size() / 3; ++n) {
      if (bone.bound[static_cast<std::size_t>(n)])
        continue;
      const Eigen::Vector3d p =
          rotation.transpose() * (x.segment<3>(3 * n) - origin - shift) + origin;
      contact.penetration_mm = std::max(contact.penetration_mm, bone.penetration->depth_mm(p));
    }
    result.push_back(contact);
  }
  return result;
}

} // namespace ligsim::sim
