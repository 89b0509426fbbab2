#pragma once
/// @brief Small glTF files for the tests: a tetrahedron as a glTF document and its binary
/// buffer, written as .glb or as .gltf (buffer in a data: URI or a .bin file beside it).

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace ligsim::test {

/// A glTF document and its one buffer's bytes.
struct GltfAsset {
  nlohmann::json document;
  std::string buffer;
};

inline void append_u32(std::string& bytes, std::uint32_t value)
{
  for (int b = 0; b < 4; ++b)
    bytes.push_back(static_cast<char>((value >> (8 * b)) & 0xff));
}

/// The unit tetrahedron (metres), outward triangles, as the mesh "tet" of node `node_name`.
inline GltfAsset tetrahedron(const std::string& node_name = "tet")
{
  const float points[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::uint16_t triangles[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  GltfAsset asset;
  asset.buffer.resize(sizeof(points) + sizeof(triangles));
  std::memcpy(asset.buffer.data(), points, sizeof(points));
  std::memcpy(asset.buffer.data() + sizeof(points), triangles, sizeof(triangles));
  asset.document = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"name", node_name}, {"mesh", 0}}}},
      {"meshes",
       {{{"name", "tet"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 12}, {"type", "SCALAR"}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", sizeof(points)}},
        {{"buffer", 0}, {"byteOffset", sizeof(points)}, {"byteLength", sizeof(triangles)}}}},
      {"buffers", {{{"byteLength", asset.buffer.size()}}}}};
  return asset;
}

/// The bytes of a binary glTF file (header, JSON chunk, BIN chunk), padded as glTF asks.
inline std::string glb_bytes(const GltfAsset& asset)
{
  std::string json = asset.document.dump();
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string bin = asset.buffer;
  bin.append((4 - bin.size() % 4) % 4, '\0');
  std::string bytes = "glTF";
  append_u32(bytes, 2);
  append_u32(bytes, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  append_u32(bytes, static_cast<std::uint32_t>(json.size()));
  append_u32(bytes, 0x4E4F534A);
  bytes += json;
  append_u32(bytes, static_cast<std::uint32_t>(bin.size()));
  append_u32(bytes, 0x004E4942);
  bytes += bin;
  return bytes;
}

inline std::filesystem::path write_bytes(const std::filesystem::path& file,
                                         const std::string& bytes)
{
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  return file;
}

inline std::filesystem::path write_glb(const std::filesystem::path& file, const GltfAsset& asset)
{
  return write_bytes(file, glb_bytes(asset));
}

/// A .gltf file whose buffer is base64 in a data: URI.
inline std::filesystem::path write_gltf_data_uri(const std::filesystem::path& file, GltfAsset asset)
{
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  const std::string& b = asset.buffer;
  for (std::size_t i = 0; i < b.size(); i += 3) {
    std::uint32_t chunk = std::uint32_t(static_cast<unsigned char>(b[i])) << 16;
    if (i + 1 < b.size())
      chunk |= std::uint32_t(static_cast<unsigned char>(b[i + 1])) << 8;
    if (i + 2 < b.size())
      chunk |= std::uint32_t(static_cast<unsigned char>(b[i + 2]));
    for (int k = 0; k < 4; ++k)
      text.push_back(i + std::size_t(k) <= b.size() ? alphabet[(chunk >> (18 - 6 * k)) & 63] : '=');
  }
  asset.document["buffers"][0]["uri"] = "data:application/octet-stream;base64," + text;
  return write_bytes(file, asset.document.dump());
}

/// A .gltf file with its buffer in `bin_name` beside it.
inline std::filesystem::path write_gltf_bin(const std::filesystem::path& file, GltfAsset asset,
                                            const std::string& bin_name)
{
  write_bytes(file.parent_path() / bin_name, asset.buffer);
  asset.document["buffers"][0]["uri"] = bin_name;
  return write_bytes(file, asset.document.dump());
}

} // namespace ligsim::test
