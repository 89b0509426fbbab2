#include "stages/labelmap/label_image.hpp"

#include "stages/labelmap/itk_label_io.hpp"

namespace ligsim::labelmap {

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
  itk_io::write(raw, file);
}

} // namespace ligsim::labelmap
