#include "sim/febio/feb_writer.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "sim/contact/contact_surface.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <utility>

namespace ligsim::sim {

namespace {

using Buffer = fmt::memory_buffer;

/// A load controller's curve (ids from 2 on): its value at time 0 and at the end of each step,
/// linear in between.
struct LoadCurve {
  double at_zero = 0.0;
  std::vector<double> at_steps;
};

/// The settle steps and the labelled ones.
std::size_t total_steps(const FebProblem& problem)
{
  return static_cast<std::size_t>(problem.settle_steps) + problem.step_labels.size();
}

/// Shortest text that reads back to the same double.
std::string number(double value)
{
  return fmt::format("{}", value);
}

std::string vector3(const Eigen::Vector3d& v)
{
  return fmt::format("{},{},{}", number(v.x()), number(v.y()), number(v.z()));
}

/// Text for an XML comment: "--" may not appear in one.
std::string comment_text(std::string text)
{
  for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--"))
    text.replace(at, 2, "- -");
  return text;
}

void validate(const FebProblem& problem)
{
  const Eigen::Index nodes = problem.ligament.V.rows();
  const Eigen::Index tets = problem.ligament.T.rows();
  if (tets == 0 || nodes == 0)
    fail("FEBio export: the ligament has no tets");
  if (problem.step_labels.empty())
    fail("FEBio export: no steps (no flexion angles)");
  if (problem.settle_steps < 0)
    fail("FEBio export: {} settle steps", problem.settle_steps);
  if (!problem.material.fiber)
    fail("FEBio export: the material has no fibers (FEBio's trans iso Mooney-Rivlin needs them)");
  if (problem.ligament_tet10.rows() > 0) {
    if (problem.ligament_tet10.rows() != tets ||
        problem.ligament_tet10.leftCols<4>() != problem.ligament.T)
      fail("FEBio export: the 10-node tets are not the ligament's tets with mid-edge nodes");
    if (problem.ligament_tet10.minCoeff() < 0 || problem.ligament_tet10.maxCoeff() >= nodes)
      fail("FEBio export: a 10-node tet names a node out of the ligament's {}", nodes);
  }
  if (problem.fiber_directions.rows() != tets)
    fail("FEBio export: {} fiber directions for {} tets", problem.fiber_directions.rows(), tets);
  for (Eigen::Index e = 0; e < tets; ++e)
    if (!(std::abs(problem.fiber_directions.row(e).norm() - 1.0) < 1e-6))
      fail("FEBio export: the fiber direction of tet {} is not a unit vector", e);
  if (!(problem.in_situ_strain > -1.0))
    fail("FEBio export: in-situ strain {} is not above -1", problem.in_situ_strain);
  std::vector<int> owner(static_cast<std::size_t>(nodes), -1);
  for (std::size_t b = 0; b < problem.bones.size(); ++b) {
    const FebRigidBody& bone = problem.bones[b];
    if (bone.surface.F.rows() == 0)
      fail("FEBio export: the {} has no surface triangles", bone.name);
    if (!(bone.contact_start_offset_mm >= 0.0) || !std::isfinite(bone.contact_start_offset_mm))
      fail("FEBio export: the {}'s contact start offset is {} mm (must be >= 0)", bone.name,
           bone.contact_start_offset_mm);
    if (!bone.poses.empty() && bone.poses.size() != problem.step_labels.size())
      fail("FEBio export: the {} has {} poses for {} steps", bone.name, bone.poses.size(),
           problem.step_labels.size());
    for (int node : bone.attached_nodes) {
      if (node < 0 || node >= nodes)
        fail("FEBio export: the {} attachment names node {}, but the ligament has {} nodes",
             bone.name, node, nodes);
      int& first = owner[static_cast<std::size_t>(node)];
      if (first >= 0 && first != static_cast<int>(b))
        fail("FEBio export: node {} is bound to the {} and the {}", node,
             problem.bones[static_cast<std::size_t>(first)].name, bone.name);
      first = static_cast<int>(b);
    }
  }
}

void write_control(Buffer& out, const FebProblem& problem)
{
  const FebSolverSettings& s = problem.solver;
  fmt::format_to(std::back_inserter(out),
                 "  <Control>\n"
                 "    <analysis>STATIC</analysis>\n"
                 "    <time_steps>{}</time_steps>\n"
                 "    <step_size>1</step_size>\n"
                 "    <plot_level>PLOT_MUST_POINTS</plot_level>\n"
                 "    <output_level>OUTPUT_MUST_POINTS</output_level>\n"
                 "    <time_stepper type=\"default\">\n"
                 "      <max_retries>{}</max_retries>\n"
                 "      <opt_iter>10</opt_iter>\n"
                 "      <dtmin>{}</dtmin>\n"
                 "      <dtmax lc=\"1\">1</dtmax>\n"
                 "    </time_stepper>\n"
                 "    <solver type=\"solid\">\n"
                 "      <symmetric_stiffness>symmetric</symmetric_stiffness>\n"
                 "      <dtol>{}</dtol>\n"
                 "      <etol>{}</etol>\n"
                 "      <rtol>{}</rtol>\n"
                 "      <lstol>0.9</lstol>\n"
                 "      <max_refs>{}</max_refs>\n"
                 "      <diverge_reform>1</diverge_reform>\n"
                 "      <optimize_bw>1</optimize_bw>\n"
                 "      <reform_each_time_step>1</reform_each_time_step>\n"
                 "      <qn_method type=\"BFGS\">\n"
                 "        <max_ups>0</max_ups>\n"
                 "      </qn_method>\n"
                 "    </solver>\n"
                 "  </Control>\n",
                 total_steps(problem), s.max_retries, number(s.min_step),
                 number(s.displacement_tolerance), number(s.energy_tolerance),
                 number(s.residual_tolerance), s.max_reformations);
}

/// The in-situ stretch's load curve: 1 at time 0 (the stretch times 1 / stretch), the full stretch
/// from time 1 on. Applied at once, it left FEBio's first Newton step with 334 inverted 10-node
/// tets on the female HRA MCL at every cut-back (a cut-back does not shrink a load with no curve);
/// ligsim's sweep ramps it too.
LoadCurve in_situ_stretch_ramp(const FebProblem& problem)
{
  return {1.0 / (1.0 + problem.in_situ_strain), std::vector<double>(total_steps(problem), 1.0)};
}

void write_materials(Buffer& out, const FebProblem& problem, std::vector<LoadCurve>& curves)
{
  const MaterialParameters& m = problem.material;
  const FiberParameters& f = *m.fiber;
  const std::string pressure_model = m.volumetric == VolumetricLaw::jm1 ? "Abaqus" : "default";
  const auto it = std::back_inserter(out);
  fmt::format_to(it, "  <Material>\n");
  if (problem.in_situ_strain == 0.0) {
    fmt::format_to(it,
                   "    <material id=\"1\" name=\"ligament\" type=\"trans iso Mooney-Rivlin\">\n"
                   "      <c1>{}</c1>\n      <c2>0</c2>\n      <c3>{}</c3>\n      <c4>{}</c4>\n"
                   "      <c5>{}</c5>\n      <lam_max>{}</lam_max>\n      <k>{}</k>\n"
                   "      <pressure_model>{}</pressure_model>\n"
                   "      <fiber type=\"map\">fiber</fiber>\n"
                   "    </material>\n",
                   number(0.5 * m.mu_mpa), number(f.c3_mpa), number(f.c4), number(f.c5_mpa),
                   number(f.lambda_star), number(m.bulk_modulus_mpa), pressure_model);
  } else {
    // The same energy as trans iso Mooney-Rivlin (Mooney-Rivlin plus the uncoupled Weiss fiber),
    // split so that the in-situ stretch pre-stretches the fiber alone, as sim/material does.
    fmt::format_to(it,
                   "    <material id=\"1\" name=\"ligament\" type=\"uncoupled solid mixture\">\n"
                   "      <k>{}</k>\n"
                   "      <pressure_model>{}</pressure_model>\n"
                   "      <solid type=\"Mooney-Rivlin\">\n"
                   "        <c1>{}</c1>\n        <c2>0</c2>\n        <k>0</k>\n"
                   "      </solid>\n"
                   "      <solid type=\"uncoupled prestrain elastic\">\n"
                   "        <elastic type=\"uncoupled fiber-exp-linear\">\n"
                   "          <c3>{}</c3>\n          <c4>{}</c4>\n          <c5>{}</c5>\n"
                   "          <lambda>{}</lambda>\n          <k>0</k>\n"
                   "          <fiber type=\"map\">fiber</fiber>\n"
                   "        </elastic>\n"
                   "        <prestrain type=\"in-situ stretch\">\n"
                   "          <stretch lc=\"{}\">{}</stretch>\n"
                   "          <isochoric>1</isochoric>\n"
                   "        </prestrain>\n"
                   "      </solid>\n"
                   "    </material>\n",
                   number(m.bulk_modulus_mpa), pressure_model, number(0.5 * m.mu_mpa),
                   number(f.c3_mpa), number(f.c4), number(f.c5_mpa), number(f.lambda_star),
                   curves.size() + 2, number(1.0 + problem.in_situ_strain));
    curves.push_back(in_situ_stretch_ramp(problem));
  }
  for (std::size_t b = 0; b < problem.bones.size(); ++b)
    fmt::format_to(it,
                   "    <material id=\"{}\" name=\"{}\" type=\"rigid body\">\n"
                   "      <density>1</density>\n"
                   "      <center_of_mass>{}</center_of_mass>\n"
                   "    </material>\n",
                   feb_material_id_of_bone(b), problem.bones[b].name,
                   vector3(problem.bones[b].center_mm));
  fmt::format_to(it, "  </Material>\n");
}

void write_node_list(Buffer& out, const std::vector<int>& ids)
{
  for (std::size_t i = 0; i < ids.size(); ++i)
    fmt::format_to(std::back_inserter(out), "{}{}", ids[i],
                   i + 1 == ids.size() ? "" : (i % 16 == 15 ? ",\n      " : ","));
}

/// The ligament's boundary faces (outward) with at least one node not bound to a bone.
Triangles free_faces(const FebProblem& problem)
{
  std::vector<bool> bound(static_cast<std::size_t>(problem.ligament.V.rows()), false);
  for (const FebRigidBody& bone : problem.bones)
    for (int node : bone.attached_nodes)
      bound[static_cast<std::size_t>(node)] = true;
  const Triangles boundary = boundary_surface(problem.ligament).faces;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < boundary.rows(); ++f) {
    bool all_bound = true;
    for (int c = 0; c < 3; ++c)
      all_bound = all_bound && bound[static_cast<std::size_t>(boundary(f, c))];
    if (!all_bound)
      kept.push_back(f);
  }
  Triangles faces(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    faces.row(static_cast<Eigen::Index>(i)) = boundary.row(kept[i]);
  return faces;
}

/// The contact facets of `faces`, 1-based: "tri3" of the corners, or with 10-node tets "tri6", the
/// corners then the mid-edge nodes of edges (0,1), (1,2), (2,0) (FEBio's order), so that the
/// facets are the faces of the quadratic elements FEBio finds them on.
std::pair<std::string, std::vector<std::vector<int>>> contact_facets(const FebProblem& problem,
                                                                     const Triangles& faces)
{
  std::map<std::pair<int, int>, int> middle; // (smaller, larger) corner -> mid-edge node
  const QuadraticTetrahedra& tet10 = problem.ligament_tet10;
  for (Eigen::Index t = 0; t < tet10.rows(); ++t)
    for (std::size_t e = 0; e < kQuadraticTetEdges.size(); ++e) {
      const int a = tet10(t, kQuadraticTetEdges[e][0]);
      const int b = tet10(t, kQuadraticTetEdges[e][1]);
      middle[std::minmax(a, b)] = tet10(t, 4 + static_cast<Eigen::Index>(e));
    }
  std::vector<std::vector<int>> facets;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::vector<int> nodes{faces(f, 0) + 1, faces(f, 1) + 1, faces(f, 2) + 1};
    if (tet10.rows() > 0)
      for (int c = 0; c < 3; ++c)
        nodes.push_back(middle.at(std::minmax(faces(f, c), faces(f, (c + 1) % 3))) + 1);
    facets.push_back(nodes);
  }
  return {tet10.rows() > 0 ? "tri6" : "tri3", facets};
}

void write_mesh(Buffer& out, const FebProblem& problem)
{
  const auto it = std::back_inserter(out);
  const TetMesh& mesh = problem.ligament;
  const Eigen::Index nodes = mesh.V.rows();
  fmt::format_to(it, "  <Mesh>\n    <Nodes name=\"ligament\">\n");
  for (Eigen::Index n = 0; n < nodes; ++n)
    fmt::format_to(it, "      <node id=\"{}\">{}</node>\n", n + 1,
                   vector3(mesh.V.row(n).transpose()));
  fmt::format_to(it, "    </Nodes>\n");
  // Bone nodes and triangles are numbered on after the ligament's.
  std::vector<int> node_offset;
  std::vector<int> element_offset;
  int next_node = static_cast<int>(nodes);
  int next_element = static_cast<int>(mesh.T.rows());
  for (const FebRigidBody& bone : problem.bones) {
    node_offset.push_back(next_node);
    element_offset.push_back(next_element);
    fmt::format_to(it, "    <Nodes name=\"{}\">\n", bone.name);
    for (Eigen::Index n = 0; n < bone.surface.V.rows(); ++n)
      fmt::format_to(it, "      <node id=\"{}\">{}</node>\n", next_node + n + 1,
                     vector3(bone.surface.V.row(n).transpose()));
    fmt::format_to(it, "    </Nodes>\n");
    next_node += static_cast<int>(bone.surface.V.rows());
    next_element += static_cast<int>(bone.surface.F.rows());
  }
  if (problem.ligament_tet10.rows() > 0) {
    fmt::format_to(it, "    <Elements type=\"TET10G4\" name=\"ligament\">\n");
    for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
      fmt::format_to(it, "      <elem id=\"{}\">{}", t + 1, problem.ligament_tet10(t, 0) + 1);
      for (int i = 1; i < 10; ++i)
        fmt::format_to(it, ",{}", problem.ligament_tet10(t, i) + 1);
      fmt::format_to(it, "</elem>\n");
    }
  } else {
    fmt::format_to(it, "    <Elements type=\"tet4\" name=\"ligament\">\n");
    for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
      fmt::format_to(it, "      <elem id=\"{}\">{},{},{},{}</elem>\n", t + 1, mesh.T(t, 0) + 1,
                     mesh.T(t, 1) + 1, mesh.T(t, 2) + 1, mesh.T(t, 3) + 1);
  }
  fmt::format_to(it, "    </Elements>\n");
  for (std::size_t b = 0; b < problem.bones.size(); ++b) {
    const FebRigidBody& bone = problem.bones[b];
    fmt::format_to(it, "    <Elements type=\"tri3\" name=\"{}\">\n", bone.name);
    for (Eigen::Index f = 0; f < bone.surface.F.rows(); ++f)
      fmt::format_to(it, "      <elem id=\"{}\">{},{},{}</elem>\n", element_offset[b] + f + 1,
                     node_offset[b] + bone.surface.F(f, 0) + 1,
                     node_offset[b] + bone.surface.F(f, 1) + 1,
                     node_offset[b] + bone.surface.F(f, 2) + 1);
    fmt::format_to(it, "    </Elements>\n");
  }
  fmt::format_to(it, "    <NodeSet name=\"ligament_nodes\">1:{}</NodeSet>\n", nodes);
  for (const FebRigidBody& bone : problem.bones) {
    if (bone.attached_nodes.empty())
      continue;
    std::vector<int> ids;
    for (int node : bone.attached_nodes)
      ids.push_back(node + 1);
    fmt::format_to(it, "    <NodeSet name=\"{}_attachment\">\n      ", bone.name);
    write_node_list(out, ids);
    fmt::format_to(it, "\n    </NodeSet>\n");
  }
  if (problem.contact) {
    const auto [type, facets] = contact_facets(problem, free_faces(problem));
    fmt::format_to(it, "    <Surface name=\"ligament_free_surface\">\n");
    for (std::size_t f = 0; f < facets.size(); ++f)
      fmt::format_to(it, "      <{0} id=\"{1}\">{2}</{0}>\n", type, f + 1,
                     fmt::join(facets[f], ","));
    fmt::format_to(it, "    </Surface>\n");
    for (std::size_t b = 0; b < problem.bones.size(); ++b) {
      const FebRigidBody& bone = problem.bones[b];
      if (!bone.contact)
        continue;
      fmt::format_to(it, "    <Surface name=\"{}_surface\">\n", bone.name);
      for (Eigen::Index f = 0; f < bone.surface.F.rows(); ++f)
        fmt::format_to(it, "      <tri3 id=\"{}\">{},{},{}</tri3>\n", f + 1,
                       node_offset[b] + bone.surface.F(f, 0) + 1,
                       node_offset[b] + bone.surface.F(f, 1) + 1,
                       node_offset[b] + bone.surface.F(f, 2) + 1);
      fmt::format_to(it, "    </Surface>\n");
      fmt::format_to(it,
                     "    <SurfacePair name=\"ligament_on_{0}\">\n"
                     "      <primary>ligament_free_surface</primary>\n"
                     "      <secondary>{0}_surface</secondary>\n"
                     "    </SurfacePair>\n",
                     bone.name);
    }
  }
  fmt::format_to(it, "  </Mesh>\n");
}

