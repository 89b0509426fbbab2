#include "stages/io/gltf_check.hpp"

#include "common/error.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>

namespace ligsim::io {

namespace fs = std::filesystem;

namespace {

using json = nlohmann::json;

constexpr std::int64_t max_int = 0x7fffffff; // VTK's loader counts and offsets in int
constexpr int max_json_depth = 64;
constexpr int max_node_depth = 1000;
constexpr std::uint32_t glb_magic = 0x46546C67; // "glTF"
constexpr std::uint32_t chunk_json = 0x4E4F534A;
constexpr std::uint32_t chunk_bin = 0x004E4942;

/// The JSON text of a glTF file and, for a .glb, the length of its BIN chunk.
struct Container {
  std::string json_text;
  std::optional<std::int64_t> bin_bytes;
};

std::uint32_t le32(const std::string& bytes, std::size_t at)
{
  std::uint32_t value = 0;
  for (int b = 3; b >= 0; --b)
    value = (value << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(b)]);
  return value;
}

/// Checks the header and chunks of a binary glTF file (glTF 2.0 specification, section 4.4).
Container read_glb(const fs::path& file, const std::string& bytes)
{
  const auto bad = [&](const std::string& what) { fail("'{}': {}", file.string(), what); };
  if (bytes.size() < 20)
    bad(fmt::format("{} bytes is too short for a glTF binary file (header and a JSON chunk need "
                    "at least 20)",
                    bytes.size()));
  if (le32(bytes, 0) != glb_magic)
    bad("not a glTF binary file (the first four bytes are not 'glTF')");
  if (le32(bytes, 4) != 2)
    bad(fmt::format("glTF binary version {}, ligsim reads version 2", le32(bytes, 4)));
  if (le32(bytes, 8) != bytes.size())
    bad(fmt::format("the header gives a length of {} bytes, the file has {} (truncated?)",
                    le32(bytes, 8), bytes.size()));
  Container container;
  std::size_t at = 12;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    if (bytes.size() - at < 8)
      bad(fmt::format("chunk {} at byte {}: its 8-byte header runs past the end", chunk, at));
    const std::uint32_t length = le32(bytes, at), type = le32(bytes, at + 4);
    if (length > bytes.size() - at - 8)
      bad(fmt::format("chunk {} at byte {}: {} bytes announced, {} left in the file", chunk, at,
                      length, bytes.size() - at - 8));
    if (chunk == 0) {
      if (type != chunk_json)
        bad("the first chunk is not JSON");
      container.json_text = bytes.substr(at + 8, length);
    } else if (chunk == 1 && type == chunk_bin) {
      container.bin_bytes = length;
    } else if (chunk == 1) {
      bad("the second chunk is neither BIN nor absent");
    }
    at += 8 + std::size_t(length);
  }
  // Some writers pad the JSON chunk with NULs instead of the spaces the specification asks for.
  while (!container.json_text.empty() && container.json_text.back() == '\0')
    container.json_text.pop_back();
  return container;
}

json parse_json(const fs::path& file, const std::string& text)
{
  try {
    return json::parse(text, [&](int depth, json::parse_event_t, json&) {
      if (depth > max_json_depth)
        fail("'{}': JSON nested deeper than {} levels", file.string(), max_json_depth);
      return true;
    });
  } catch (const json::exception& e) {
    fail("'{}': not valid JSON: {}", file.string(), e.what());
  }
}

/// Checks glTF's JSON document against the file's buffers, element by element.
class Checker {
public:
  Checker(fs::path file, const json& root, std::optional<std::int64_t> bin_bytes)
      : m_file(std::move(file))
      , m_root(root)
      , m_bin_bytes(bin_bytes)
  {
  }

  GltfContents run()
  {
    if (!m_root.is_object())
      bad("the JSON document is not an object");
    check_asset();
    for (const char* unsupported : {"skins", "animations"})
      if (const json* list = member(m_root, unsupported); list && !list->empty())
        bad(fmt::format("has {}: ligsim reads static meshes only", unsupported));
    for (const char* name : {"buffers", "bufferViews", "accessors", "meshes", "nodes", "scenes",
                             "materials", "textures", "images", "samplers", "cameras"})
      list(name);
    check_buffers();
    check_buffer_views();
    check_accessors();
    check_meshes();
    check_materials();
    check_textures();
    check_nodes();
    return scene_contents();
  }

private:
  [[noreturn]] void bad(const std::string& what) const { fail("'{}': {}", m_file.string(), what); }

