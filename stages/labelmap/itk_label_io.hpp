#pragma once
/// @brief The one translation unit that includes ITK: label maps read and written as plain
/// arrays. No Eigen here: ITK ships its own, older copy under the same include guards.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ligsim::labelmap::itk_io {

struct RawLabelImage {
  std::array<int, 3> dims{};
  std::array<double, 3> spacing_mm{};
  std::array<double, 3> origin_mm{};
  std::array<double, 9> direction{}; ///< row-major 3 x 3; columns are the index axes
  std::vector<std::int32_t> labels;  ///< x fastest
  /// The header's text key/value pairs (NRRD's `key:=value`: Slicer's segment names).
  std::vector<std::pair<std::string, std::string>> key_values;
};

/// See labelmap::read_label_image.
RawLabelImage read(const std::filesystem::path& file);

/// See labelmap::write_label_image.
void write(const RawLabelImage& image, const std::filesystem::path& file);

} // namespace ligsim::labelmap::itk_io
