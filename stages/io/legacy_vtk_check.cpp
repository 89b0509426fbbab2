#include "stages/io/legacy_vtk_check.hpp"

#include "stages/io/text_cursor.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace ligsim::io {

namespace fs = std::filesystem;

namespace {

/// vtkDataReader reads words and lines into 256-byte buffers.
constexpr std::size_t max_word_chars = 255;
constexpr long long max_count = 1LL << 40;

std::string lower(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

struct DataType {
  int bytes = 0;
  bool is_signed = true;
};

/// The data types vtkDataReader reads (bit, string and variant arrays are refused).
bool data_type(const std::string& name, DataType& type)
{
  struct Named {
    const char* name;
    DataType type;
  };
  static const std::array<Named, 13> types = {{
      {"char", {1, true}},
      {"unsigned_char", {1, false}},
      {"short", {2, true}},
      {"unsigned_short", {2, false}},
      {"int", {4, true}},
      {"unsigned_int", {4, false}},
      {"long", {8, true}},
      {"unsigned_long", {8, false}},
      {"float", {4, true}},
      {"double", {8, true}},
      {"vtkidtype", {8, true}},
      {"vtktypeint64", {8, true}},
      {"vtktypeuint64", {8, false}},
  }};
  for (const Named& named : types)
    if (lower(name) == named.name) {
      type = named.type;
      return true;
    }
  return false;
}

class LegacyVtkChecker {
public:
  LegacyVtkChecker(const fs::path& file, const std::string& bytes)
      : text_(file, bytes)
  {
  }

  void check()
  {
    header();
    while (text_.skip_space())
      section(lower(word("a section keyword")));
  }

private:
  std::string word(const char* what)
  {
    std::string found = text_.word(what);
    if (found.size() > max_word_chars)
      text_.fail_here("a word of {} characters (at most {} are read)", found.size(),
                      max_word_chars);
    return found;
  }

  long long count(const char* what) { return text_.integer(what, 0, max_count); }

  DataType type_word()
  {
    const std::string name = word("a data type");
    DataType type;
    if (!data_type(name, type))
      text_.fail_here("unsupported data type '{:.40}'", name);
    return type;
  }

  void header()
  {
    const std::string first = text_.rest_of_line();
    int major = 0, minor = 0;
    if (first.size() > max_word_chars ||
        std::sscanf(first.c_str(), "# vtk DataFile Version %d.%d", &major, &minor) != 2)
      text_.fail_here("a legacy VTK file starts with '# vtk DataFile Version <major>.<minor>'");
    new_layout_ = major >= 5; // as vtkDataReader decides: offsets and connectivity arrays
    text_.next_line();
    if (text_.position() == text_.size())
      text_.fail_here("the file ends after its first line");
    if (text_.rest_of_line().size() > max_word_chars)
      text_.fail_here("the title is longer than {} characters", max_word_chars);
    text_.next_line();
    const std::string encoding = lower(word("ASCII or BINARY"));
    if (encoding != "ascii" && encoding != "binary")
      text_.fail_here("expected ASCII or BINARY, found '{:.40}'", encoding);
    binary_ = encoding == "binary";
    if (lower(word("DATASET")) != "dataset")
      text_.fail_here("expected 'DATASET POLYDATA'");
    const std::string type = word("a dataset type");
    if (lower(type) != "polydata")
      text_.fail_here("dataset type '{:.40}' is not a surface (expected POLYDATA)", type);
  }

  /// Skips `values` values of `type`; returns them when `keep` (cell ids).
  std::vector<long long> values(long long values, DataType type, const char* what, bool keep)
  {
    std::vector<long long> kept;
    if (binary_) {
      text_.next_line();
      const std::size_t start = text_.position();
      if (static_cast<unsigned long long>(values) * static_cast<unsigned>(type.bytes) >
          text_.size() - start)
        text_.fail_here("{} needs {} values of {} bytes, but the file ends {} bytes later "
                        "(truncated?)",
                        what, values, type.bytes, text_.size() - start);
      text_.skip_bytes(static_cast<std::size_t>(values) * static_cast<std::size_t>(type.bytes),
                       what);
      if (keep)
        for (long long i = 0; i < values; ++i)
          kept.push_back(big_endian(start + static_cast<std::size_t>(i * type.bytes), type));
      return kept;
    }
    for (long long i = 0; i < values; ++i) {
      if (keep)
        kept.push_back(text_.integer(what, -max_count, max_count));
      else
        text_.number(what);
    }
    return kept;
  }

  long long big_endian(std::size_t at, DataType type) const
  {
    std::uint64_t value = 0;
    for (int i = 0; i < type.bytes; ++i)
      value = (value << 8) |
              static_cast<unsigned char>(text_.bytes()[at + static_cast<std::size_t>(i)]);
    const int bits = 8 * type.bytes;
    if (type.is_signed && bits < 64 && (value >> (bits - 1)) != 0u)
      return static_cast<long long>(value) - (1LL << bits);
    return static_cast<long long>(value);
  }

  void require_point(long long id, long long cell)
  {
    if (id < 0 || id >= points_)
      text_.fail_here("cell {} refers to point {}, but there are {} points", cell, id, points_);
  }

  void points()
  {
    if (points_ >= 0)
      text_.fail_here("a second POINTS section");
    points_ = count("the point count");
    values(3 * points_, type_word(), "the points", false);
  }

  void cells(const std::string& keyword)
  {
    if (points_ < 0)
      text_.fail_here("{} before POINTS", keyword);
    const long long first = count("a cell count");
    const long long second = count("a cell array size");
    if (new_layout_)
      offset_cells(first, second);
    else
      packed_cells(first, second);
  }

  /// Up to version 4: N SIZE, then SIZE integers "n id0 .. idn-1" for N cells.
  void packed_cells(long long cells, long long size)
  {
    const std::vector<long long> ids = values(size, {4, true}, "the cell list", true);
    std::size_t at = 0;
    for (long long c = 0; c < cells; ++c) {
      if (at >= ids.size() || ids[at] < 0 || ids[at] > static_cast<long long>(ids.size() - at - 1))
        text_.fail_here("cell {} of {} does not fit in the cell list of {} numbers", c, cells,
                        size);
      const long long n = ids[at++];
      for (long long k = 0; k < n; ++k)
        require_point(ids[at++], c);
    }
    if (at != ids.size())
      text_.fail_here("the cell list holds {} numbers, {} more than its {} cells use", size,
                      ids.size() - at, cells);
    cells_ += cells;
  }

  /// Version 5: OFFSETS (N+1 values from 0 to SIZE, not decreasing) and CONNECTIVITY (SIZE ids).
  void offset_cells(long long offset_count, long long size)
  {
    if (lower(word("OFFSETS")) != "offsets")
      text_.fail_here("expected OFFSETS");
    const std::vector<long long> offsets = values(offset_count, type_word(), "the offsets", true);
    if (lower(word("CONNECTIVITY")) != "connectivity")
      text_.fail_here("expected CONNECTIVITY");
    const std::vector<long long> ids = values(size, type_word(), "the connectivity", true);
    if (offsets.empty() ? size != 0 : offsets.front() != 0 || offsets.back() != size)
      text_.fail_here("the offsets must run from 0 to the connectivity size {}", size);
    for (std::size_t c = 1; c < offsets.size(); ++c)
      if (offsets[c] < offsets[c - 1])
        text_.fail_here("offset {} decreases ({} after {})", c, offsets[c], offsets[c - 1]);
    for (std::size_t c = 1; c < offsets.size(); ++c)
      for (long long k = offsets[c - 1]; k < offsets[c]; ++k)
        require_point(ids[static_cast<std::size_t>(k)], static_cast<long long>(c - 1));
    cells_ += offsets.empty() ? 0 : static_cast<long long>(offsets.size()) - 1;
  }

  void attribute_block(long long expected, const char* what)
  {
    const long long n = count(what);
    if (n != expected)
      text_.fail_here("{} is {}, but the file has {}", what, n, expected);
    tuples_ = n;
  }

  void require_attribute_block(const std::string& keyword) const
  {
    if (tuples_ < 0)
      text_.fail_here("{} outside POINT_DATA or CELL_DATA", keyword);
  }

  /// COMPONENT_NAMES lines and INFORMATION keys (a NAME line, a DATA line each), up to an empty
  /// line.
  void metadata()
  {
    text_.next_line();
    for (;;) {
      const std::string line = text_.rest_of_line();
      if (text_.position() == text_.size() && line.empty())
        return;
      if (line.find_first_not_of(" \t") == std::string::npos) {
        text_.next_line();
        return;
      }
      if (line.size() > max_word_chars)
        text_.fail_here("a METADATA line longer than {} characters", max_word_chars);
      text_.next_line();
    }
  }

  void field()
  {
    word("a field name");
    const long long arrays = count("the number of field arrays");
    for (long long a = 0; a < arrays; ++a) {
      word("an array name");
      const long long components = text_.integer("a component count", 1, 1 << 16);
      const long long tuples = count("a tuple count");
      values(components * tuples, type_word(), "a field array", false);
      if (lower(text_.peek_word()) == "metadata") {
        word("METADATA");
        metadata();
      }
    }
  }

  void section(const std::string& keyword)
  {
    if (keyword == "points")
      return points();
    if (keyword == "vertices" || keyword == "lines" || keyword == "polygons" ||
        keyword == "triangle_strips")
      return cells(keyword);
    if (keyword == "point_data")
      return attribute_block(points_ < 0 ? 0 : points_, "the POINT_DATA count");
    if (keyword == "cell_data")
      return attribute_block(cells_, "the CELL_DATA count");
    if (keyword == "field")
      return field();
    if (keyword == "metadata")
      return metadata();
    require_attribute_block(keyword);
    word("an attribute name");
    if (keyword == "scalars") {
      const DataType type = type_word();
      long long components = 1;
      if (!text_.at_line_end())
        components = text_.integer("the component count", 1, 4);
      if (lower(word("LOOKUP_TABLE")) != "lookup_table")
        text_.fail_here("expected LOOKUP_TABLE after SCALARS");
      word("a lookup table name");
      values(components * tuples_, type, "the scalars", false);
    } else if (keyword == "color_scalars") {
      const long long components = text_.integer("the component count", 1, 4);
      values(components * tuples_, binary_ ? DataType{1, false} : DataType{4, true},
             "the colour scalars", false);
    } else if (keyword == "lookup_table") {
      const long long entries = count("the lookup table size");
      values(4 * entries, binary_ ? DataType{1, false} : DataType{4, true}, "the lookup table",
             false);
    } else if (keyword == "vectors" || keyword == "normals") {
      values(3 * tuples_, type_word(), "the vectors", false);
    } else if (keyword == "texture_coordinates") {
      const long long dimension = text_.integer("the texture dimension", 1, 3);
      values(dimension * tuples_, type_word(), "the texture coordinates", false);
    } else if (keyword == "tensors" || keyword == "tensors6") {
      values((keyword == "tensors" ? 9 : 6) * tuples_, type_word(), "the tensors", false);
    } else if (keyword == "global_ids" || keyword == "pedigree_ids") {
      values(tuples_, type_word(), "the ids", false);
    } else {
      text_.fail_here("unknown section '{:.40}'", keyword);
    }
  }

  TextCursor text_;
  bool binary_ = false;
  bool new_layout_ = false;
  long long points_ = -1; // -1 until POINTS
  long long cells_ = 0;
  long long tuples_ = -1; // values per attribute in the current POINT_DATA/CELL_DATA block
};

} // namespace

void check_legacy_vtk(const fs::path& file)
{
  const std::string bytes = read_bytes(file);
  LegacyVtkChecker(file, bytes).check();
}

} // namespace ligsim::io
