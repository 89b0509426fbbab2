#include "common/error.hpp"
#include "common/vtk_files.hpp"

#include <gtest/gtest.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>

namespace fs = std::filesystem;

TEST(VtkFiles, ImageRoundTrip)
{
  const fs::path file = fs::temp_directory_path() / "ligsim_vtk_roundtrip.vti";
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(3, 4, 5);
  image->SetSpacing(0.5, 0.5, 0.5);
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetName("d");
  values->SetNumberOfValues(60);
  for (int i = 0; i < 60; ++i)
    values->SetValue(i, 0.25f * i);
  image->GetPointData()->SetScalars(values);
  ligsim::write_vtk(image, file);

  auto back = ligsim::read_vti(file);
  ASSERT_EQ(back->GetNumberOfPoints(), 60);
  auto* array = back->GetPointData()->GetArray("d");
  ASSERT_NE(array, nullptr);
  EXPECT_FLOAT_EQ(static_cast<float>(array->GetTuple1(7)), 1.75f);
  EXPECT_DOUBLE_EQ(back->GetSpacing()[2], 0.5);
}

TEST(VtkFiles, UnknownExtensionAndMissingFileAreClearErrors)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  EXPECT_THROW(ligsim::write_vtk(image, fs::temp_directory_path() / "x.png"), ligsim::InputError);
  EXPECT_THROW(ligsim::read_vtu("/nonexistent/ligsim.vtu"), ligsim::InputError);
}
