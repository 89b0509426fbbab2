#include "stages/labelmap/label_surface.hpp"

#include "common/error.hpp"
#include "stages/geometry/surface_query.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/vtk_convert.hpp"

#include <vtkAlgorithmOutput.h>
#include <vtkCleanPolyData.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkImageGaussianSmooth.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <deque>

namespace ligsim::labelmap {

namespace {

/// Labels each voxel of `on` with its connected component (0: not on), through 26 or 6
/// neighbours; returns the component sizes (index 0 unused).
std::vector<long> components(const Eigen::Vector3i& dims, const std::vector<std::uint8_t>& on,
                             bool twenty_six, std::vector<int>& component)
{
  component.assign(on.size(), 0);
  std::vector<long> sizes{0};
  const auto index = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims.x()) * (j + static_cast<std::size_t>(dims.y()) * k);
  };
  std::deque<Eigen::Vector3i> queue;
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i) {
        if (!on[index(i, j, k)] || component[index(i, j, k)] != 0)
          continue;
        const int id = static_cast<int>(sizes.size());
        sizes.push_back(0);
        component[index(i, j, k)] = id;
        queue.emplace_back(i, j, k);
        while (!queue.empty()) {
          const Eigen::Vector3i v = queue.front();
          queue.pop_front();
          ++sizes.back();
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const int steps = std::abs(dx) + std::abs(dy) + std::abs(dz);
                if (steps == 0 || (!twenty_six && steps > 1))
                  continue;
                const Eigen::Vector3i w = v + Eigen::Vector3i(dx, dy, dz);
                if ((w.array() < 0).any() || (w.array() >= dims.array()).any())
                  continue;
                const std::size_t n = index(w.x(), w.y(), w.z());
                if (on[n] && component[n] == 0) {
                  component[n] = id;
                  queue.push_back(w);
                }
              }
        }
      }
  return sizes;
}

/// Moves every vertex of the closed, outward-facing `surface` along its (area-weighted) normal
/// by one distance, so that it encloses `target_mm3`: the smoothing rounds the voxels' edges and
/// corners and so loses volume (11 % on a 1.5 mm band in 1 mm slices, 3 % on the shipped MCL),
/// while the voxel count is the segmentation's volume. On the shipped MCL this also brings the
/// surface nearer the segmented one (rms 0.097 mm instead of 0.100, max 0.35 instead of 0.37).
void restore_volume(TriangleSurface& surface, double target_mm3)
{
  for (int round = 0; round < 2; ++round) { // the offset's own curvature term: a second round
    Points normals = Points::Zero(surface.V.rows(), 3);
    double area = 0.0;
    for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
      const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)), b = surface.V.row(surface.F(f, 1)),
                            c = surface.V.row(surface.F(f, 2));
      const Eigen::Vector3d twice_area_normal = (b - a).cross(c - a);
      area += 0.5 * twice_area_normal.norm();
      for (int corner = 0; corner < 3; ++corner)
        normals.row(surface.F(f, corner)) += twice_area_normal.transpose();
    }
    const double offset_mm = (target_mm3 - signed_volume(surface)) / area;
    for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
      surface.V.row(v) += offset_mm * normals.row(v).normalized();
  }
}

} // namespace

