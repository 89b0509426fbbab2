// Label names: Slicer's segment names in a .seg.nrrd header (a hand-written header, as Slicer
// writes it, and ours written back), colour tables beside the map, and names resolved exactly,
// then ignoring case, with clear errors for unknown and ambiguous names.

#include "common/error.hpp"
#include "stages/labelmap/label_image.hpp"
#include "stages/labelmap/label_names.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

using namespace ligsim;
using namespace ligsim::labelmap;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name)
{
  const fs::path dir =
      fs::temp_directory_path() / ("ligsim_label_names_" + std::to_string(::getpid()) + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// A NRRD of 4 x 3 x 2 unsigned-char voxels (labels 0, 2 and 5) with Slicer's segment keys,
/// written byte by byte as Slicer writes a single-layer segmentation; `layers` > 1 makes it the
/// 4-D layered kind.
void write_slicer_segmentation(const fs::path& file, int layers = 1)
{
  std::ofstream out(file, std::ios::binary);
  out << "NRRD0004\n"
         "type: unsigned char\n";
  if (layers == 1)
    out << "dimension: 3\n"
           "space: left-posterior-superior\n"
           "sizes: 4 3 2\n"
           "space directions: (0.5,0,0) (0,0.5,0) (0,0,1)\n"
           "kinds: domain domain domain\n";
  else
    out << "dimension: 4\n"
           "space: left-posterior-superior\n"
           "sizes: "
        << layers
        << " 4 3 2\n"
           "space directions: none (0.5,0,0) (0,0.5,0) (0,0,1)\n"
           "kinds: list domain domain domain\n";
  out << "encoding: raw\n"
         "space origin: (10,20,30)\n"
         "Segment0_Color:=0.9 0.4 0.3\n"
         "Segment0_ID:=Segment_1\n"
         "Segment0_LabelValue:=2\n"
         "Segment0_Layer:=0\n"
         "Segment0_Name:=Medial collateral ligament\n"
         "Segment1_ID:=Segment_2\n"
         "Segment1_LabelValue:=5\n"
         "Segment1_Layer:=0\n"
         "Segment1_Name:=Tibia\n"
         "Segmentation_MasterRepresentation:=Binary labelmap\n"
         "\n";
  for (int l = 0; l < layers; ++l)
    for (int v = 0; v < 24; ++v)
      out.put(static_cast<char>(v < 8 ? 2 : v < 16 ? 5 : 0));
}

/// The message of the InputError `action` throws (a test failure if it throws none).
std::string input_error(const std::function<void()>& action)
{
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

} // namespace

TEST(LabelNames, SlicerSegmentNamesAreReadFromTheHeader)
{
  const fs::path dir = fresh_dir("slicer");
  write_slicer_segmentation(dir / "knee.seg.nrrd");
  const LabelImage image = read_label_image(dir / "knee.seg.nrrd");
  EXPECT_EQ(image.dims, Eigen::Vector3i(4, 3, 2));
  EXPECT_EQ(std::count(image.labels.begin(), image.labels.end(), 2), 8);
  ASSERT_EQ(image.segment_names.size(), 2u);
  EXPECT_EQ(resolve_label("Medial collateral ligament", image.segment_names, "label"), 2);
  EXPECT_EQ(resolve_label("tibia", image.segment_names, "label"), 5);
  EXPECT_EQ(image.segment_names[1].source, "segment 1 of knee.seg.nrrd");

  // Our writer puts them back as Slicer's keys, so the names survive a round trip.
  write_label_image(image, dir / "copy.seg.nrrd");
  const LabelImage copy = read_label_image(dir / "copy.seg.nrrd");
  ASSERT_EQ(copy.segment_names.size(), 2u);
  EXPECT_EQ(resolve_label("Tibia", copy.segment_names, "label"), 5);
  EXPECT_EQ(copy.labels, image.labels);
  fs::remove_all(dir);
}

TEST(LabelNames, ALayeredSegmentationIsAClearError)
{
  const fs::path dir = fresh_dir("layers");
  write_slicer_segmentation(dir / "overlap.seg.nrrd", 2);
  const std::string layered = input_error([&] { read_label_image(dir / "overlap.seg.nrrd"); });
  EXPECT_TRUE(contains(layered, "overlap.seg.nrrd")) << layered;
  EXPECT_TRUE(contains(layered, "2 layers")) << layered;
  EXPECT_TRUE(contains(layered, "single-layer")) << layered;
  // A name of a segment in another layer cannot be used with a single layer.
  const std::vector<LabelName> names = {{3, "Femur", 1, "segment 4 of x.seg.nrrd"}};
  EXPECT_THROW(resolve_label("Femur", names, "label"), InputError);
  fs::remove_all(dir);
}

TEST(LabelNames, ColourTablesBesideTheImage)
{
  const fs::path dir = fresh_dir("tables");
  const auto beside = colour_tables_beside(dir / "seg.nrrd");
  EXPECT_EQ(beside.front(), dir / "seg.ctbl");
  EXPECT_NE(std::find(beside.begin(), beside.end(), dir / "seg.txt"), beside.end());
  EXPECT_NE(std::find(beside.begin(), beside.end(), dir / "seg_ColorTable.ctbl"), beside.end());
  const auto of_nifti = colour_tables_beside(dir / "knee.nii.gz");
  EXPECT_EQ(of_nifti.front(), dir / "knee.ctbl");
  const auto of_seg = colour_tables_beside(dir / "knee.seg.nrrd");
  EXPECT_NE(std::find(of_seg.begin(), of_seg.end(), dir / "knee.ctbl"), of_seg.end());
  EXPECT_NE(std::find(of_seg.begin(), of_seg.end(), dir / "knee.seg.ctbl"), of_seg.end());

  {
    std::ofstream table(dir / "seg.txt");
    table << "# FreeSurfer-style look-up table\n"
             "\n"
             "0   Unknown        0   0   0   0\n"
             "1   MCL          216 101  79 255   # the ligament\n"
             "7   Femur        241 214 145 255\n";
  }
  const std::vector<LabelName> names = read_colour_table(dir / "seg.txt");
  ASSERT_EQ(names.size(), 3u);
  EXPECT_EQ(resolve_label("Femur", names, "label"), 7);
  EXPECT_EQ(resolve_label("mcl", names, "label"), 1);
  EXPECT_EQ(names[1].source, "seg.txt:4");

  // What we write reads back the same, spaces as underscores.
  write_colour_table({{1, "Medial collateral ligament", 0, ""}, {7, "Femur", 0, ""}},
                     dir / "seg.ctbl");
  const std::vector<LabelName> written = read_colour_table(dir / "seg.ctbl");
  EXPECT_EQ(resolve_label("Medial_collateral_ligament", written, "label"), 1);
  EXPECT_EQ(resolve_label("background", written, "label"), 0);

  {
    std::ofstream bad(dir / "bad.ctbl");
    bad << "# header\n1 MCL 1 2 3 255\nseven Femur 1 2 3 255\n";
  }
  {
    std::ofstream itk_snap(dir / "snap.txt");
    itk_snap << "# ITK-SNAP Label Description File\n"
                "#  IDX   -R-  -G-  -B-  -A--  VIS MSH  LABEL\n"
                "    0     0    0    0     0  0  0    \"Clear Label\"\n"
                "    3   255    0    0     1  1  1    \"Medial collateral ligament\"\n";
  }
  const std::vector<LabelName> snap = read_colour_table(dir / "snap.txt");
  ASSERT_EQ(snap.size(), 2u);
  EXPECT_EQ(resolve_label("Medial collateral ligament", snap, "label"), 3);
  EXPECT_EQ(snap[1].source, "snap.txt:4");

  const std::string bad = input_error([&] { read_colour_table(dir / "bad.ctbl"); });
  EXPECT_TRUE(contains(bad, "bad.ctbl', line 3")) << bad;
  EXPECT_THROW(read_colour_table(dir / "missing.ctbl"), InputError);
  fs::remove_all(dir);
}

TEST(LabelNames, ExactNamesFirstThenCaseThenClearErrors)
{
  const std::vector<LabelName> names = {{1, "mcl", 0, "segment 0 of a.seg.nrrd"},
                                        {5, "MCL", 0, "a.ctbl:3"},
                                        {2, "Femur", 0, "segment 1 of a.seg.nrrd"},
                                        {2, "femur", 0, "a.ctbl:4"},
                                        {3, "Tibia", 0, "a.ctbl:5"}};
  EXPECT_EQ(resolve_label("4", names, "label"), 4); // numbers are numbers
  EXPECT_EQ(resolve_label("mcl", names, "label"), 1);
  EXPECT_EQ(resolve_label("MCL", names, "label"), 5);
  EXPECT_EQ(resolve_label("FEMUR", names, "label"), 2); // two sources, one label
  EXPECT_EQ(resolve_label("tibia", names, "label"), 3);
  const std::string ambiguous = input_error([&] { resolve_label("Mcl", names, "ligament label"); });
  EXPECT_TRUE(contains(ambiguous, "ligament label 'Mcl' is ambiguous")) << ambiguous;
  EXPECT_TRUE(contains(ambiguous, "1 (segment 0 of a.seg.nrrd)")) << ambiguous;
  EXPECT_TRUE(contains(ambiguous, "5 (a.ctbl:3)")) << ambiguous;
  const std::string unknown = input_error([&] { resolve_label("ACL", names, "label"); });
  EXPECT_TRUE(contains(unknown, "'ACL' is not a label")) << unknown;
  EXPECT_TRUE(contains(unknown, "'Tibia' (3)")) << unknown;
  EXPECT_TRUE(contains(unknown, "'MCL' (5)")) << unknown;
  const std::string unnamed = input_error([&] { resolve_label("ACL", {}, "label"); });
  EXPECT_TRUE(contains(unnamed, "names no labels")) << unnamed;
}