void write_domains_and_data(Buffer& out, const FebProblem& problem)
{
  const auto it = std::back_inserter(out);
  fmt::format_to(it, "  <MeshDomains>\n    <SolidDomain name=\"ligament\" mat=\"ligament\"/>\n");
  for (const FebRigidBody& bone : problem.bones)
    fmt::format_to(it, "    <ShellDomain name=\"{0}\" mat=\"{0}\"/>\n", bone.name);
  fmt::format_to(it, "  </MeshDomains>\n  <MeshData>\n"
                     "    <ElementData name=\"fiber\" elem_set=\"ligament\" data_type=\"vec3\">\n");
  for (Eigen::Index e = 0; e < problem.fiber_directions.rows(); ++e)
    fmt::format_to(it, "      <e lid=\"{}\">{}</e>\n", e + 1,
                   vector3(problem.fiber_directions.row(e).transpose()));
  fmt::format_to(it, "    </ElementData>\n  </MeshData>\n");
}

/// The bones' attachments, the fixed bones and the moving bones' six degrees of freedom, each
/// following its own load curve (curve 1 is the must-point curve of the time stepper).
void write_boundary_and_rigid(Buffer& out, const FebProblem& problem,
                              std::vector<LoadCurve>& curves)
{
  const auto it = std::back_inserter(out);
  fmt::format_to(it, "  <Boundary>\n");
  for (const FebRigidBody& bone : problem.bones)
    if (!bone.attached_nodes.empty())
      fmt::format_to(it,
                     "    <bc name=\"{0}_attachment\" node_set=\"{0}_attachment\" "
                     "type=\"rigid\">\n      <rb>{0}</rb>\n    </bc>\n",
                     bone.name);
  fmt::format_to(it, "  </Boundary>\n  <Rigid>\n");
  static constexpr const char* translations[3] = {"x", "y", "z"};
  static constexpr const char* rotations[3] = {"Ru", "Rv", "Rw"};
  for (const FebRigidBody& bone : problem.bones) {
    if (bone.poses.empty()) {
      fmt::format_to(it,
                     "    <rigid_bc name=\"{0}_fixed\" type=\"rigid_fixed\">\n"
                     "      <rb>{0}</rb>\n"
                     "      <Rx_dof>1</Rx_dof>\n      <Ry_dof>1</Ry_dof>\n"
                     "      <Rz_dof>1</Rz_dof>\n      <Ru_dof>1</Ru_dof>\n"
                     "      <Rv_dof>1</Rv_dof>\n      <Rw_dof>1</Rw_dof>\n"
                     "    </rigid_bc>\n",
                     bone.name);
      continue;
    }
    std::vector<Eigen::Matrix<double, 6, 1>> dofs(static_cast<std::size_t>(problem.settle_steps),
                                                  Eigen::Matrix<double, 6, 1>::Zero());
    for (const Eigen::Isometry3d& pose : bone.poses)
      dofs.push_back(feb_rigid_dofs(pose, bone.center_mm));
    for (int d = 0; d < 6; ++d) {
      LoadCurve curve;
      for (const auto& step : dofs)
        curve.at_steps.push_back(step(d));
      curves.push_back(curve);
      const bool turn = d >= 3;
      fmt::format_to(it,
                     "    <rigid_bc name=\"{0}_{1}\" type=\"{2}\">\n"
                     "      <rb>{0}</rb>\n"
                     "      <dof>{1}</dof>\n"
                     "      <value lc=\"{3}\">1</value>\n"
                     "      <relative>0</relative>\n"
                     "    </rigid_bc>\n",
                     bone.name, turn ? rotations[d - 3] : translations[d],
                     turn ? "rigid_rotation" : "rigid_displacement", curves.size() + 1);
    }
  }
  fmt::format_to(it, "  </Rigid>\n");
}