std::vector<std::uint8_t> select_label(const LabelImage& image, int label, Selection* selection)
{
  std::vector<std::uint8_t> mask(image.labels.size(), 0);
  for (std::size_t v = 0; v < mask.size(); ++v)
    mask[v] = image.labels[v] == label ? 1 : 0;
  std::vector<int> component;
  const std::vector<long> sizes = components(image.dims, mask, true, component);
  if (sizes.size() < 2)
    fail("label {} does not occur in the label map", label);
  const auto largest =
      static_cast<int>(std::max_element(sizes.begin() + 1, sizes.end()) - sizes.begin());
  Selection result;
  result.label = label;
  result.components = static_cast<int>(sizes.size()) - 1;
  for (std::size_t v = 0; v < mask.size(); ++v)
    if (mask[v] && component[v] != largest) {
      mask[v] = 0;
      ++result.dropped_voxels;
    }
  // Holes: background (6-connected) that does not reach the image border.
  std::vector<std::uint8_t> background(mask.size());
  for (std::size_t v = 0; v < mask.size(); ++v)
    background[v] = mask[v] ? 0 : 1;
  std::vector<int> pocket;
  const std::vector<long> pocket_sizes = components(image.dims, background, false, pocket);
  std::vector<bool> reaches_border(pocket_sizes.size(), false);
  const Eigen::Vector3i& d = image.dims;
  for (int k = 0; k < d.z(); ++k)
    for (int j = 0; j < d.y(); ++j)
      for (int i = 0; i < d.x(); ++i)
        if (i == 0 || j == 0 || k == 0 || i == d.x() - 1 || j == d.y() - 1 || k == d.z() - 1)
          reaches_border[static_cast<std::size_t>(pocket[image.index(i, j, k)])] = true;
  for (std::size_t v = 0; v < mask.size(); ++v)
    if (background[v] && !reaches_border[static_cast<std::size_t>(pocket[v])]) {
      mask[v] = 1;
      ++result.filled_hole_voxels;
    }
  for (std::uint8_t m : mask)
    result.voxels += m;
  if (selection != nullptr)
    *selection = result;
  return mask;
}

namespace {

/// The mask in index space with `pad` voxels of padding all round (so that the surface closes at
/// the image border), as VTK image data of `T` values 0 and 1.
template <class Array>
vtkSmartPointer<vtkImageData> padded_volume(const LabelImage& image,
                                            const std::vector<std::uint8_t>& mask, int pad)
{
  const Eigen::Vector3i dims = image.dims + Eigen::Vector3i::Constant(2 * pad);
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->SetDimensions(dims.x(), dims.y(), dims.z());
  volume->SetOrigin(-pad, -pad, -pad);
  volume->SetSpacing(1.0, 1.0, 1.0);
  auto values = vtkSmartPointer<Array>::New();
  values->SetName("label");
  values->SetNumberOfTuples(static_cast<vtkIdType>(dims.prod()));
  values->FillValue(0);
  for (int k = 0; k < image.dims.z(); ++k)
    for (int j = 0; j < image.dims.y(); ++j)
      for (int i = 0; i < image.dims.x(); ++i)
        if (mask[image.index(i, j, k)])
          values->SetValue((i + pad) +
                               static_cast<vtkIdType>(dims.x()) *
                                   ((j + pad) + static_cast<vtkIdType>(dims.y()) * (k + pad)),
                           1);
  volume->GetPointData()->SetScalars(values);
  return volume;
}

/// Triangles of `polydata` (index space) in physical coordinates, facing outward.
TriangleSurface physical_surface(vtkAlgorithmOutput* polydata, const LabelImage& image)
{
  auto triangles = vtkSmartPointer<vtkTriangleFilter>::New();
  triangles->SetInputConnection(polydata);
  auto clean = vtkSmartPointer<vtkCleanPolyData>::New();
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->Update();
  TriangleSurface surface = io::from_polydata(clean->GetOutput());
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    surface.V.row(v) = image.physical_point(surface.V.row(v).transpose()).transpose();
  if (signed_volume(surface) < 0.0)
    surface.F.col(1).swap(surface.F.col(2));
  return surface;
}

} // namespace

TriangleSurface blurred_mask_surface(const LabelImage& image, const std::vector<std::uint8_t>& mask)
{
  // Sigma: one in-plane voxel, half a slice (and one voxel of an isotropic map), in voxels.
  const double in_plane = image.spacing_mm.minCoeff(), slice = image.spacing_mm.maxCoeff();
  auto blur = vtkSmartPointer<vtkImageGaussianSmooth>::New();
  blur->SetInputData(padded_volume<vtkFloatArray>(image, mask, 3));
  blur->SetDimensionality(3);
  double sigma[3];
  for (int a = 0; a < 3; ++a)
    sigma[a] =
        (image.spacing_mm[a] < slice ? image.spacing_mm[a] : std::max(in_plane, 0.5 * slice)) /
        image.spacing_mm[a];
  blur->SetStandardDeviations(sigma);
  blur->SetRadiusFactors(3.0, 3.0, 3.0);
  auto contour = vtkSmartPointer<vtkFlyingEdges3D>::New();
  contour->SetInputConnection(blur->GetOutputPort());
  contour->SetValue(0, 0.5);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  return physical_surface(contour->GetOutputPort(), image);
}

