#include "stages/io/surface_path.hpp"

#include <algorithm>
#include <cctype>

namespace ligsim::io {

namespace fs = std::filesystem;

SurfacePath split_surface_path(const fs::path& path)
{
  const std::string text = path.string();
  std::error_code ignored;
  if (fs::is_regular_file(path, ignored))
    return {path, ""};
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::size_t split = std::string::npos;
  for (const char* marker : {".glb#", ".gltf#"}) {
    const std::size_t at = lower.find(marker);
    if (at != std::string::npos)
      split = std::min(split, at + std::char_traits<char>::length(marker) - 1);
  }
  if (split == std::string::npos)
    return {path, ""};
  return {fs::path(text.substr(0, split)), text.substr(split + 1)};
}

} // namespace ligsim::io
