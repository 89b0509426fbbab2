#include "common/tet_faces.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace ligsim {

std::vector<std::array<int, 3>> tet_boundary_faces(const Tetrahedra& T)
{
  // Faces opposite each corner, ordered so that the normal points out of a positive tet.
  static constexpr int face_corners[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces; // by sorted corners
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (const auto& corners : face_corners) {
      const std::array<int, 3> face = {T(t, corners[0]), T(t, corners[1]), T(t, corners[2])};
      std::array<int, 3> key = face;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.try_emplace(key, 1, face);
      if (!inserted)
        ++it->second.first;
    }
  std::vector<std::array<int, 3>> boundary;
  for (const auto& [key, entry] : faces)
    if (entry.first == 1)
      boundary.push_back(entry.second);
  return boundary;
}

} // namespace ligsim
