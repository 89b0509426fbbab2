#include "stages/io/obj_reader.hpp"

#include "common/error.hpp"
#include "stages/io/text_cursor.hpp"

#include <vtkCellArray.h>
#include <vtkPoints.h>

#include <cerrno>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

namespace ligsim::io {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split_words(std::string_view line)
{
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
      ++i;
    if (i > start)
      words.emplace_back(line.substr(start, i - start));
  }
  return words;
}

struct Counts {
  long long vertices = 0, texture_coordinates = 0, normals = 0;
};

class ObjParser {
public:
  explicit ObjParser(const fs::path& file)
      : file_(file.string())
  {
  }

  void parse_line(std::string_view line, std::size_t number)
  {
    line_ = number;
    const std::size_t comment = line.find('#');
    const std::vector<std::string> words = split_words(line.substr(0, comment));
    if (words.empty())
      return;
    if (words[0] == "v")
      parse_vertex(words);
    else if (words[0] == "vt")
      ++counts_.texture_coordinates;
    else if (words[0] == "vn")
      ++counts_.normals;
    else if (words[0] == "f")
      parse_face(words);
  }

  vtkSmartPointer<vtkPolyData> result()
  {
    auto data = vtkSmartPointer<vtkPolyData>::New();
    data->SetPoints(points_);
    data->SetPolys(faces_);
    return data;
  }

private:
  template <class... Args>
  [[noreturn]] void fail_here(fmt::format_string<Args...> format, Args&&... args) const
  {
    fail("'{}' line {}: {}", file_, line_, fmt::format(format, std::forward<Args>(args)...));
  }

  double coordinate(const std::string& word) const
  {
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size())
      fail_here("vertex coordinate '{:.40}' is not a number", word);
    return value;
  }

  void parse_vertex(const std::vector<std::string>& words)
  {
    if (words.size() < 4)
      fail_here("a vertex needs three coordinates, found {}", words.size() - 1);
    points_->InsertNextPoint(coordinate(words[1]), coordinate(words[2]), coordinate(words[3]));
    ++counts_.vertices;
  }

  /// One index of a face corner: 1-based, or negative counting back from the last defined;
  /// returns it 0-based. `kind` names what it indexes in errors.
  long long index(std::string_view text, long long defined, const char* kind,
                  const std::string& corner) const
  {
    const std::string digits(text);
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(digits.c_str(), &end, 10);
    if (digits.empty() || end != digits.c_str() + digits.size() || errno == ERANGE)
      fail_here("face corner '{:.40}': {} index '{:.40}' is not an integer", corner, kind, digits);
    const long long zero_based = value > 0 ? value - 1 : defined + value;
    if (value == 0 || zero_based < 0 || zero_based >= defined)
      fail_here("face corner '{:.40}' refers to {} {}, but {} are defined above it", corner, kind,
                value, defined);
    return zero_based;
  }

  void parse_face(const std::vector<std::string>& words)
  {
    if (words.size() < 4)
      fail_here("a face needs at least three corners, found {}", words.size() - 1);
    std::vector<vtkIdType> ids;
    ids.reserve(words.size() - 1);
    for (std::size_t k = 1; k < words.size(); ++k) {
      const std::string_view corner = words[k];
      const std::size_t slash = corner.find('/');
      ids.push_back(index(corner.substr(0, slash), counts_.vertices, "vertex", words[k]));
      if (slash == std::string_view::npos)
        continue;
      const std::string_view rest = corner.substr(slash + 1);
      const std::size_t second = rest.find('/');
      const std::string_view texture = rest.substr(0, second);
      if (!texture.empty())
        index(texture, counts_.texture_coordinates, "texture coordinate", words[k]);
      if (second == std::string_view::npos) {
        if (texture.empty())
          fail_here("face corner '{:.40}' ends in '/' without an index", words[k]);
        continue;
      }
      index(rest.substr(second + 1), counts_.normals, "normal", words[k]);
    }
    faces_->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }

  std::string file_;
  std::size_t line_ = 0;
  Counts counts_;
  vtkSmartPointer<vtkPoints> points_ = vtkSmartPointer<vtkPoints>::New();
  vtkSmartPointer<vtkCellArray> faces_ = vtkSmartPointer<vtkCellArray>::New();
};

} // namespace

vtkSmartPointer<vtkPolyData> read_obj(const fs::path& file)
{
  const std::string bytes = read_bytes(file);
  ObjParser parser(file);
  std::size_t start = 0, number = 1;
  while (start < bytes.size()) {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos)
      end = bytes.size();
    parser.parse_line(std::string_view(bytes).substr(start, end - start), number++);
    start = end + 1;
  }
  return parser.result();
}

} // namespace ligsim::io