  static const json* member(const json& object, const char* key)
  {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  /// The root's array `name`, each element an object (empty if absent).
  const json& list(const char* name) const
  {
    static const json empty = json::array();
    const json* found = member(m_root, name);
    if (found == nullptr)
      return empty;
    if (!found->is_array())
      bad(fmt::format("'{}' is not an array", name));
    if (static_cast<std::int64_t>(found->size()) > max_int)
      bad(fmt::format("'{}' has too many elements", name));
    for (std::size_t i = 0; i < found->size(); ++i)
      if (!(*found)[i].is_object())
        bad(fmt::format("{}[{}] is not an object", name, i));
    return *found;
  }

  std::int64_t count(const char* name) const
  {
    return static_cast<std::int64_t>(list(name).size());
  }

  /// `object[key]`: an integer in [lo, hi]; `fallback` if absent (absent without one: an error).
  std::int64_t integer(const json& object, const char* key, const std::string& where,
                       std::int64_t lo, std::int64_t hi,
                       std::optional<std::int64_t> fallback = std::nullopt) const
  {
    const json* value = member(object, key);
    if (value == nullptr) {
      if (!fallback)
        bad(fmt::format("{}.{} is missing", where, key));
      return *fallback;
    }
    if (!value->is_number_integer())
      bad(fmt::format("{}.{} is not an integer", where, key));
    const bool above =
        value->is_number_unsigned() && value->get<std::uint64_t>() > std::uint64_t(max_int);
    if (above || value->get<std::int64_t>() < lo || value->get<std::int64_t>() > hi)
      bad(fmt::format("{}.{} = {} is not within {}..{}", where, key, value->dump(), lo, hi));
    return value->get<std::int64_t>();
  }

  /// `object[key]`, if present, names an element of the root's array `target`.
  std::optional<std::int64_t> reference(const json& object, const char* key,
                                        const std::string& where, const char* target) const
  {
    if (member(object, key) == nullptr)
      return std::nullopt;
    const std::int64_t n = count(target);
    if (n == 0)
      bad(fmt::format("{}.{} refers to {}, but the file has none", where, key, target));
    return integer(object, key, where, 0, n - 1);
  }

  /// `object[key]`, which must be present, names an element of the root's array `target`.
  std::int64_t required_reference(const json& object, const char* key, const std::string& where,
                                  const char* target) const
  {
    const std::optional<std::int64_t> index = reference(object, key, where, target);
    if (!index)
      bad(fmt::format("{}.{} is missing", where, key));
    return *index;
  }

  /// `object[key]`, if present, is an array of `size` numbers (any size if `size` < 0).
  void numbers(const json& object, const char* key, const std::string& where, int size) const
  {
    const json* value = member(object, key);
    if (value == nullptr)
      return;
    if (!value->is_array() || (size >= 0 && value->size() != std::size_t(size)))
      bad(size >= 0 ? fmt::format("{}.{} is not an array of {} numbers", where, key, size)
                    : fmt::format("{}.{} is not an array of numbers", where, key));
    for (const json& v : *value)
      if (!v.is_number())
        bad(fmt::format("{}.{} holds something other than numbers", where, key));
  }

  std::string string(const json& object, const char* key, const std::string& where) const
  {
    const json* value = member(object, key);
    if (value == nullptr)
      return "";
    if (!value->is_string())
      bad(fmt::format("{}.{} is not a string", where, key));
    return value->get<std::string>();
  }

  void check_asset() const
  {
    const json* asset = member(m_root, "asset");
    if (asset == nullptr || !asset->is_object())
      bad("no 'asset' object (is this a glTF file?)");
    const std::string version = string(*asset, "version", "asset");
    if (version.rfind("2.", 0) != 0)
      bad(fmt::format("glTF version '{}', ligsim reads 2.x", version));
    if (const json* required = member(m_root, "extensionsRequired"); required && !required->empty())
      bad(fmt::format("requires the extensions {}, which ligsim cannot read", required->dump()));
  }

  /// A data: URI's payload must be base64 of at least `bytes` bytes.
  void check_data_uri(const std::string& uri, std::int64_t bytes, const std::string& where) const
  {
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.rfind(";base64", comma) != comma - 7)
      bad(fmt::format("{}.uri is a data: URI without ';base64,'", where));
    const std::string payload = uri.substr(comma + 1);
    std::size_t padding = 0;
    for (std::size_t i = 0; i < payload.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(payload[i]);
      const bool letter = std::isalnum(c) != 0 || c == '+' || c == '/';
      if (c == '=' && i + 2 >= payload.size())
        ++padding;
      else if (!letter || padding > 0)
        bad(fmt::format("{}.uri: base64 data has '{}' at character {}", where, payload[i], i));
    }
    if (payload.size() % 4 != 0)
      bad(fmt::format("{}.uri: base64 data of {} characters is not a multiple of 4", where,
                      payload.size()));
    const std::int64_t decoded = std::int64_t(payload.size() / 4 * 3) - std::int64_t(padding);
    if (decoded < bytes)
      bad(fmt::format("{}.uri holds {} bytes, byteLength says {}", where, decoded, bytes));
  }