namespace {

/// The part of `image` that holds `label`, with one voxel more all round where the image has it:
/// the selection and the contour see the same voxels and holes, at the cost of the label's size
/// rather than the map's (a whole-knee map is some 30 million voxels, a ligament's box 1 %).
LabelImage cropped_to(const LabelImage& image, int label)
{
  Eigen::Vector3i lo = image.dims, hi = Eigen::Vector3i::Constant(-1);
  for (int k = 0; k < image.dims.z(); ++k)
    for (int j = 0; j < image.dims.y(); ++j)
      for (int i = 0; i < image.dims.x(); ++i)
        if (image(i, j, k) == label) {
          lo = lo.cwiseMin(Eigen::Vector3i(i, j, k));
          hi = hi.cwiseMax(Eigen::Vector3i(i, j, k));
        }
  if ((hi.array() < 0).any())
    return image; // absent: select_label says so
  lo = (lo - Eigen::Vector3i::Ones()).cwiseMax(0);
  hi = (hi + Eigen::Vector3i::Ones()).cwiseMin(image.dims - Eigen::Vector3i::Ones());
  LabelImage crop;
  crop.dims = hi - lo + Eigen::Vector3i::Ones();
  crop.spacing_mm = image.spacing_mm;
  crop.direction = image.direction;
  crop.origin_mm = image.physical_point(lo.cast<double>());
  crop.labels.resize(static_cast<std::size_t>(crop.dims.prod()));
  for (int k = 0; k < crop.dims.z(); ++k)
    for (int j = 0; j < crop.dims.y(); ++j)
      for (int i = 0; i < crop.dims.x(); ++i)
        crop(i, j, k) = image(lo.x() + i, lo.y() + j, lo.z() + k);
  return crop;
}

} // namespace

Selection label_pieces(const LabelImage& image, int label)
{
  Selection selection;
  select_label(cropped_to(image, label), label, &selection);
  return selection;
}

TriangleSurface label_surface(const LabelImage& whole, int label, Selection* selection,
                              int smoothing_iterations, bool never_crossing)
{
  const LabelImage image = cropped_to(whole, label);
  Selection selected;
  const std::vector<std::uint8_t> mask = select_label(image, label, &selected);
  auto contour = vtkSmartPointer<vtkDiscreteFlyingEdges3D>::New();
  contour->SetInputData(padded_volume<vtkUnsignedCharArray>(image, mask, 1));
  contour->SetValue(0, 1.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  auto smooth = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
  smooth->SetInputConnection(contour->GetOutputPort());
  smooth->SetNumberOfIterations(std::max(smoothing_iterations, 0));
  smooth->SetPassBand(0.01); // removes the voxel staircase, keeps the shape
  smooth->NormalizeCoordinatesOn();
  smooth->BoundarySmoothingOff();
  smooth->FeatureEdgeSmoothingOff();
  smooth->NonManifoldSmoothingOn();
  TriangleSurface surface = physical_surface(
      smoothing_iterations > 0 ? smooth->GetOutputPort() : contour->GetOutputPort(), image);
  if (smoothing_iterations > 0) {
    const auto voxels = static_cast<double>(std::count(mask.begin(), mask.end(), 1));
    restore_volume(surface, voxels * image.spacing_mm.prod());
  }
  if (never_crossing) {
    const auto crossing = self_intersections(surface);
    if (!crossing.empty()) {
      selected.contour = "blurred";
      selected.crossing_pairs = static_cast<int>(crossing.size());
      surface = blurred_mask_surface(image, mask);
    }
  }
  if (selection != nullptr)
    *selection = selected;
  return surface;
}

} // namespace ligsim::labelmap
