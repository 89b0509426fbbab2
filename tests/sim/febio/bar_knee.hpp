#pragma once
/// A knee small enough for FEBio to solve in a second: a 4 x 4 x 20 mm bar of 160 tets, fibers
/// along it, the tibia (a sphere below) bound to its bottom face and the femur (a sphere above)
/// to its top face, flexed about the x axis through the middle of the top face.

#include "sim/contact/contact_surface.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/mesh/sphere_surface.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <memory>
#include <vector>

namespace ligsim::test {

/// A bone of the model: `surface`, shared.
inline sim::BoneSurface bone(const TriangleSurface& surface)
{
  return std::make_shared<const TriangleSurface>(surface);
}

constexpr double bar_length_mm = 20.0;

inline sim::KneeModel bar_knee()
{
  sim::KneeModel model;
  model.mesh = sim::structured_box_mesh({2, 2, 8}, {4.0, 4.0, bar_length_mm});
  model.fiber_directions = Eigen::MatrixX3d::Zero(model.mesh.T.rows(), 3);
  model.fiber_directions.col(2).setOnes();
  for (Eigen::Index n = 0; n < model.mesh.V.rows(); ++n) {
    if (model.mesh.V(n, 2) < 1e-9)
      model.tibia_nodes.push_back(static_cast<int>(n));
    if (model.mesh.V(n, 2) > bar_length_mm - 1e-9)
      model.femur_nodes.push_back(static_cast<int>(n));
  }
  model.femur = bone(sim::sphere_surface({2.0, 2.0, bar_length_mm + 6.0}, 3.0, 1));
  model.tibia = bone(sim::sphere_surface({2.0, 2.0, -6.0}, 3.0, 1));
  return model;
}

/// The bar knee with its tibia (still bound to the bar's bottom face) a 10 mm box beside the bar
/// that the bar's free side x = 0 overlaps by `overlap_mm` from z = 4 to 16 mm, as a segmented
/// ligament overlaps its bone: the side's nodes there lie that deep inside it.
inline sim::KneeModel overlapping_bar_knee(double overlap_mm)
{
  sim::KneeModel model = bar_knee();
  const TetMesh box = sim::structured_box_mesh({1, 1, 1}, {10.0, 10.0, 12.0});
  TriangleSurface surface;
  surface.V = box.V.rowwise() + Eigen::RowVector3d(overlap_mm - 10.0, -3.0, 4.0);
  surface.F = sim::boundary_surface(box).faces;
  model.tibia = bone(surface);
  return model;
}

inline sim::FlexionAxis bar_axis()
{
  return {Eigen::Vector3d(2.0, 2.0, bar_length_mm), Eigen::Vector3d::UnitX()};
}

/// Quasi-static sweep to 60 degrees about bar_axis(), contact off, Weiss' convention.
inline sim::FlexionSettings bar_settings(double in_situ_strain)
{
  sim::FlexionSettings settings;
  settings.angles_deg = {0.0, 30.0, 60.0};
  settings.in_situ_strain = in_situ_strain;
  settings.material.fiber->convention = sim::FiberConvention::weiss;
  settings.axis.source = sim::AxisSettings::Source::points;
  settings.axis.first_mm = bar_axis().point_mm;
  settings.axis.second_mm = bar_axis().point_mm + bar_axis().direction;
  settings.contact.enabled = false;
  settings.images = false;
  return settings;
}

} // namespace ligsim::test