/// Frictionless sliding-elastic contact of the free surface with each contact bone; a bone with a
/// start offset gets FEBio's contact offset -offset at time 0, ramped to 0 at time 1 by its own
/// load curve.
void write_contact(Buffer& out, const FebProblem& problem, std::vector<LoadCurve>& curves)
{
  if (!problem.contact)
    return;
  const auto it = std::back_inserter(out);
  int ramp = 0; // the ramp's load curve id, once written
  fmt::format_to(it, "  <Contact>\n");
  for (const FebRigidBody& bone : problem.bones) {
    if (!bone.contact)
      continue;
    fmt::format_to(it,
                   "    <contact name=\"ligament_on_{0}\" type=\"sliding-elastic\" "
                   "surface_pair=\"ligament_on_{0}\">\n"
                   "      <laugon>PENALTY</laugon>\n"
                   "      <penalty>{1}</penalty>\n"
                   "      <auto_penalty>1</auto_penalty>\n"
                   "      <two_pass>0</two_pass>\n"
                   "      <search_tol>{2}</search_tol>\n"
                   "      <symmetric_stiffness>1</symmetric_stiffness>\n"
                   "      <fric_coeff>0</fric_coeff>\n",
                   bone.name, number(problem.contact_settings.penalty),
                   number(problem.contact_settings.search_tol));
    if (bone.contact_start_offset_mm > 0.0) {
      if (ramp == 0) {
        LoadCurve down{1.0, std::vector<double>(total_steps(problem), 0.0)};
        curves.push_back(down);
        ramp = static_cast<int>(curves.size()) + 1;
      }
      fmt::format_to(it, "      <offset lc=\"{}\">{}</offset>\n", ramp,
                     number(-bone.contact_start_offset_mm));
    }
    fmt::format_to(it, "    </contact>\n");
  }
  fmt::format_to(it, "  </Contact>\n");
}

