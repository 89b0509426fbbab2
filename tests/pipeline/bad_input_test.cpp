/// Bad inputs to `ligsim build`: each gives a non-zero exit, one clear line on stderr, and no
/// output file.

#include "tests/pipeline/cli_runner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

const std::string kMcl =
    source_path("data/vhf-right-knee/VHF_Right_Ligament_MCL_smooth.stl").string();
const std::string kTibia =
    source_path("data/vhf-right-knee/VHF_Right_Bone_Tibia_smooth.stl").string();

/// Runs a build expected to fail; checks the exit code, the one line and that `out` holds no file
/// (or only the outputs of stages before the failing one, listed in `allowed`).
void expect_clean_failure(const std::string& arguments, const fs::path& out,
                          const std::string& words, const std::vector<std::string>& allowed = {})
{
  const CliResult result = run_ligsim(arguments + " --out " + out.string());
  EXPECT_NE(result.exit_code, 0) << arguments;
  ASSERT_FALSE(result.stderr_text.empty());
  // Progress lines start with "ligsim: <stage>:" or two spaces; the error is the one last line.
  const auto last_start = result.stderr_text.rfind('\n', result.stderr_text.size() - 2);
  const std::string last =
      result.stderr_text.substr(last_start == std::string::npos ? 0 : last_start + 1);
  EXPECT_EQ(last.rfind("ligsim: error: ", 0), 0u) << result.stderr_text;
  EXPECT_EQ(std::count(last.begin(), last.end(), '\n'), 1) << last;
  EXPECT_NE(last.find(words), std::string::npos) << "expected '" << words << "' in: " << last;
  if (fs::exists(out))
    for (const auto& entry : fs::recursive_directory_iterator(out)) {
      if (!entry.is_regular_file())
        continue;
      const std::string name = entry.path().filename().string();
      const bool ok = std::find(allowed.begin(), allowed.end(), name) != allowed.end() ||
                      entry.path().parent_path().filename() == ".ligsim-cache";
      EXPECT_TRUE(ok) << "left behind: " << entry.path();
    }
}

/// `text` in a file of this process's scratch root (removed when the tests end).
fs::path write_text(const std::string& name, const std::string& text)
{
  fs::create_directories(scratch_root());
  const fs::path file = scratch_root() / name;
  std::ofstream(file) << text;
  return file;
}

} // namespace

TEST(BuildBadInput, MissingFile)
{
  expect_clean_failure("build --surface /nonexistent/mcl.stl", fresh_folder("missing"),
                       "missing surface file");
}

TEST(BuildBadInput, UnknownFormat)
{
  const fs::path file = write_text("ligsim_surface.xyz", "0 0 0\n");
  expect_clean_failure("build --surface " + file.string(), fresh_folder("format"),
                       "unknown surface format");
}

TEST(BuildBadInput, OpenSurface)
{
  // A tetrahedron missing one face.
  const fs::path file = write_text(
      "ligsim_open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n");
  expect_clean_failure("build --surface " + file.string(), fresh_folder("open"),
                       "3 boundary edges");
}

TEST(BuildBadInput, NanCoordinate)
{
  // A binary STL tetrahedron, one corner NaN, as a broken export writes it.
  const fs::path file = write_text("ligsim_nan.stl", "");
  {
    const float nan = std::nanf("");
    const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, nan}};
    const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    std::ofstream stl(file, std::ios::binary);
    const std::string header(80, ' ');
    stl.write(header.data(), 80);
    const std::uint32_t count = 4;
    stl.write(reinterpret_cast<const char*>(&count), 4);
    for (const auto& f : faces) {
      const float normal[3] = {0, 0, 0};
      stl.write(reinterpret_cast<const char*>(normal), 12);
      for (int k : f)
        stl.write(reinterpret_cast<const char*>(corners[k]), 12);
      const std::uint16_t attribute = 0;
      stl.write(reinterpret_cast<const char*>(&attribute), 2);
    }
  }
  expect_clean_failure("build --surface " + file.string(), fresh_folder("nan"), "non-finite");
}

TEST(BuildBadInput, EmptyAttachmentArea)
{
  expect_clean_failure("build --surface " + kMcl + " --tibia " + kTibia +
                           " --attach-distance 0.0001",
                       fresh_folder("empty"), "attachment area is empty", {"anatomy.json"});
}

