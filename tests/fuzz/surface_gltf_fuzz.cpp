// libFuzzer target: glTF through read_surface. The bytes go to a .glb file if they start with
// the binary container's magic, else to a .gltf file; then every named mesh of the scene (the
// first four) is read, and a file of one mesh without a name. Any input must end in surfaces
// or an InputError, never a crash, a hang or a sanitizer report.

#include "common/error.hpp"
#include "stages/io/gltf_check.hpp"
#include "stages/io/surface_reader.hpp"
#include "tests/fuzz/fuzz_support.hpp"

#include <cstring>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::filesystem::path file =
      ligsim::fuzz::write_input_file(data, size, binary ? ".glb" : ".gltf");
  try {
    const ligsim::io::GltfContents contents = ligsim::io::check_gltf(file);
    if (contents.mesh_nodes.size() == 1)
      ligsim::io::read_surface(file);
    int read = 0;
    for (const ligsim::io::GltfMeshNode& node : contents.mesh_nodes)
      if (!node.node_name.empty() && read++ < 4) {
        try {
          ligsim::io::read_surface(file.string() + "#" + node.node_name);
        } catch (const ligsim::Error& error) {
          ligsim::fuzz::rejected(error);
        }
      }
  } catch (const ligsim::Error& error) {
    ligsim::fuzz::rejected(error);
  }
  return 0;
}
