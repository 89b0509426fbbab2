#include "stages/model/model.hpp"

#include "common/error.hpp"
#include "common/tet_faces.hpp"
#include "stages/attachments/footprint_rim.hpp"
#include "stages/geometry/surface_query.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

namespace ligsim::model {

std::vector<bool> boundary_nodes(const TetMesh& mesh)
{
  std::vector<bool> on_boundary(static_cast<std::size_t>(mesh.V.rows()), false);
  for (const auto& face : tet_boundary_faces(mesh.T))
    for (int v : face)
      on_boundary[static_cast<std::size_t>(v)] = true;
  return on_boundary;
}

int free_unsupported_nodes(const std::vector<std::array<int, 3>>& faces, std::vector<bool>& bound)
{
  int freed = 0;
  for (;;) {
    std::vector<bool> supported(bound.size(), false);
    for (const auto& face : faces)
      if (bound[static_cast<std::size_t>(face[0])] && bound[static_cast<std::size_t>(face[1])] &&
          bound[static_cast<std::size_t>(face[2])])
        for (int v : face)
          supported[static_cast<std::size_t>(v)] = true;
    int round = 0;
    for (std::size_t v = 0; v < bound.size(); ++v)
      if (bound[v] && !supported[v]) {
        bound[v] = false;
        ++round;
      }
    if (round == 0)
      return freed;
    freed += round;
  }
}

namespace {

Eigen::Vector3d face_centroid(const TetMesh& mesh, const std::array<int, 3>& face)
{
  return (mesh.V.row(face[0]) + mesh.V.row(face[1]) + mesh.V.row(face[2])).transpose() / 3.0;
}

double face_area(const TetMesh& mesh, const std::array<int, 3>& face)
{
  const Eigen::RowVector3d a = mesh.V.row(face[0]);
  return 0.5 * (mesh.V.row(face[1]) - a).cross(mesh.V.row(face[2]) - a).norm();
}

} // namespace

Model assemble(const TetMesh& mesh, const Eigen::MatrixX3d& directions,
               const TriangleSurface& ligament, const std::vector<int>& femur_area,
               const std::vector<int>& tibia_area, const Parameters& parameters, FootprintRule rule)
{
  if (directions.rows() != mesh.T.rows())
    fail("model: {} fiber directions for {} tets", directions.rows(), mesh.T.rows());
  for (Eigen::Index t = 0; t < directions.rows(); ++t)
    if (!directions.row(t).allFinite() || std::abs(directions.row(t).norm() - 1.0) > 1e-6)
      fail("model: the fiber direction of tet {} is not a unit vector", t);
  if (!(parameters.in_situ_strain > -1.0) || !std::isfinite(parameters.in_situ_strain))
    fail("model: in-situ strain must exceed -1, got {}", parameters.in_situ_strain);

  Model model;
  model.mesh = mesh;
  model.fibers = (1.0 + parameters.in_situ_strain) * directions;
  const std::vector<std::array<int, 3>> faces = tet_boundary_faces(mesh.T);
  const std::vector<bool> boundary = boundary_nodes(mesh);
  const std::size_t n = boundary.size();
  model.femur_nodes.assign(n, false);
  model.tibia_nodes.assign(n, false);

  std::vector<bool> in_femur(static_cast<std::size_t>(ligament.V.rows()), false);
  std::vector<bool> in_tibia(in_femur.size(), false);
  for (int v : femur_area)
    in_femur.at(static_cast<std::size_t>(v)) = true;
  for (int v : tibia_area)
    in_tibia.at(static_cast<std::size_t>(v)) = true;
  model.boundary_nodes = static_cast<int>(std::count(boundary.begin(), boundary.end(), true));
  const SurfaceQuery query(ligament);
  const auto sides = {std::tuple{&in_femur, &model.femur_nodes, &model.femur_area_mm2},
                      std::tuple{&in_tibia, &model.tibia_nodes, &model.tibia_area_mm2}};
  if (rule == FootprintRule::faces_inside_rim) {
    for (const auto& face : faces) {
      const SurfaceQuery::Closest nearest = query.closest(face_centroid(mesh, face));
      for (auto [in_area, nodes, area_mm2] : sides) {
        if (attachments::footprint_share(ligament, *in_area, nearest.face, nearest.point) <= 0.5)
          continue;
        for (int v : face)
          (*nodes)[static_cast<std::size_t>(v)] = true;
        *area_mm2 += face_area(mesh, face);
      }
    }
  } else {
    for (std::size_t v = 0; v < n; ++v) {
      if (!boundary[v])
        continue;
      const int face = query.closest(mesh.V.row(static_cast<Eigen::Index>(v)).transpose()).face;
      for (auto [in_area, nodes, area_mm2] : sides) {
        int corners = 0;
        for (int k = 0; k < 3; ++k)
          corners += (*in_area)[static_cast<std::size_t>(ligament.F(face, k))];
        (*nodes)[v] = corners >= 2;
      }
    }
    model.femur_nodes_unbound = free_unsupported_nodes(faces, model.femur_nodes);
    model.tibia_nodes_unbound = free_unsupported_nodes(faces, model.tibia_nodes);
    for (const auto& face : faces)
      for (auto [in_area, nodes, area_mm2] : sides)
        if ((*nodes)[static_cast<std::size_t>(face[0])] &&
            (*nodes)[static_cast<std::size_t>(face[1])] &&
            (*nodes)[static_cast<std::size_t>(face[2])])
          *area_mm2 += face_area(mesh, face);
  }
  const auto femur_count = std::count(model.femur_nodes.begin(), model.femur_nodes.end(), true);
  const auto tibia_count = std::count(model.tibia_nodes.begin(), model.tibia_nodes.end(), true);
  if (femur_count == 0 || tibia_count == 0)
    fail("model: no mesh node lies on the {} attachment area ({} vertices): the tet mesh is too "
         "coarse for it; use a smaller tetmesh facet size",
         femur_count == 0 ? "femoral" : "tibial",
         femur_count == 0 ? femur_area.size() : tibia_area.size());
  return model;
}

namespace {

/// The nodes sharing a tet with each node (itself excluded), sorted.
std::vector<std::vector<int>> tet_neighbours(const TetMesh& mesh)
{
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b)
          neighbours[static_cast<std::size_t>(mesh.T(t, a))].push_back(mesh.T(t, b));
  for (std::vector<int>& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

int close_in_bone(const TetMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                  const SurfaceQuery& bone, std::vector<bool>& bound,
                  const std::vector<bool>& bound_elsewhere)
{
  std::vector<char> inside(bound.size(), -1); // -1 not yet asked
  int added = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t v = 0; v < bound.size(); ++v) {
      if (bound[v] || bound_elsewhere[v])
        continue;
      int to_bone = 0, free = 0;
      for (int w : neighbours[v])
        ++(bound[static_cast<std::size_t>(w)] ? to_bone : free);
      if (to_bone <= free)
        continue;
      if (inside[v] < 0)
        inside[v] = bone.inside(mesh.V.row(static_cast<Eigen::Index>(v)).transpose()) ? 1 : 0;
      if (inside[v] == 1) {
        bound[v] = true;
        ++added;
        changed = true;
      }
    }
  }
  return added;
}

/// Interior nodes inside the bone that share a tet with its footprint: the first ring as it is,
/// then ring after ring deeper into the insertion, but only through nodes with no free node of
/// the ligament's surface beside them (so it never follows a ligament along the bone). Contact
/// holds the surface out of the bones, not the interior, so these would stay inside.
int close_interior_rings(const TetMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                         const std::vector<bool>& boundary, const SurfaceQuery& bone,
                         std::vector<bool>& bound, const std::vector<bool>& bound_elsewhere)
{
  int added = 0;
  for (bool first = true;; first = false) {
    std::vector<int> ring;
    for (std::size_t v = 0; v < bound.size(); ++v) {
      if (bound[v] || bound_elsewhere[v] || boundary[v])
        continue;
      bool touches = false, beside_free_surface = false;
      for (int w : neighbours[v]) {
        const auto u = static_cast<std::size_t>(w);
        touches = touches || bound[u];
        beside_free_surface = beside_free_surface || (boundary[u] && !bound[u]);
      }
      if (touches && (first || !beside_free_surface) &&
          bone.inside(mesh.V.row(static_cast<Eigen::Index>(v)).transpose()))
        ring.push_back(static_cast<int>(v));
    }
    if (ring.empty())
      return added;
    for (int v : ring)
      bound[static_cast<std::size_t>(v)] = true;
    added += static_cast<int>(ring.size());
  }
}

/// Both rules for one bone.
int close_footprint(const TetMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                    const std::vector<bool>& boundary, const TriangleSurface& surface,
                    std::vector<bool>& bound, const std::vector<bool>& bound_elsewhere)
{
  const SurfaceQuery bone(surface);
  const int surrounded = close_in_bone(mesh, neighbours, bone, bound, bound_elsewhere);
  return surrounded +
         close_interior_rings(mesh, neighbours, boundary, bone, bound, bound_elsewhere);
}

} // namespace

FootprintClosing close_footprints_in_bones(Model& model, const TriangleSurface* femur,
                                           const TriangleSurface* tibia)
{
  const std::vector<std::vector<int>> neighbours = tet_neighbours(model.mesh);
  const std::vector<bool> boundary = boundary_nodes(model.mesh);
  FootprintClosing closing;
  if (femur != nullptr)
    closing.femur_nodes = close_footprint(model.mesh, neighbours, boundary, *femur,
                                          model.femur_nodes, model.tibia_nodes);
  if (tibia != nullptr)
    closing.tibia_nodes = close_footprint(model.mesh, neighbours, boundary, *tibia,
                                          model.tibia_nodes, model.femur_nodes);
  return closing;
}

Axis default_flexion_axis(const TriangleSurface& ligament,
                          const Eigen::Vector3d& femoral_attachment)
{
  const Eigen::RowVector3d mean = ligament.V.colwise().mean();
  const Eigen::MatrixX3d centred = ligament.V.rowwise() - mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(centred.transpose() * centred);
  Eigen::Vector3d direction = solver.eigenvectors().col(0); // smallest eigenvalue
  if (direction.x() < 0.0)
    direction = -direction;
  return {femoral_attachment, direction.normalized()};
}

} // namespace ligsim::model
