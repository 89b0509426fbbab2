#include "stages/labelmap/label_image.hpp"

#include "stages/labelmap/itk_label_io.hpp"

#include <algorithm>
#include <cctype>

namespace ligsim::labelmap {

namespace {
constexpr const char* kFrameKey = "ligsim_frame";
constexpr const char* kFromSurfaces = "surfaces";
} // namespace

LabelImage read_label_image(const std::filesystem::path& file)
{
  itk_io::RawLabelImage raw = itk_io::read(file);
  LabelImage image;
  for (int a = 0; a < 3; ++a) {
    image.dims[a] = raw.dims[a];
    image.spacing_mm[a] = raw.spacing_mm[a];
    image.origin_mm[a] = raw.origin_mm[a];
    for (int b = 0; b < 3; ++b)
      image.direction(a, b) = raw.direction[3 * a + b];
  }
  image.labels = std::move(raw.labels);
  image.segment_names = segment_names(raw.key_values, file);
  image.frame_from_surfaces =
      std::find(raw.key_values.begin(), raw.key_values.end(),
                std::pair<std::string, std::string>{kFrameKey, kFromSurfaces}) !=
      raw.key_values.end();
  return image;
}

void write_label_image(const LabelImage& image, const std::filesystem::path& file)
{
  itk_io::RawLabelImage raw;
  for (int a = 0; a < 3; ++a) {
    raw.dims[a] = image.dims[a];
    raw.spacing_mm[a] = image.spacing_mm[a];
    raw.origin_mm[a] = image.origin_mm[a];
    for (int b = 0; b < 3; ++b)
      raw.direction[3 * a + b] = image.direction(a, b);
  }
  raw.labels = image.labels;
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!image.segment_names.empty() && extension == ".nrrd")
    raw.key_values = segment_keys(image.segment_names);
  if (image.frame_from_surfaces && extension == ".nrrd")
    raw.key_values.emplace_back(kFrameKey, kFromSurfaces);
  itk_io::write(raw, file);
}

} // namespace ligsim::labelmap
