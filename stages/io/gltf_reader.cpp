#include "stages/io/gltf_reader.hpp"

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "stages/io/gltf_check.hpp"

#include <vtkAppendPolyData.h>
#include <vtkCompositeDataSet.h>
#include <vtkGLTFReader.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>

namespace ligsim::io {

namespace fs = std::filesystem;

namespace {

/// glTF's unit of length is the metre (glTF 2.0 specification, section 3.4); ligsim's the mm.
constexpr double mm_per_gltf_unit = 1000.0;

std::string describe(const GltfMeshNode& node)
{
  if (!node.node_name.empty())
    return node.node_name;
  if (!node.mesh_name.empty())
    return fmt::format("{} (a mesh of node {}, which has no name)", node.mesh_name, node.node);
  return fmt::format("(node {}, mesh {}: no names)", node.node, node.mesh);
}

std::string name_list(const std::vector<GltfMeshNode>& nodes)
{
  std::string text;
  for (const GltfMeshNode& node : nodes)
    text += (text.empty() ? "" : ", ") + describe(node);
  return text;
}

const GltfMeshNode& select(const fs::path& file, const std::vector<GltfMeshNode>& nodes,
                           const std::string& name)
{
  if (nodes.empty())
    fail("'{}' holds no mesh", file.string());
  if (name.empty()) {
    if (nodes.size() > 1)
      fail("'{}' holds {} meshes; name one as '{}#NAME': {}", file.string(), nodes.size(),
           file.string(), name_list(nodes));
    return nodes.front();
  }
  for (auto field : {&GltfMeshNode::node_name, &GltfMeshNode::mesh_name}) {
    const auto count = std::count_if(nodes.begin(), nodes.end(),
                                     [&](const GltfMeshNode& n) { return n.*field == name; });
    if (count > 1)
      fail("'{}': {} nodes are named '{}' (ligsim needs one)", file.string(), count, name);
    if (count == 1)
      return *std::find_if(nodes.begin(), nodes.end(),
                           [&](const GltfMeshNode& n) { return n.*field == name; });
  }
  fail("'{}' has no mesh named '{}'; its meshes: {}", file.string(), name, name_list(nodes));
}

std::string block_name(vtkMultiBlockDataSet* parent, unsigned block)
{
  const char* name = parent->HasMetaData(block)
                         ? parent->GetMetaData(block)->Get(vtkCompositeDataSet::NAME())
                         : nullptr;
  return name ? name : "";
}

/// The block named `name` anywhere below `parent`.
vtkDataObject* find_block(vtkMultiBlockDataSet* parent, const std::string& name)
{
  for (unsigned b = 0; b < parent->GetNumberOfBlocks(); ++b) {
    if (block_name(parent, b) == name)
      return parent->GetBlock(b);
    if (auto* child = vtkMultiBlockDataSet::SafeDownCast(parent->GetBlock(b)))
      if (vtkDataObject* found = find_block(child, name))
        return found;
  }
  return nullptr;
}

} // namespace

vtkSmartPointer<vtkPolyData> read_gltf(const fs::path& file, const std::string& name)
{
  const std::string extension = file.extension().string();
  if (extension != ".glb" && extension != ".gltf")
    fail("'{}': VTK's glTF reader needs the extension in lower case (.glb or .gltf)",
         file.string());
  const GltfContents contents = check_gltf(file);
  const GltfMeshNode& chosen = select(file, contents.mesh_nodes, name);

  auto reader = vtkSmartPointer<vtkGLTFReader>::New();
  const VtkErrorTrap trap(reader);
  reader->SetFileName(file.c_str());
  reader->SetCurrentScene(contents.scene);
  try {
    reader->Update();
  } catch (const std::exception& e) {
    // VTK's loader lets the standard library's errors through (std::length_error from a size
    // it computed); what check_gltf found nothing wrong with should not get here.
    fail("cannot read '{}': VTK's glTF reader failed: {}", file.string(), e.what());
  }
  if (trap.caught())
    fail("cannot read '{}': {}", file.string(), trap.message());

  // VTK 9.1 names the blocks by index: a node's block "Node_<n>" holds its mesh's block
  // "Mesh_<m>", whose children are the primitives, then the blocks of the node's children.
  auto* node = vtkMultiBlockDataSet::SafeDownCast(
      find_block(reader->GetOutput(), fmt::format("Node_{}", chosen.node)));
  vtkMultiBlockDataSet* mesh = nullptr;
  for (unsigned b = 0; node != nullptr && b < node->GetNumberOfBlocks(); ++b)
    if (block_name(node, b) == fmt::format("Mesh_{}", chosen.mesh))
      mesh = vtkMultiBlockDataSet::SafeDownCast(node->GetBlock(b));
  if (mesh == nullptr)
    fail("'{}': VTK's glTF reader returned no mesh for node {} ('{}')", file.string(), chosen.node,
         describe(chosen));
  auto append = vtkSmartPointer<vtkAppendPolyData>::New();
  for (unsigned p = 0; p < mesh->GetNumberOfBlocks(); ++p)
    if (auto* primitive = vtkPolyData::SafeDownCast(mesh->GetBlock(p)))
      append->AddInputData(primitive);
  if (append->GetNumberOfInputConnections(0) == 0)
    fail("'{}': mesh '{}' holds no primitives", file.string(), describe(chosen));
  append->Update();

  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->ShallowCopy(append->GetOutput());
  vtkPoints* in = result->GetPoints();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(in ? in->GetNumberOfPoints() : 0);
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
    double p[3];
    in->GetPoint(i, p);
    points->SetPoint(i, mm_per_gltf_unit * p[0], mm_per_gltf_unit * p[1], mm_per_gltf_unit * p[2]);
  }
  result->SetPoints(points);
  return result;
}

} // namespace ligsim::io
