#include "pipeline/commands/anatomy_outputs.hpp"

#include "common/error.hpp"
#include "common/knee_anatomy.hpp"
#include "common/knee_manifest.hpp"
#include "common/progress.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/render/anatomy_picture.hpp"
#include "pipeline/render/offscreen_display.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <vector>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

void write_landmarks_vtp(const KneeAnatomy& anatomy, const fs::path& file)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> vertices;
  vtkNew<vtkStringArray> names;
  names->SetName("name");
  for (const auto& [name, landmark] : anatomy.landmarks) {
    const vtkIdType id = points->InsertNextPoint(landmark.point_mm.data());
    vertices->InsertNextCell(1, &id);
    names->InsertNextValue(name);
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetVerts(vertices);
  data->GetPointData()->AddArray(names);
  write_vtk(data, file);
}

/// The surfaces of the folder worth drawing: its bones, and its ligaments (a knee's folders'
/// attachments.vtp, or its own).
void read_surfaces(const fs::path& dir, std::vector<vtkSmartPointer<vtkPolyData>>& bones,
                   std::vector<vtkSmartPointer<vtkPolyData>>& ligaments)
{
  for (const char* bone : {"femur.vtp", "tibia.vtp", "fibula.vtp"})
    if (fs::exists(dir / bone))
      bones.push_back(read_vtp(dir / bone));
  if (const auto manifest = read_knee_manifest(dir)) {
    for (const KneeLigament& ligament : manifest->ligaments)
      if (fs::exists(dir / ligament.folder / "attachments.vtp"))
        ligaments.push_back(read_vtp(dir / ligament.folder / "attachments.vtp"));
  } else if (fs::exists(dir / "attachments.vtp")) {
    ligaments.push_back(read_vtp(dir / "attachments.vtp"));
  }
}

} // namespace

void write_anatomy_outputs(const fs::path& dir, bool picture)
{
  const KneeAnatomy anatomy = read_knee_anatomy(dir);
  write_landmarks_vtp(anatomy, dir / "landmarks.vtp");
  if (!picture || anatomy.landmarks.empty() || !anatomy.proximal || !anatomy.posterior)
    return;
  std::vector<vtkSmartPointer<vtkPolyData>> bones, ligaments;
  read_surfaces(dir, bones, ligaments);
  render::AnatomyPicture scene;
  for (const auto& bone : bones)
    scene.bones.push_back(bone);
  for (const auto& ligament : ligaments)
    scene.ligaments.push_back(ligament);
  for (const auto& [name, landmark] : anatomy.landmarks) {
    scene.landmark_names.push_back(name);
    scene.landmarks_mm.push_back(landmark.point_mm);
  }
  scene.proximal = anatomy.proximal->normalized();
  scene.posterior =
      (*anatomy.posterior - anatomy.posterior->dot(scene.proximal) * scene.proximal).normalized();
  const Eigen::Vector3d right = (-scene.posterior).cross(scene.proximal).normalized();
  scene.medial = anatomy.side == "right" ? Eigen::Vector3d(-right) : right;
  scene.caption = anatomy.side.empty() ? "side not known" : "a " + anatomy.side + " knee";
  try {
    const render::OffscreenDisplay display;
    render::render_anatomy_png(scene, dir / "anatomy.png");
    log_info(fmt::format("anatomy: the landmarks drawn on the bones in {}",
                         (dir / "anatomy.png").string()));
  } catch (const Error& e) {
    log_info(fmt::format("anatomy: no picture ({})", e.what()));
  }
}

} // namespace ligsim::cli
