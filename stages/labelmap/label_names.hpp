#pragma once
/// @brief Names of labels: Slicer's segment names (`.seg.nrrd` header) and colour tables
/// (`.ctbl`, FreeSurfer-style `.txt`: lines `value name r g b a`; ITK-SNAP's label descriptions),
/// and a label given as a number or a name resolved against them.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::labelmap {

/// One name of a label and where it was read.
struct LabelName {
  std::int32_t value = 0;
  std::string name;
  int layer = 0;      ///< Slicer segment layer; a single-layer (3-D) map only has layer 0
  std::string source; ///< "segment 2 of seg.nrrd", "seg.ctbl:7"
};

/// Slicer's segment keys of a NRRD header (`SegmentN_Name`, `SegmentN_LabelValue`, default 1,
/// `SegmentN_Layer`, default 0) as names; `file` is named in the sources. Throws InputError on
/// a label value or layer that is not an integer.
std::vector<LabelName> segment_names(const std::vector<std::pair<std::string, std::string>>& keys,
                                     const std::filesystem::path& file);

/// The header keys that carry `names` as Slicer segments (binary labelmap, one layer).
std::vector<std::pair<std::string, std::string>> segment_keys(const std::vector<LabelName>& names);

/// A colour table: `#` comments, blank lines, lines `value name [r g b a ...]` (Slicer,
/// FreeSurfer) or `value r g b a visible mesh "name"` (ITK-SNAP: a quoted name wins). Throws
/// InputError naming the file and line of a line without an integer value and a name.
std::vector<LabelName> read_colour_table(const std::filesystem::path& file);

/// Writes `names` as a Slicer colour table (names' spaces as underscores), atomically.
void write_colour_table(const std::vector<LabelName>& names, const std::filesystem::path& file);

/// The colour tables that may lie beside a label map, existing or not: for `seg.nrrd`,
/// `seg.ctbl`, `seg.txt` and Slicer's `seg_ColorTable.ctbl` (for `seg.seg.nrrd` the stem `seg`
/// as well as `seg.seg`).
std::vector<std::filesystem::path> colour_tables_beside(const std::filesystem::path& image);

/// The colour tables that name a label map's labels: those of colour_tables_beside that exist;
/// if none does, the one `.ctbl` file in the map's folder (a Slicer bundle saves `seg.nrrd` beside
/// `knee.ctbl`). Several `.ctbl` files and none of the map's own stem: none (which one is meant
/// is not known; `note`, if given, says so).
std::vector<std::filesystem::path> colour_tables_found(const std::filesystem::path& image,
                                                       std::string* note = nullptr);

/// The label `text` names: a number as itself, else a name of `names`, matched exactly, then
/// ignoring case. Throws InputError, starting with `what`, if the name is unknown (listing the
/// names there are), ambiguous (naming the labels it could be), or a segment of another layer.
std::int32_t resolve_label(const std::string& text, const std::vector<LabelName>& names,
                           const std::string& what);

} // namespace ligsim::labelmap
