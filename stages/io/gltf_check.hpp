#pragma once
/// @brief Checks a glTF 2.0 file (.glb or .gltf) before VTK's reader sees it, and lists the
/// meshes its scene draws. VTK 9.1's vtkGLTFReader trusts the file: a node that is its own
/// descendant recurses until the stack overflows (SIGSEGV), and an accessor longer than its
/// buffer view, or a data: URI shorter than its buffer, is read past the end.

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::io {

/// A node of the scene that draws a mesh: what the `#name` of a surface path selects.
struct GltfMeshNode {
  int node = -1;         ///< index in the file's `nodes`
  int mesh = -1;         ///< index in the file's `meshes`
  std::string node_name; ///< may be empty
  std::string mesh_name; ///< may be empty
};

struct GltfContents {
  int scene = 0;                        ///< the scene to read: the file's `scene`, else 0
  std::vector<GltfMeshNode> mesh_nodes; ///< the scene's nodes that draw a mesh, depth first
};

/// Throws InputError naming the file, the element (`accessors[3].count`) and what is wrong
/// unless: a .glb has the binary container's header (magic `glTF`, version 2, the file's length)
/// and chunks that fit, the first JSON and the second (if any) BIN; the JSON parses (nested at
/// most 64 deep) and says glTF 2.x; it requires no extension and has no skins, animations, morph
/// targets or sparse accessors (ligsim reads static meshes); every index names an existing
/// element; the nodes form trees (one parent each, at most 1000 deep) whose roots the scenes
/// list; every buffer holds its byteLength (in the BIN chunk, a base64 data: URI or a file
/// beside this one), buffer views fit their buffer and accessors their buffer view; a
/// primitive's attributes have POSITION's count and the types the specification gives, and its
/// index count suits its mode. Index values are not read here: read_surface checks them.
GltfContents check_gltf(const std::filesystem::path& file);

} // namespace ligsim::io
