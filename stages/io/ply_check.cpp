#include "stages/io/ply_check.hpp"

#include "stages/io/text_cursor.hpp"

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace ligsim::io {

namespace fs = std::filesystem;

namespace {

/// vtkPLY reads a line into a 4096-byte buffer; a longer one is split and misread.
constexpr std::size_t max_line_chars = 4000;
constexpr long long max_elements = 0x7fffffff; // vtkPLY counts in int

struct Type {
  int bytes = 0;
  bool is_signed = false;
  bool is_integer = false;
};

bool type_of(const std::string& name, Type& type)
{
  struct Named {
    const char* name;
    Type type;
  };
  static const std::array<Named, 16> types = {{
      {"char", {1, true, true}},
      {"int8", {1, true, true}},
      {"uchar", {1, false, true}},
      {"uint8", {1, false, true}},
      {"short", {2, true, true}},
      {"int16", {2, true, true}},
      {"ushort", {2, false, true}},
      {"uint16", {2, false, true}},
      {"int", {4, true, true}},
      {"int32", {4, true, true}},
      {"uint", {4, false, true}},
      {"uint32", {4, false, true}},
      {"float", {4, true, false}},
      {"float32", {4, true, false}},
      {"double", {8, true, false}},
      {"float64", {8, true, false}},
  }};
  for (const Named& named : types)
    if (name == named.name) {
      type = named.type;
      return true;
    }
  return false;
}

struct Property {
  std::string name;
  bool list = false;
  Type count_type; // lists only
  Type item_type;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

enum class Format { ascii, little_endian, big_endian };

std::vector<std::string> words_of(const std::string& line)
{
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t')
      ++i;
    if (i > start)
      words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::string checked_line(TextCursor& text)
{
  const std::size_t start = text.position();
  if (start == text.size())
    text.fail_here("the file ends (truncated?)");
  std::string line = text.rest_of_line();
  if (line.size() > max_line_chars)
    text.fail_here("line starting at byte {} is longer than {} characters", start, max_line_chars);
  if (line.find('\0') != std::string::npos)
    text.fail_here("a NUL byte in a text line");
  return line;
}

long long header_count(TextCursor& text, const std::string& word)
{
  char* end = nullptr;
  const long long count = std::strtoll(word.c_str(), &end, 10);
  if (end != word.c_str() + word.size() || word.empty() || count < 0 || count > max_elements)
    text.fail_here("element count '{:.40}' is not an integer in 0..{}", word, max_elements);
  return count;
}

Type header_type(TextCursor& text, const std::string& word)
{
  Type type;
  if (!type_of(word, type))
    text.fail_here("unknown property type '{:.40}'", word);
  return type;
}

void check_header_line(TextCursor& text, const std::vector<std::string>& words,
                       std::vector<Element>& elements, Format& format, bool& have_format)
{
  // VTK's PLY reader frees an uninitialised pointer after a blank header line (fuzz finding).
  if (words.empty())
    text.fail_here("a blank line in the header");
  if (words[0] == "comment" || words[0] == "obj_info")
    return;
  if (words[0] == "format") {
    if (words.size() != 3 || words[2] != "1.0")
      text.fail_here("expected 'format <kind> 1.0' on this line");
    if (words[1] == "ascii")
      format = Format::ascii;
    else if (words[1] == "binary_little_endian")
      format = Format::little_endian;
    else if (words[1] == "binary_big_endian")
      format = Format::big_endian;
    else
      text.fail_here("unknown PLY format '{:.40}'", words[1]);
    have_format = true;
  } else if (words[0] == "element") {
    if (words.size() != 3)
      text.fail_here("expected 'element <name> <count>' on this line");
    for (const Element& e : elements)
      if (e.name == words[1])
        text.fail_here("element '{:.40}' is declared twice", words[1]);
    elements.push_back({words[1], header_count(text, words[2]), {}});
  } else if (words[0] == "property") {
    if (elements.empty())
      text.fail_here("a property before any element");
    Property p;
    if (words.size() == 5 && words[1] == "list") {
      p = {words[4], true, header_type(text, words[2]), header_type(text, words[3])};
      if (!p.count_type.is_integer)
        text.fail_here("list '{:.40}' has a non-integer count type", p.name);
    } else if (words.size() == 3) {
      p = {words[2], false, {}, header_type(text, words[1])};
    } else {
      text.fail_here("expected 'property <type> <name>' or 'property list <count type> "
                     "<type> <name>' on this line");
    }
    // Two properties of one name made vtkPLYReader read out of bounds (SEGV).
    for (const Property& other : elements.back().properties)
      if (other.name == p.name)
        text.fail_here("property '{:.40}' is declared twice in element '{:.40}'", p.name,
                       elements.back().name);
    elements.back().properties.push_back(p);
  } else {
    text.fail_here("unknown header line starting '{:.40}'", words[0]);
  }
}

Format parse_header(TextCursor& text, std::vector<Element>& elements)
{
  if (checked_line(text) != "ply")
    text.fail_here("a PLY file starts with the line 'ply'");
  text.next_line();
  bool have_format = false;
  Format format = Format::ascii;
  for (;;) {
    const std::vector<std::string> words = words_of(checked_line(text));
    if (words.size() == 1 && words[0] == "end_header") {
      text.next_line();
      break;
    }
    check_header_line(text, words, elements, format, have_format);
    text.next_line();
  }
  if (!have_format)
    text.fail_here("the header has no 'format' line");
  return format;
}

const Property* find_property(const Element& element, const std::string& name)
{
  for (const Property& p : element.properties)
    if (p.name == name)
      return &p;
  return nullptr;
}

/// What vtkPLYReader relies on: x, y, z on the vertices, a corner list on the faces.
void require_surface_elements(TextCursor& text, const std::vector<Element>& elements)
{
  bool have_vertices = false;
  for (const Element& e : elements) {
    if (e.count > 0 && e.properties.empty())
      text.fail_here("element '{:.40}' has {} entries but no properties", e.name, e.count);
    if (e.name == "vertex") {
      have_vertices = true;
      for (const char* axis : {"x", "y", "z"}) {
        const Property* p = find_property(e, axis);
        if (p == nullptr || p->list)
          text.fail_here("the vertex element has no scalar property '{}'", axis);
      }
    }
    if (e.name == "face") {
      // vtkPLYReader reads the faces into the points it has read so far (SEGV without them).
      if (!have_vertices)
        text.fail_here("the face element comes before the vertex element");
      const Property* p = find_property(e, "vertex_indices");
      if (p == nullptr)
        p = find_property(e, "vertex_index");
      if (p == nullptr || !p->list || !p->item_type.is_integer)
        text.fail_here("the face element has no integer list 'vertex_indices'");
    }
  }
  if (!have_vertices)
    text.fail_here("the header declares no 'vertex' element");
}

long long read_count(const std::string& bytes, std::size_t at, Type type, bool big_endian)
{
  std::array<unsigned char, 4> raw{};
  std::memcpy(raw.data(), bytes.data() + at, static_cast<std::size_t>(type.bytes));
  std::uint32_t value = 0;
  for (int i = 0; i < type.bytes; ++i) {
    const int k = big_endian ? i : type.bytes - 1 - i;
    value = (value << 8) | raw[static_cast<std::size_t>(k)];
  }
  if (!type.is_signed)
    return value;
  const int bits = 8 * type.bytes;
  if (bits < 32 && (value >> (bits - 1)) != 0u)
    return static_cast<long long>(value) - (1LL << bits);
  return static_cast<std::int32_t>(value);
}

bool is_face_corners(const Element& element, const Property& property)
{
  return element.name == "face" &&
         (property.name == "vertex_indices" || property.name == "vertex_index");
}

void check_list_count(TextCursor& text, const Element& element, long long entry,
                      const Property& property, long long count)
{
  if (count < 0)
    text.fail_here("{} {}: list '{}' has a negative length {}", element.name, entry, property.name,
                   count);
  if (is_face_corners(element, property) && count > 255)
    text.fail_here("face {} has {} corners (at most 255 are read)", entry, count);
}

void check_binary_body(TextCursor& text, const std::vector<Element>& elements, bool big_endian)
{
  for (const Element& element : elements)
    for (long long entry = 0; entry < element.count; ++entry)
      for (const Property& property : element.properties) {
        if (!property.list) {
          text.skip_bytes(static_cast<std::size_t>(property.item_type.bytes), "the next property");
          continue;
        }
        const std::size_t at = text.position();
        text.skip_bytes(static_cast<std::size_t>(property.count_type.bytes), "a list length");
        const long long count = read_count(text.bytes(), at, property.count_type, big_endian);
        check_list_count(text, element, entry, property, count);
        text.skip_bytes(static_cast<std::size_t>(count) *
                            static_cast<std::size_t>(property.item_type.bytes),
                        "a list");
      }
}

void check_ascii_body(TextCursor& text, const std::vector<Element>& elements)
{
  for (const Element& element : elements)
    for (long long entry = 0; entry < element.count; ++entry) {
      const std::vector<std::string> words = words_of(checked_line(text));
      std::size_t next = 0;
      for (const Property& property : element.properties) {
        long long items = 1;
        if (property.list) {
          char* end = nullptr;
          items = next < words.size() ? std::strtoll(words[next].c_str(), &end, 10) : -1;
          if (next >= words.size() || end != words[next].c_str() + words[next].size())
            text.fail_here("{} {}: list '{}' has no integer length", element.name, entry,
                           property.name);
          check_list_count(text, element, entry, property, items);
          ++next;
        }
        for (long long i = 0; i < items; ++i, ++next) {
          char* end = nullptr;
          if (next < words.size())
            std::strtod(words[next].c_str(), &end);
          if (next >= words.size() || end != words[next].c_str() + words[next].size())
            text.fail_here("{} {}: expected a number for '{}', found '{:.40}'", element.name, entry,
                           property.name,
                           next < words.size() ? words[next] : std::string("the line end"));
        }
      }
      if (next != words.size())
        text.fail_here("{} {} has {} numbers, {} more than its properties", element.name, entry,
                       words.size(), words.size() - next);
      // VTK's PLY reader frees a word list twice when the last line has no line end (fuzz
      // finding); a whole file has one.
      if (text.position() == text.size())
        text.fail_here("{} {}: the last line has no line end (truncated?)", element.name, entry);
      text.next_line();
    }
}

} // namespace

void check_ply(const fs::path& file)
{
  const std::string bytes = read_bytes(file);
  TextCursor text(file, bytes);
  std::vector<Element> elements;
  const Format format = parse_header(text, elements);
  require_surface_elements(text, elements);
  if (format == Format::ascii)
    check_ascii_body(text, elements);
  else
    check_binary_body(text, elements, format == Format::big_endian);
}

} // namespace ligsim::io