void write_load_data(Buffer& out, const FebProblem& problem, const std::vector<LoadCurve>& curves)
{
  const auto it = std::back_inserter(out);
  const std::size_t steps = total_steps(problem);
  // Curve 1: the step ends are must points (the time stepper lands on each of them).
  fmt::format_to(it, "  <LoadData>\n"
                     "    <load_controller id=\"1\" name=\"must_points\" type=\"loadcurve\">\n"
                     "      <interpolate>STEP</interpolate>\n      <points>\n");
  // FEBio refuses to initialise a step whose must-point curve has one point: time 0 is one too.
  fmt::format_to(it, "        <pt>0,1</pt>\n");
  for (std::size_t k = 0; k < steps; ++k)
    fmt::format_to(it, "        <pt>{},1</pt>\n", k + 1);
  fmt::format_to(it, "      </points>\n    </load_controller>\n");
  for (std::size_t c = 0; c < curves.size(); ++c) {
    fmt::format_to(it,
                   "    <load_controller id=\"{}\" type=\"loadcurve\">\n"
                   "      <interpolate>LINEAR</interpolate>\n"
                   "      <extend>CONSTANT</extend>\n"
                   "      <points>\n        <pt>0,{}</pt>\n",
                   c + 2, number(curves[c].at_zero));
    for (std::size_t k = 0; k < steps; ++k)
      fmt::format_to(it, "        <pt>{},{}</pt>\n", k + 1, number(curves[c].at_steps[k]));
    fmt::format_to(it, "      </points>\n    </load_controller>\n");
  }
  fmt::format_to(it, "  </LoadData>\n");
}

