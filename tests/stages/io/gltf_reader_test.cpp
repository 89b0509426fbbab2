#include "common/error.hpp"
#include "stages/geometry/surface_topology.hpp"
#include "stages/io/surface_path.hpp"
#include "stages/io/surface_reader.hpp"
#include "tests/stages/io/gltf_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace ligsim;
namespace fs = std::filesystem;

namespace {

const fs::path hra = fs::path(LIGSIM_SOURCE_DIR) / "data/hra-knee";

fs::path scratch(const std::string& name)
{
  const fs::path dir = fs::temp_directory_path() / "ligsim_gltf_test";
  fs::create_directories(dir);
  return dir / name;
}

std::string read_bytes(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The message of the InputError reading `path` throws ("" and a failure if none).
std::string error_of(const fs::path& path)
{
  try {
    io::read_surface(path);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "read " << path << " without an error";
  return "";
}

void expect_contains(const std::string& text, const std::string& part)
{
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

} // namespace

TEST(SurfacePath, SplitsAtTheHashAfterAGltfExtension)
{
  const auto mcl = io::split_surface_path("data/knee.glb#VH_F_left_tibial_collateral_ligament");
  EXPECT_EQ(mcl.file, fs::path("data/knee.glb"));
  EXPECT_EQ(mcl.mesh, "VH_F_left_tibial_collateral_ligament");
  const auto odd = io::split_surface_path("dir/Knee.GLTF#name#with:odd/chars");
  EXPECT_EQ(odd.file, fs::path("dir/Knee.GLTF"));
  EXPECT_EQ(odd.mesh, "name#with:odd/chars");
  EXPECT_EQ(io::split_surface_path("scan#2.stl").file, fs::path("scan#2.stl"));
  EXPECT_EQ(io::split_surface_path("knee.glb").mesh, "");
  // A file whose name holds '.glb#' is the file.
  const fs::path whole = test::write_glb(scratch("odd.glb#name.glb"), test::tetrahedron());
  EXPECT_EQ(io::split_surface_path(whole).file, whole);
  EXPECT_EQ(io::split_surface_path(whole).mesh, "");
}

TEST(GltfReader, ReadsTheFemaleMclInMillimetres)
{
  const TriangleSurface mcl =
      io::read_surface(hra / "VH_F_Ligaments_Knee_L.glb#VH_F_left_tibial_collateral_ligament");
  EXPECT_EQ(mcl.V.rows(), 842);
  EXPECT_EQ(mcl.F.rows(), 1680);
  EXPECT_TRUE(check_topology(mcl).closed_manifold());
  EXPECT_GT(signed_volume(mcl), 0.0);
  // The accessor's min and max, in metres: x 0.0687021..0.113756, y -0.457249..-0.349133,
  // z -0.0829495..-0.0647914.
  const Eigen::Vector3d lo = mcl.V.colwise().minCoeff(), hi = mcl.V.colwise().maxCoeff();
  EXPECT_NEAR(lo.x(), 68.7021, 1e-3);
  EXPECT_NEAR(hi.x(), 113.756, 1e-3);
  EXPECT_NEAR(lo.y(), -457.249, 1e-3);
  EXPECT_NEAR(hi.y(), -349.133, 1e-3);
  EXPECT_NEAR(lo.z(), -82.9495, 1e-3);
  EXPECT_NEAR(hi.z(), -64.7914, 1e-3);
}

TEST(GltfReader, ReadsTheFemaleTibiaByNodeName)
{
  const TriangleSurface tibia = io::read_surface(hra / "VH_F_Knee_L.glb#VH_F_tibia_L");
  EXPECT_EQ(tibia.V.rows(), 1747);
  EXPECT_EQ(tibia.F.rows(), 3490);
  EXPECT_TRUE(check_topology(tibia).closed_manifold());
  const Eigen::Vector3d lo = tibia.V.colwise().minCoeff(), hi = tibia.V.colwise().maxCoeff();
  EXPECT_NEAR(lo.y(), -720.632, 1e-2); // about 343 mm long, below the joint line
  EXPECT_NEAR(hi.y(), -377.160, 1e-2);
}

TEST(GltfReader, UnknownOrMissingNameListsTheMeshes)
{
  const std::string unknown = error_of(hra / "VH_F_Ligaments_Knee_L.glb#VH_F_MCL");
  expect_contains(unknown, "no mesh named 'VH_F_MCL'");
  for (const char* name :
       {"VH_F_left_tibial_collateral_ligament", "VH_F_fibular_collateral_ligament_L",
        "VH_F_anterior_cruciate_ligament_of_knee_L", "VH_F_posterior_cruciate_ligament_of_knee_L",
        "VH_F_patellar_ligament_L", "VH_F_anterolateral_ligament_of_knee_L"})
    expect_contains(unknown, name);
  const std::string missing = error_of(hra / "VH_F_Ligaments_Knee_L.glb");
  expect_contains(missing, "holds 6 meshes; name one as");
  expect_contains(missing, "VH_F_left_tibial_collateral_ligament");
}

TEST(GltfReader, OneMeshNeedsNoNameAndMeshNamesAlsoSelect)
{
  const fs::path file = test::write_glb(scratch("tet.glb"), test::tetrahedron("node"));
  const TriangleSurface tet = io::read_surface(file);
  EXPECT_EQ(tet.V.rows(), 4);
  EXPECT_EQ(tet.F.rows(), 4);
  EXPECT_NEAR(signed_volume(tet), 1e9 / 6.0, 1.0); // a 1 m tetrahedron, in mm^3
  EXPECT_EQ(io::read_surface(fs::path(file.string() + "#node")).F.rows(), 4);
  EXPECT_EQ(io::read_surface(fs::path(file.string() + "#tet")).F.rows(), 4); // the mesh's name
}

TEST(GltfReader, NodeTransformsAreApplied)
{
  // A parent moved 100 m along x holds the tetrahedron's node, scaled 2x and moved 1 m along y.
  test::GltfAsset asset = test::tetrahedron("child");
  asset.document["nodes"] = {{{"name", "parent"}, {"translation", {100, 0, 0}}, {"children", {1}}},
                             {{"name", "child"},
                              {"mesh", 0},
                              {"matrix", {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 1, 0, 1}}}};
  const TriangleSurface tet =
      io::read_surface(fs::path(test::write_glb(scratch("moved.glb"), asset).string() + "#child"));
  const Eigen::Vector3d lo = tet.V.colwise().minCoeff(), hi = tet.V.colwise().maxCoeff();
  EXPECT_NEAR((lo - Eigen::Vector3d(100e3, 1e3, 0)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((hi - Eigen::Vector3d(102e3, 3e3, 2e3)).norm(), 0.0, 1e-6);
}

TEST(GltfReader, PrimitivesAreMergedIntoOneSurface)
{
  // The tetrahedron's four triangles as two primitives, each with its own copy of the points.
  test::GltfAsset asset = test::tetrahedron();
  asset.document["accessors"].push_back(
      {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
  asset.document["accessors"].push_back({{"bufferView", 1},
                                         {"byteOffset", 12},
                                         {"componentType", 5123},
                                         {"count", 6},
                                         {"type", "SCALAR"}});
  asset.document["meshes"][0]["primitives"] = {{{"attributes", {{"POSITION", 0}}}, {"indices", 2}},
                                               {{"attributes", {{"POSITION", 0}}}, {"indices", 3}}};
  const TriangleSurface tet = io::read_surface(test::write_glb(scratch("split.glb"), asset));
  EXPECT_EQ(tet.V.rows(), 4);
  EXPECT_EQ(tet.F.rows(), 4);
  EXPECT_TRUE(check_topology(tet).closed_manifold());
}

TEST(GltfReader, ReadsGltfTextWithDataUriOrBinFile)
{
  EXPECT_EQ(io::read_surface(test::write_gltf_data_uri(scratch("tet.gltf"), test::tetrahedron()))
                .F.rows(),
            4);
  EXPECT_EQ(io::read_surface(
                test::write_gltf_bin(scratch("tet_bin.gltf"), test::tetrahedron(), "tet_bin.bin"))
                .F.rows(),
            4);
  // A buffer file shorter than the buffer is named.
  test::GltfAsset asset = test::tetrahedron();
  const fs::path file = test::write_gltf_bin(scratch("short.gltf"), asset, "short.bin");
  fs::resize_file(scratch("short.bin"), asset.buffer.size() - 4);
  expect_contains(error_of(file), "holds 68 bytes, byteLength says 72");
}

TEST(GltfReader, TruncatedOrCorruptedFilesAreInputErrors)
{
  const std::string bytes = read_bytes(hra / "VH_F_Ligaments_Knee_L.glb");
  const std::string mcl = "#VH_F_left_tibial_collateral_ligament";
  for (std::size_t size : {std::size_t(0), std::size_t(11), std::size_t(19), std::size_t(3000),
                           std::size_t(6096), bytes.size() / 2, bytes.size() - 1}) {
    const fs::path cut = test::write_bytes(scratch("cut.glb"), bytes.substr(0, size));
    const std::string message = error_of(fs::path(cut.string() + mcl));
    if (size >= 20)
      expect_contains(message, "the file has " + std::to_string(size));
  }
  // The same file with its header's length fixed up, so only the chunks are short.
  std::string cut = bytes.substr(0, bytes.size() / 2);
  cut[8] = static_cast<char>(cut.size() & 0xff), cut[9] = static_cast<char>(cut.size() >> 8 & 0xff);
  cut[10] = static_cast<char>(cut.size() >> 16 & 0xff), cut[11] = 0;
  expect_contains(error_of(fs::path(test::write_bytes(scratch("chunk.glb"), cut).string() + mcl)),
                  "bytes announced");

  std::string magic = bytes;
  magic[0] = 'X';
  expect_contains(error_of(fs::path(test::write_bytes(scratch("magic.glb"), magic).string() + mcl)),
                  "not a glTF binary file");
  std::string json = bytes;
  json[40] = '}';
  expect_contains(error_of(fs::path(test::write_bytes(scratch("json.glb"), json).string() + mcl)),
                  "not valid JSON");
}

TEST(GltfReader, InconsistentDocumentsAreInputErrors)
{
  const auto message = [](const std::string& name, const auto& change) {
    test::GltfAsset asset = test::tetrahedron();
    change(asset.document);
    return error_of(test::write_glb(scratch(name), asset));
  };
  // VTK 9.1 recursed for ever on a node that is its own descendant (SIGSEGV); two parents.
  expect_contains(message("cycle.glb",
                          [](auto& d) {
                            d["nodes"] = {{{"mesh", 0}}, {{"children", {2}}}, {{"children", {1}}}};
                          }),
                  "node 1 lies on a cycle");
  expect_contains(message("parents.glb",
                          [](auto& d) {
                            d["nodes"] = {{{"mesh", 0}, {"children", {1}}},
                                          {{"children", {2}}},
                                          {{"children", {1}}}};
                          }),
                  "node 1 is a child of nodes 0 and 2");
  // VTK 9.1 read 400 points from a 48-byte buffer view.
  expect_contains(message("overrun.glb", [](auto& d) { d["accessors"][0]["count"] = 400; }),
                  "accessors[0]: 400 elements of 12 bytes from byte 0 need 4800 bytes, "
                  "bufferView 0 has 48");
  // Found by fuzz_surface_gltf: VTK 9.1 threw std::length_error through its pipeline.
  expect_contains(message("viewbuffer.glb", [](auto& d) { d["bufferViews"][0].erase("buffer"); }),
                  "bufferViews[0].buffer is missing");
  expect_contains(message("view.glb", [](auto& d) { d["bufferViews"][1]["byteLength"] = 400; }),
                  "bufferViews[1] (bytes 48..448) runs past the end of buffer 0 (72 bytes)");
  expect_contains(
      message("index.glb", [](auto& d) { d["meshes"][0]["primitives"][0]["indices"] = 7; }),
      "primitives[0].indices = 7 is not within 0..1");
  expect_contains(message("count.glb", [](auto& d) { d["accessors"][1]["count"] = 10; }),
                  "10 corners do not make whole triangles");
  expect_contains(
      message("normal.glb",
              [](auto& d) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 1; }),
      "attribute NORMAL is SCALAR");
  expect_contains(message("skin.glb",
                          [](auto& d) {
                            d["skins"] = {{{"joints", {0}}}};
                          }),
                  "has skins: ligsim reads static meshes only");
  expect_contains(message("noscene.glb", [](auto& d) { d.erase("scenes"); }), "has no scene");
  expect_contains(message("version.glb", [](auto& d) { d["asset"]["version"] = "1.0"; }),
                  "glTF version '1.0'");
  // An index beyond the points is found once VTK has read the file.
  test::GltfAsset asset = test::tetrahedron();
  asset.buffer[48] = 9;
  expect_contains(error_of(test::write_glb(scratch("vertex.glb"), asset)),
                  "refers to vertex 9, but the file has 4 vertices");
}