TEST(BuildBadInput, OverlappingAttachmentAreas)
{
  expect_clean_failure("build --surface " + kMcl + " --femur-indices 1,2,3 --tibia-indices 3,4",
                       fresh_folder("overlap"), "overlap", {"anatomy.json"});
}

TEST(BuildBadInput, AttachmentsTheCenterlineCannotConnect)
{
  // Two disjoint closed boxes: the attachments sit on different ones.
  std::string obj;
  for (int box = 0; box < 2; ++box) {
    const double z0 = box * 20.0;
    for (int i = 0; i < 8; ++i)
      obj += "v " + std::to_string((i & 1) * 4.0) + " " + std::to_string(((i >> 1) & 1) * 4.0) +
             " " + std::to_string(z0 + ((i >> 2) & 1) * 10.0) + "\n";
    const int o = box * 8 + 1;
    const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                              {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& f : faces)
      obj += "f " + std::to_string(o + f[0]) + " " + std::to_string(o + f[1]) + " " +
             std::to_string(o + f[2]) + "\n";
  }
  const fs::path file = write_text("ligsim_two_boxes.obj", obj);
  expect_clean_failure("centerline --surface " + file.string(), fresh_folder("unconnected"),
                       "cannot be connected",
                       {"anatomy.json", "attachments.vtp", "mask.vti", "surface.vdb",
                        "distance.vti", "distance.vdb"});
}

TEST(BuildBadInput, ConfigWithUnknownKey)
{
  const fs::path config =
      write_text("ligsim_bad.toml", "[input]\nsurface = \"x.stl\"\n[centerline]\nalfa = 0.2\n");
  expect_clean_failure("build --config " + config.string(), fresh_folder("config"),
                       "unknown key 'alfa'");
}

// An integer beyond int was cast and wrapped (5000000000 became 705032704 iterations).
TEST(BuildBadInput, ConfigIntegerBeyondIntIsRefused)
{
  const fs::path config =
      write_text("ligsim_big.toml", "[input]\nsurface = \"x.stl\"\n"
                                    "[centerline]\nrelax_iterations = 5000000000\n");
  expect_clean_failure("build --config " + config.string(), fresh_folder("config_int"),
                       "ligsim_big.toml:4: [centerline] relax_iterations: expected an integer");
}

TEST(BuildBadInput, StrictRefusesANonManifoldEdgeAndSaysWhere)
{
  // Two closed tetrahedra sharing the edge (1, 0, 0)-(0, 1, 0): four triangles there. The
  // indices in the message are those of the surface as read (VTK merges and renumbers).
  const fs::path file =
      write_text("ligsim_bowtie.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 -1\nv 1 1 1\n"
                                      "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"
                                      "f 2 3 5\nf 3 2 6\nf 2 5 6\nf 3 6 5\n");
  expect_clean_failure("build --strict --surface " + file.string(), fresh_folder("strict"),
                       "three or more triangles (first: vertices 1 (0.00, 1.00, 0.00) and 2 "
                       "(1.00, 0.00, 0.00) mm)");
}

TEST(BuildBadInput, UnknownOrAmbiguousLabelNamesAreNamed)
{
  const std::string knee = source_path("data/vhf-right-knee/knee_labels.nrrd").string();
  // The shipped map names its labels MCL, femoral_cartilage, tibia.
  expect_clean_failure("build --labels " + knee + " --ligament-label ACL",
                       fresh_folder("unknown_label"), "'ACL' is not a label of this map");
  expect_clean_failure("build --labels " + knee + " --ligament-label ACL",
                       fresh_folder("unknown_label_list"), "'MCL' (1)");
  // A colour table that gives the name 'mcl' to another label makes 'Mcl' ambiguous.
  const fs::path table = write_text("ambiguous.ctbl", "1 MCL 1 2 3 255\n2 mcl 1 2 3 255\n");
  expect_clean_failure("build --labels " + knee + " --colour-table " + table.string() +
                           " --ligament-label Mcl",
                       fresh_folder("ambiguous_label"), "'Mcl' is ambiguous");
  expect_clean_failure("build --labels " + knee + " --colour-table /nonexistent/names.ctbl" +
                           " --ligament-label MCL",
                       fresh_folder("missing_table"), "missing colour table");
  fs::remove(table);
}
