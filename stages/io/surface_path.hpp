#pragma once
/// @brief Surface paths that name one mesh of a file holding several:
/// `data/hra-knee/VH_F_Ligaments_Knee_L.glb#VH_F_left_tibial_collateral_ligament`, or several
/// meshes joined into one surface: `knee.glb#VH_F_femur_L+VH_F_articular_cartilage_of_knee_L`.

#include <filesystem>
#include <string>

namespace ligsim::io {

/// A surface file and, for a glTF file, the mesh chosen in it.
struct SurfacePath {
  std::filesystem::path file;
  std::string mesh; ///< empty: the file's only mesh; "A+B": meshes A and B as one surface
};

/// Splits `path` at the first `#` that follows a `.glb` or `.gltf` extension (any case): the part
/// before is the file, the rest the mesh name, kept as it is. A path naming an existing file as
/// a whole, or one without such a `#`, is the file alone.
SurfacePath split_surface_path(const std::filesystem::path& path);

} // namespace ligsim::io
