#include "stages/labelmap/itk_label_io.hpp"

#include "common/error.hpp"
#include "stages/io/metaimage_check.hpp"

#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageIOBase.h>
#include <itkMetaDataObject.h>
#include <itkMetaImageIOFactory.h>
#include <itkNiftiImageIOFactory.h>
#include <itkNrrdImageIOFactory.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <string>

#include <unistd.h>

namespace ligsim::labelmap::itk_io {

namespace fs = std::filesystem;

namespace {

using Image = itk::Image<std::int32_t, 3>;

/// The formats we support, registered once (we do not use ITK_USE_FILE's global registration).
void register_formats()
{
  static std::once_flag flag;
  std::call_once(flag, [] {
    itk::NrrdImageIOFactory::RegisterOneFactory();
    itk::NiftiImageIOFactory::RegisterOneFactory();
    itk::MetaImageIOFactory::RegisterOneFactory();
  });
}

/// Whether the file name ends with `ending` (lower case), in any case.
bool name_ends_with(const fs::path& file, const std::string& ending)
{
  std::string name = file.filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name.size() > ending.size() &&
         name.compare(name.size() - ending.size(), std::string::npos, ending) == 0;
}

bool supported_name(const fs::path& file)
{
  for (const char* ending : {".nrrd", ".nii", ".nii.gz", ".mha", ".mhd"})
    if (name_ends_with(file, ending))
      return true;
  return false;
}

void require_supported(const fs::path& file)
{
  if (!supported_name(file))
    fail("'{}': unknown label-map format (use .nrrd, .seg.nrrd, .nii, .nii.gz, .mha or .mhd)",
         file.string());
}

} // namespace

RawLabelImage read(const fs::path& file)
{
  if (!fs::is_regular_file(file))
    fail("missing label map '{}'", file.string());
  require_supported(file);
  if (name_ends_with(file, ".mha") || name_ends_with(file, ".mhd"))
    io::check_metaimage_header(file); // ITK's MetaIO loops for ever on NDims = -3
  register_formats();
  // Ask the file first: a 4-D layered segmentation or a float image is a clear error.
  itk::ImageIOBase::Pointer io = itk::ImageIOFactory::CreateImageIO(
      file.c_str(), itk::ImageIOFactory::IOFileModeEnum::ReadMode);
  if (!io)
    fail("cannot read label map '{}': no reader recognises it", file.string());
  try {
    io->SetFileName(file.string());
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject& e) {
    fail("cannot read label map '{}': {}", file.string(), e.GetDescription());
  }
  // ITK reads the layers of a layered .seg.nrrd (NRRD kind "list") as components per voxel.
  if (io->GetNumberOfDimensions() == 3 && io->GetNumberOfComponents() > 1)
    fail("label map '{}' holds {} layers (a segmentation whose segments overlap): one 3-D layer "
         "of labels is needed (export a single-layer segmentation, its segments not overlapping)",
         file.string(), io->GetNumberOfComponents());
  if (io->GetNumberOfDimensions() != 3 || io->GetNumberOfComponents() != 1)
    fail("label map '{}' has {} dimensions and {} components per voxel: one 3-D layer of labels "
         "is needed (export a single-layer segmentation)",
         file.string(), io->GetNumberOfDimensions(), io->GetNumberOfComponents());
  // ITK allocates what the header says before it reads a byte (a fuzzed DimSize asked for
  // 206 GB); 2^28 voxels (1 GiB of labels) is more than a 0.3 mm knee MRI needs.
  constexpr double max_voxels = 268435456.0;
  const double voxels = static_cast<double>(io->GetDimensions(0)) *
                        static_cast<double>(io->GetDimensions(1)) *
                        static_cast<double>(io->GetDimensions(2));
  if (voxels > max_voxels)
    fail("label map '{}' is {} x {} x {} voxels, more than the 2^28 = 268435456 we read",
         file.string(), io->GetDimensions(0), io->GetDimensions(1), io->GetDimensions(2));
  const auto type = io->GetComponentType();
  if (type == itk::IOComponentEnum::FLOAT || type == itk::IOComponentEnum::DOUBLE)
    fail("label map '{}' holds floating-point values, not integer labels", file.string());

  auto reader = itk::ImageFileReader<Image>::New();
  reader->SetFileName(file.string());
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& e) {
    fail("cannot read label map '{}': {}", file.string(), e.GetDescription());
  }
  const Image* image = reader->GetOutput();
  const auto region = image->GetLargestPossibleRegion();
  RawLabelImage result;
  for (int a = 0; a < 3; ++a) {
    result.dims[a] = static_cast<int>(region.GetSize()[a]);
    result.spacing_mm[a] = image->GetSpacing()[a];
    result.origin_mm[a] = image->GetOrigin()[a];
    for (int b = 0; b < 3; ++b)
      result.direction[3 * a + b] = image->GetDirection()(a, b);
  }
  const std::int32_t* data = image->GetBufferPointer();
  result.labels.assign(data, data + region.GetNumberOfPixels());
  const itk::MetaDataDictionary& dictionary = image->GetMetaDataDictionary();
  for (const std::string& key : dictionary.GetKeys()) {
    std::string value;
    if (itk::ExposeMetaData<std::string>(dictionary, key, value))
      result.key_values.emplace_back(key, value);
  }
  return result;
}

void write(const RawLabelImage& label_image, const fs::path& file)
{
  require_supported(file);
  if (file.extension() == ".mhd")
    fail("'{}': write .mha (one file) rather than .mhd (two files)", file.string());
  register_formats();
  auto image = Image::New();
  Image::RegionType region;
  Image::SpacingType spacing;
  Image::PointType origin;
  Image::DirectionType direction;
  for (int a = 0; a < 3; ++a) {
    region.SetSize(a, static_cast<itk::SizeValueType>(label_image.dims[a]));
    spacing[a] = label_image.spacing_mm[a];
    origin[a] = label_image.origin_mm[a];
    for (int b = 0; b < 3; ++b)
      direction(a, b) = label_image.direction[3 * a + b];
  }
  image->SetRegions(region);
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  image->Allocate();
  std::copy(label_image.labels.begin(), label_image.labels.end(), image->GetBufferPointer());
  for (const auto& [key, value] : label_image.key_values)
    itk::EncapsulateMetaData<std::string>(image->GetMetaDataDictionary(), key, value);

  // A temporary beside the target that keeps the whole name's ending (.nii.gz picks ITK's
  // writer), renamed over it once complete.
  const fs::path temp =
      file.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + file.filename().string());
  auto writer = itk::ImageFileWriter<Image>::New();
  writer->SetFileName(temp.string());
  writer->SetInput(image);
  writer->UseCompressionOn();
  try {
    writer->Update();
  } catch (const itk::ExceptionObject& e) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    fail("cannot write label map '{}': {}", file.string(), e.GetDescription());
  }
  fs::rename(temp, file);
}

} // namespace ligsim::labelmap::itk_io