void write_output(Buffer& out, const FebProblem& problem)
{
  fmt::format_to(std::back_inserter(out),
                 "  <Output>\n"
                 "    <plotfile type=\"febio\">\n"
                 "      <var type=\"displacement\"/>\n"
                 "      <var type=\"stress\"/>\n"
                 "      <var type=\"relative volume\"/>\n"
                 "      <var type=\"strain energy density\"/>\n"
                 "{}"
                 "    </plotfile>\n"
                 "    <logfile>\n"
                 "      <node_data data=\"x;y;z\" node_set=\"ligament_nodes\"/>\n"
                 "      <rigid_body_data data=\"x;y;z;qx;qy;qz;qw;Fx;Fy;Fz;Mx;My;Mz\"/>\n"
                 "      <element_data data=\"sed\" elem_set=\"ligament\"/>\n"
                 "    </logfile>\n"
                 "  </Output>\n",
                 problem.contact ? "      <var type=\"contact pressure\"/>\n"
                                   "      <var type=\"contact gap\"/>\n"
                                 : "");
}

} // namespace

Eigen::Matrix<double, 6, 1> feb_rigid_dofs(const Eigen::Isometry3d& pose,
                                           const Eigen::Vector3d& center_mm)
{
  const Eigen::AngleAxisd turn(pose.linear());
  Eigen::Matrix<double, 6, 1> dofs;
  dofs.head<3>() = pose * center_mm - center_mm;
  dofs.tail<3>() = turn.angle() * turn.axis();
  return dofs;
}

std::string feb_text(const FebProblem& problem)
{
  validate(problem);
  Buffer out;
  const auto it = std::back_inserter(out);
  fmt::format_to(it, "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n");
  for (const std::string& note : problem.notes)
    fmt::format_to(it, "<!-- {} -->\n", comment_text(note));
  fmt::format_to(it, "<febio_spec version=\"4.0\">\n  <Module type=\"solid\"/>\n");
  write_control(out, problem);
  std::vector<LoadCurve> curves;
  write_materials(out, problem, curves);
  write_mesh(out, problem);
  write_domains_and_data(out, problem);
  write_boundary_and_rigid(out, problem, curves);
  write_contact(out, problem, curves);
  write_load_data(out, problem, curves);
  write_output(out, problem);
  fmt::format_to(it, "</febio_spec>\n");
  return fmt::to_string(out);
}

void write_feb(const std::filesystem::path& file, const FebProblem& problem)
{
  write_text_atomically(file, feb_text(problem));
}

} // namespace ligsim::sim