  void check_buffers()
  {
    const json& buffers = list("buffers");
    for (std::size_t b = 0; b < buffers.size(); ++b) {
      const std::string where = fmt::format("buffers[{}]", b);
      const std::int64_t bytes = integer(buffers[b], "byteLength", where, 1, max_int);
      m_buffer_bytes.push_back(bytes);
      if (member(buffers[b], "uri") == nullptr) {
        if (b != 0 || !m_bin_bytes)
          bad(fmt::format("{} has no uri and is not the BIN chunk of a .glb file", where));
        if (*m_bin_bytes < bytes)
          bad(fmt::format("{}: the BIN chunk holds {} bytes, byteLength says {}", where,
                          *m_bin_bytes, bytes));
        continue;
      }
      const std::string uri = string(buffers[b], "uri", where);
      if (uri.rfind("data:", 0) == 0) {
        check_data_uri(uri, bytes, where);
        continue;
      }
      if (uri.empty() || uri.front() == '/' || uri.find("://") != std::string::npos)
        bad(fmt::format("{}.uri '{}' is neither a data: URI nor a file beside this one", where,
                        uri));
      const fs::path data = m_file.parent_path() / uri;
      std::error_code error;
      if (!fs::is_regular_file(data, error))
        bad(fmt::format("{}: missing buffer file '{}'", where, data.string()));
      const auto size = fs::file_size(data, error);
      if (error || std::int64_t(size) < bytes)
        bad(fmt::format("{}: '{}' holds {} bytes, byteLength says {}", where, data.string(),
                        error ? 0 : size, bytes));
    }
  }

  void check_buffer_views()
  {
    const json& views = list("bufferViews");
    for (std::size_t v = 0; v < views.size(); ++v) {
      const std::string where = fmt::format("bufferViews[{}]", v);
      const std::int64_t buffer = required_reference(views[v], "buffer", where, "buffers");
      const std::int64_t offset = integer(views[v], "byteOffset", where, 0, max_int, 0);
      const std::int64_t length = integer(views[v], "byteLength", where, 1, max_int);
      m_view_stride.push_back(integer(views[v], "byteStride", where, 4, 252, 0));
      if (offset + length > m_buffer_bytes[std::size_t(buffer)])
        bad(fmt::format("{} (bytes {}..{}) runs past the end of buffer {} ({} bytes)", where,
                        offset, offset + length, buffer, m_buffer_bytes[std::size_t(buffer)]));
      m_view_bytes.push_back(length);
    }
    if (member(m_root, "bufferViews") == nullptr && count("accessors") > 0)
      bad("has accessors but no bufferViews");
  }

  struct Accessor {
    std::string type;
    std::int64_t component_type = 0;
    std::int64_t count = 0;
  };

