#pragma once
/// @brief A built knee model as `ligsim build` leaves it in its output folder: the ligament's
/// tets with per-tet fiber directions and attachment flags (model.vtu), the femur and tibia
/// surfaces (femur.vtp, tibia.vtp).

#include "common/knee_anatomy.hpp"
#include "common/mesh.hpp"

#include <Eigen/Core>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::sim {

struct KneeModel {
  TetMesh mesh;
  Eigen::MatrixX3d fiber_directions; ///< unit, one row per tet
  std::vector<int> femur_nodes;      ///< move rigidly with the femur
  std::vector<int> tibia_nodes;      ///< stay with the (fixed) tibia
  vtkSmartPointer<vtkPolyData> femur;
  vtkSmartPointer<vtkPolyData> tibia;
  KneeAnatomy anatomy; ///< anatomy.json of the folder (empty for models built without it)
  Points centerline;   ///< centerline.vtp of the folder, #P x 3 mm (0 rows without it)
};

/// Reads the model folder. Throws InputError naming the file and what is missing: the folder,
/// model.vtu, its "fiber" cell array or attachment flags, an empty or overlapping attachment
/// set, a bone surface, a fiber of zero length.
KneeModel load_knee_model(const std::filesystem::path& dir);

/// Up the leg: from the tibia's mean vertex to the femur's (a hint for the axis fit and the
/// pictures' up direction, not an anatomical axis).
Eigen::Vector3d proximal_direction(const KneeModel& model);

/// The triangles of a bone surface (polygons split into triangles' fans are not expected: the
/// pipeline writes triangles only). Throws InputError naming `what` for a non-triangle cell.
TriangleSurface triangle_surface(vtkPolyData* surface, const std::string& what);

} // namespace ligsim::sim