  static int components(const std::string& type)
  {
    static const std::pair<const char*, int> types[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3},
                                                        {"VEC4", 4},   {"MAT2", 4}, {"MAT3", 9},
                                                        {"MAT4", 16}};
    for (const auto& [name, n] : types)
      if (type == name)
        return n;
    return 0;
  }

  static int component_bytes(std::int64_t component_type)
  {
    switch (component_type) {
    case 5120: // byte
    case 5121: // unsigned byte
      return 1;
    case 5122: // short
    case 5123: // unsigned short
      return 2;
    case 5125: // unsigned int
    case 5126: // float
      return 4;
    default:
      return 0;
    }
  }

  void check_accessors()
  {
    const json& accessors = list("accessors");
    for (std::size_t a = 0; a < accessors.size(); ++a) {
      const std::string where = fmt::format("accessors[{}]", a);
      const json& accessor = accessors[a];
      if (member(accessor, "sparse") != nullptr)
        bad(fmt::format("{} is sparse: ligsim does not read sparse accessors", where));
      if (member(accessor, "bufferView") == nullptr)
        bad(fmt::format("{} has no bufferView (all zeros): not a mesh ligsim can read", where));
      const std::int64_t view = required_reference(accessor, "bufferView", where, "bufferViews");
      Accessor read;
      read.component_type = integer(accessor, "componentType", where, 0, max_int);
      const int bytes = component_bytes(read.component_type);
      if (bytes == 0)
        bad(fmt::format("{}.componentType {} is not one of glTF's (5120..5126)", where,
                        read.component_type));
      read.type = string(accessor, "type", where);
      const int n = components(read.type);
      if (n == 0)
        bad(fmt::format("{}.type '{}' is not SCALAR, VEC2..4 or MAT2..4", where, read.type));
      read.count = integer(accessor, "count", where, 1, max_int);
      const std::int64_t offset = integer(accessor, "byteOffset", where, 0, max_int, 0);
      const std::int64_t element = std::int64_t(n) * bytes;
      const std::int64_t stride =
          m_view_stride[std::size_t(view)] > 0 ? m_view_stride[std::size_t(view)] : element;
      const std::int64_t end = offset + stride * (read.count - 1) + element;
      if (end > m_view_bytes[std::size_t(view)])
        bad(fmt::format("{}: {} elements of {} bytes from byte {} need {} bytes, bufferView {} "
                        "has {}",
                        where, read.count, element, offset, end, view,
                        m_view_bytes[std::size_t(view)]));
      numbers(accessor, "min", where, n);
      numbers(accessor, "max", where, n);
      m_accessors.push_back(read);
    }
  }

  /// The types the specification allows for a known attribute (an unknown one: any).
  void check_attribute(const std::string& name, const Accessor& accessor,
                       const std::string& where) const
  {
    const auto starts = [&](const char* prefix) { return name.rfind(prefix, 0) == 0; };
    std::vector<std::string> types;
    std::vector<std::int64_t> components;
    if (name == "POSITION" || name == "NORMAL") {
      types = {"VEC3"}, components = {5126};
    } else if (name == "TANGENT") {
      types = {"VEC4"}, components = {5126};
    } else if (starts("TEXCOORD_")) {
      types = {"VEC2"}, components = {5126, 5121, 5123};
    } else if (starts("COLOR_")) {
      types = {"VEC3", "VEC4"}, components = {5126, 5121, 5123};
    } else if (starts("JOINTS_")) {
      types = {"VEC4"}, components = {5121, 5123};
    } else if (starts("WEIGHTS_")) {
      types = {"VEC4"}, components = {5126, 5121, 5123};
    } else {
      return;
    }
    const bool type_ok = std::find(types.begin(), types.end(), accessor.type) != types.end();
    const bool component_ok = std::find(components.begin(), components.end(),
                                        accessor.component_type) != components.end();
    if (!type_ok || !component_ok)
      bad(fmt::format("{}: attribute {} is {} of component type {}, which glTF does not allow",
                      where, name, accessor.type, accessor.component_type));
  }

  void check_primitive(const json& primitive, const std::string& where) const
  {
    if (member(primitive, "targets") != nullptr)
      bad(fmt::format("{} has morph targets: ligsim reads static meshes only", where));
    const json* attributes = member(primitive, "attributes");
    if (attributes == nullptr || !attributes->is_object() || !attributes->contains("POSITION"))
      bad(fmt::format("{} has no attributes.POSITION", where));
    const Accessor& position =
        m_accessors[std::size_t(required_reference(*attributes, "POSITION", where, "accessors"))];
    for (const auto& [name, value] : attributes->items()) {
      const Accessor& accessor = m_accessors[std::size_t(
          required_reference(*attributes, name.c_str(), where + ".attributes", "accessors"))];
      check_attribute(name, accessor, where);
      if (accessor.count != position.count)
        bad(fmt::format("{}: attribute {} has {} elements, POSITION {}", where, name,
                        accessor.count, position.count));
    }
    std::int64_t corners = position.count;
    if (const auto indices = reference(primitive, "indices", where, "accessors")) {
      const Accessor& accessor = m_accessors[std::size_t(*indices)];
      if (accessor.type != "SCALAR" ||
          (accessor.component_type != 5121 && accessor.component_type != 5123 &&
           accessor.component_type != 5125))
        bad(fmt::format("{}: indices must be unsigned SCALAR integers, accessor {} is {} of "
                        "component type {}",
                        where, *indices, accessor.type, accessor.component_type));
      corners = accessor.count;
    }
    const std::int64_t mode = integer(primitive, "mode", where, 0, 6, 4);
    // points, lines, line loop, line strip, triangles, triangle strip, triangle fan
    const std::int64_t least[] = {1, 2, 2, 2, 3, 3, 3};
    const bool fits = corners >= least[mode] && (mode != 1 || corners % 2 == 0) &&
                      (mode != 4 || corners % 3 == 0);
    if (!fits)
      bad(fmt::format("{}: {} corners do not make whole {} (mode {})", where, corners,
                      mode == 4   ? "triangles"
                      : mode == 1 ? "lines"
                                  : "primitives",
                      mode));
    reference(primitive, "material", where, "materials");
  }

  void check_meshes() const
  {
    const json& meshes = list("meshes");
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const std::string where = fmt::format("meshes[{}]", m);
      string(meshes[m], "name", where);
      numbers(meshes[m], "weights", where, -1);
      const json* primitives = member(meshes[m], "primitives");
      if (primitives == nullptr || !primitives->is_array() || primitives->empty())
        bad(fmt::format("{} has no primitives", where));
      for (std::size_t p = 0; p < primitives->size(); ++p) {
        if (!(*primitives)[p].is_object())
          bad(fmt::format("{}.primitives[{}] is not an object", where, p));
        check_primitive((*primitives)[p], fmt::format("{}.primitives[{}]", where, p));
      }
    }
  }

  /// A textureInfo (`{"index": texture}`) at `key` of `object`, if present.
  void check_texture_info(const json& object, const char* key, const std::string& where) const
  {
    const json* info = member(object, key);
    if (info == nullptr)
      return;
    if (!info->is_object())
      bad(fmt::format("{}.{} is not an object", where, key));
    const std::string at = fmt::format("{}.{}", where, key);
    if (!reference(*info, "index", at, "textures"))
      bad(fmt::format("{}.index is missing", at));
    integer(*info, "texCoord", at, 0, 255, 0);
  }

  void check_materials() const
  {
    const json& materials = list("materials");
    for (std::size_t m = 0; m < materials.size(); ++m) {
      const std::string where = fmt::format("materials[{}]", m);
      for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
        check_texture_info(materials[m], key, where);
      numbers(materials[m], "emissiveFactor", where, 3);
      if (const json* pbr = member(materials[m], "pbrMetallicRoughness")) {
        if (!pbr->is_object())
          bad(fmt::format("{}.pbrMetallicRoughness is not an object", where));
        const std::string at = where + ".pbrMetallicRoughness";
        for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
          check_texture_info(*pbr, key, at);
        numbers(*pbr, "baseColorFactor", at, 4);
      }
    }
  }

  void check_textures() const
  {
    const json& textures = list("textures");
    for (std::size_t t = 0; t < textures.size(); ++t) {
      const std::string where = fmt::format("textures[{}]", t);
      reference(textures[t], "source", where, "images");
      reference(textures[t], "sampler", where, "samplers");
    }
    const json& images = list("images");
    for (std::size_t i = 0; i < images.size(); ++i) {
      const std::string where = fmt::format("images[{}]", i);
      const bool view = reference(images[i], "bufferView", where, "bufferViews").has_value();
      const std::string uri = string(images[i], "uri", where);
      if (view == !uri.empty())
        bad(fmt::format("{} needs either a uri or a bufferView", where));
      if (uri.rfind("data:", 0) == 0)
        check_data_uri(uri, 0, where);
    }
  }

  void check_nodes()
  {
    const json& nodes = list("nodes");
    m_parent.assign(nodes.size(), -1);
    std::int64_t lights = 0;
    if (const json* extensions = member(m_root, "extensions");
        extensions && extensions->is_object())
      if (const json* punctual = member(*extensions, "KHR_lights_punctual");
          punctual && punctual->is_object())
        if (const json* list = member(*punctual, "lights"); list && list->is_array())
          lights = static_cast<std::int64_t>(list->size());
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      const json& node = nodes[n];
      const std::string where = fmt::format("nodes[{}]", n);
      if (member(node, "skin") != nullptr)
        bad(fmt::format("{} has a skin: ligsim reads static meshes only", where));
      string(node, "name", where);
      reference(node, "mesh", where, "meshes");
      reference(node, "camera", where, "cameras");
      numbers(node, "matrix", where, 16);
      numbers(node, "translation", where, 3);
      numbers(node, "rotation", where, 4);
      numbers(node, "scale", where, 3);
      numbers(node, "weights", where, -1);
      if (const json* extensions = member(node, "extensions");
          extensions && extensions->is_object())
        if (const json* light = member(*extensions, "KHR_lights_punctual");
            light && light->is_object())
          integer(*light, "light", where + ".extensions.KHR_lights_punctual", 0, lights - 1);
      const json* children = member(node, "children");
      if (children == nullptr)
        continue;
      if (!children->is_array())
        bad(fmt::format("{}.children is not an array", where));
      for (const json& child : *children) {
        if (!child.is_number_integer() || child.get<std::int64_t>() < 0 ||
            child.get<std::int64_t>() >= std::int64_t(nodes.size()))
          bad(fmt::format("{}.children holds {}, not a node index", where, child.dump()));
        const std::size_t c = child.get<std::size_t>();
        if (m_parent[c] >= 0)
          bad(fmt::format("node {} is a child of nodes {} and {}: nodes must form trees", c,
                          m_parent[c], n));
        if (c == n)
          bad(fmt::format("{} is its own child", where));
        m_parent[c] = static_cast<int>(n);
      }
    }
    // With one parent each, a node that never reaches a root lies on a cycle.
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      int depth = 0;
      for (int up = m_parent[n]; up >= 0; up = m_parent[std::size_t(up)])
        if (++depth > max_node_depth)
          bad(fmt::format("node {} lies on a cycle of nodes or deeper than {} levels", n,
                          max_node_depth));
    }
  }

  GltfContents scene_contents() const
  {
    const json& scenes = list("scenes");
    if (scenes.empty())
      bad("has no scene: nothing to read");
    GltfContents contents;
    contents.scene =
        static_cast<int>(integer(m_root, "scene", "root", 0, std::int64_t(scenes.size()) - 1, 0));
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const std::string where = fmt::format("scenes[{}]", s);
      const json* roots = member(scenes[s], "nodes");
      if (roots == nullptr)
        continue;
      if (!roots->is_array())
        bad(fmt::format("{}.nodes is not an array", where));
      std::set<std::int64_t> seen;
      for (const json& root : *roots) {
        if (!root.is_number_integer() || root.get<std::int64_t>() < 0 ||
            root.get<std::int64_t>() >= count("nodes"))
          bad(fmt::format("{}.nodes holds {}, not a node index", where, root.dump()));
        const std::int64_t r = root.get<std::int64_t>();
        if (m_parent[std::size_t(r)] >= 0 || !seen.insert(r).second)
          bad(fmt::format("{}.nodes lists node {}, which is not a root or listed twice", where, r));
      }
    }
    const json& nodes = list("nodes");
    const json& meshes = list("meshes");
    std::vector<std::int64_t> open;
    if (const json* roots = member(scenes[std::size_t(contents.scene)], "nodes"))
      for (auto it = roots->rbegin(); it != roots->rend(); ++it)
        open.push_back(it->get<std::int64_t>());
    while (!open.empty()) {
      const std::int64_t n = open.back();
      open.pop_back();
      const json& node = nodes[std::size_t(n)];
      if (const json* mesh = member(node, "mesh")) {
        const json& m = meshes[mesh->get<std::size_t>()];
        contents.mesh_nodes.push_back({static_cast<int>(n), mesh->get<int>(),
                                       node.value("name", std::string()),
                                       m.value("name", std::string())});
      }
      if (const json* children = member(node, "children"))
        for (auto it = children->rbegin(); it != children->rend(); ++it)
          open.push_back(it->get<std::int64_t>());
    }
    return contents;
  }

  fs::path m_file;
  const json& m_root;
  std::optional<std::int64_t> m_bin_bytes;
  std::vector<std::int64_t> m_buffer_bytes;
  std::vector<std::int64_t> m_view_bytes;
  std::vector<std::int64_t> m_view_stride; ///< 0: tightly packed
  std::vector<Accessor> m_accessors;
  std::vector<int> m_parent; ///< per node, -1 for a root
};

} // namespace

GltfContents check_gltf(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
    fail("cannot open '{}'", file.string());
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (static_cast<std::int64_t>(bytes.size()) > max_int)
    fail("'{}': {} bytes, more than VTK's glTF reader takes", file.string(), bytes.size());
  std::string extension = file.extension().string();
  Container container =
      extension == ".glb" ? read_glb(file, bytes) : Container{bytes, std::nullopt};
  const json root = parse_json(file, container.json_text);
  return Checker(file, root, container.bin_bytes).run();
}

} // namespace ligsim::io
