#include "sim/verify/flexion_stability.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/resources.hpp"
#include "common/vtk_files.hpp"
#include "sim/flexion/flexion_output.hpp"
#include "sim/flexion/knee_contact.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/mesh/tet_shape.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

namespace ligsim::sim {

namespace fs = std::filesystem;

struct FlexionStabilitySuite::LoadedModel {
  fs::path dir;
  KneeModel model;
  ResolvedAxis axis;
};

namespace {

struct CaseDefinition {
  StabilityCase info;
  bool fine = false;
  std::function<void(FlexionSettings&)> settings;
  /// Changes the model; returns what it did.
  std::function<std::string(KneeModel&)> model;
};

/// "1e6", "1e-4": a power of ten in a case name.
std::string power_of_ten(double value)
{
  return fmt::format("1e{}", static_cast<int>(std::lround(std::log10(value))));
}

/// Interactive sweep at `time_step_s` up to `angles`' last angle (45 deg/s, the default speed).
CaseDefinition interactive_case(double time_step_s, std::vector<double> angles)
{
  const int frames = static_cast<int>(std::lround(angles.back() / (45.0 * time_step_s)));
  return {{"interactive_dt_" + power_of_ten(time_step_s),
           fmt::format("interactive, time step {:.0e} s, 45 deg/s to {:g} deg ({} frames)",
                       time_step_s, angles.back(), frames)},
          false,
          [time_step_s, angles](FlexionSettings& s) {
            s.mode = FlexionMode::interactive;
            s.interactive.time_step_s = time_step_s;
            s.angles_deg = angles;
          },
          {}};
}

/// Each fiber turned by 90 degrees about a direction across it (the coordinate axis it is
/// least aligned with, crossed with it).
std::string turn_fibers(KneeModel& model)
{
  for (Eigen::MatrixX3d* fibers : {&model.fiber_directions, &model.fiber_directions_at_points})
    for (Eigen::Index e = 0; e < fibers->rows(); ++e) {
      const Eigen::Vector3d a = fibers->row(e);
      Eigen::Index least = 0;
      a.cwiseAbs().minCoeff(&least);
      fibers->row(e) = a.cross(Eigen::Vector3d::Unit(least)).normalized();
    }
  return fmt::format("{} fibers turned 90 degrees", model.fiber_directions.rows());
}

/// Every other element's fiber reversed: the law depends on a (x) a only, so nothing may change.
std::string reverse_fibers(KneeModel& model)
{
  for (Eigen::Index e = 0; e < model.fiber_directions.rows(); e += 2)
    model.fiber_directions.row(e) *= -1.0;
  for (Eigen::Index p = 0; p < model.fiber_directions_at_points.rows(); p += 2)
    model.fiber_directions_at_points.row(p) *= -1.0;
  return fmt::format("{} fibers reversed (every other element)",
                     (model.fiber_directions.rows() + 1) / 2);
}

std::vector<CaseDefinition> definitions()
{
  std::vector<CaseDefinition> list;
  list.push_back({{"coarse_140", "quasi-static flexion to 140 deg, the flexion config's material"},
                  false,
                  {},
                  {}});
  for (double strain : {0.0, 0.05, 0.10})
    list.push_back({{fmt::format("in_situ_{:.0f}pct", 100 * strain),
                     fmt::format("in-situ strain {:.0f} %", 100 * strain)},
                    false,
                    [strain](FlexionSettings& s) { s.in_situ_strain = strain; },
                    {}});
  for (double k : {1e2, 1e4, 1e5, 1e6})
    list.push_back({{"k_" + power_of_ten(k), fmt::format("K = {:.0e} MPa", k)},
                    false,
                    [k](FlexionSettings& s) { s.material.bulk_modulus_mpa = k; },
                    {}});
  list.push_back({{"c5_x10", "C5 times 10 (6,407 MPa)"},
                  false,
                  [](FlexionSettings& s) { s.material.fiber->c5_mpa *= 10.0; },
                  {}});
  list.push_back({{"stiff_all", "K = 1e6 MPa, C5 times 10 and 10 % in-situ strain together"},
                  false,
                  [](FlexionSettings& s) {
                    s.material.bulk_modulus_mpa = 1e6;
                    s.material.fiber->c5_mpa *= 10.0;
                    s.in_situ_strain = 0.10;
                  },
                  {}});
  list.push_back({{"fine_140", "fine model, quasi-static flexion to 140 deg"}, true, {}, {}});
  list.push_back({{"fine_k_1e6", "fine model, K = 1e6 MPa"},
                  true,
                  [](FlexionSettings& s) { s.material.bulk_modulus_mpa = 1e6; },
                  {}});
  list.push_back(interactive_case(1e-4, {0, 2, 5}));
  list.push_back(interactive_case(1e-3, {0, 20, 45}));
  list.push_back(interactive_case(1e-2, {0, 20, 40, 60, 80, 100, 120, 140}));
  list.push_back(interactive_case(1e-1, {0, 20, 40, 60, 80, 100, 120, 140}));
  list.push_back({{"slivers", "1 % of the tets flattened to 1 % of their volume"},
                  false,
                  {},
                  [](KneeModel& model) {
                    std::vector<int> fixed = model.femur_nodes;
                    fixed.insert(fixed.end(), model.tibia_nodes.begin(), model.tibia_nodes.end());
                    const int wanted = std::max(10, static_cast<int>(model.mesh.T.rows() / 100));
                    const int made = inject_slivers(model.mesh, wanted, 0.01, fixed);
                    return fmt::format("{} slivers injected", made);
                  }});
  list.push_back({{"fibers_turned_90", "every fiber turned 90 degrees (across the ligament)"},
                  false,
                  {},
                  turn_fibers});
  list.push_back({{"fibers_reversed", "every other fiber reversed (must change nothing)"},
                  false,
                  {},
                  reverse_fibers});
  list.push_back({{"contact_140", "flexion to 140 deg with ligament-bone contact"},
                  false,
                  [](FlexionSettings& s) { s.contact.enabled = true; },
                  {}});
  return list;
}

double signed_volume(const TetMesh& mesh, Eigen::Index e)
{
  const Eigen::Vector3d a = mesh.V.row(mesh.T(e, 0));
  return (Eigen::Vector3d(mesh.V.row(mesh.T(e, 1))) - a)
             .dot((Eigen::Vector3d(mesh.V.row(mesh.T(e, 2))) - a)
                      .cross(Eigen::Vector3d(mesh.V.row(mesh.T(e, 3))) - a)) /
         6.0;
}

/// Every value of `array` finite? Otherwise "array name, entry i".
std::optional<std::string> check_array(vtkDataArray* array, const std::string& what)
{
  if (!array)
    return std::nullopt;
  const vtkIdType values = array->GetNumberOfTuples() * array->GetNumberOfComponents();
  for (vtkIdType i = 0; i < values; ++i) {
    const double value =
        array->GetComponent(i / array->GetNumberOfComponents(), i % array->GetNumberOfComponents());
    if (!std::isfinite(value))
      return fmt::format("{} '{}', entry {} is {}", what, array->GetName() ? array->GetName() : "",
                         i, value);
  }
  return std::nullopt;
}

std::optional<std::string> check_data_set(vtkDataSet* data)
{
  if (auto* points = vtkPointSet::SafeDownCast(data); points && points->GetPoints())
    if (auto found = check_array(points->GetPoints()->GetData(), "points"))
      return found;
  for (auto [attributes, what] :
       {std::pair<vtkFieldData*, const char*>{data->GetPointData(), "point array"},
        {data->GetCellData(), "cell array"},
        {data->GetFieldData(), "field array"}})
    for (int a = 0; a < attributes->GetNumberOfArrays(); ++a)
      if (auto found = check_array(attributes->GetArray(a), what))
        return found;
  return std::nullopt;
}

/// Text files: a token that reads as nan or inf (as printf, fmt and nlohmann::json write them;
/// nlohmann writes null for a non-finite number, so null counts too in JSON).
std::optional<std::string> check_text(const fs::path& file)
{
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  static const std::regex non_finite(R"((^|[^A-Za-z_])([-+]?(nan|inf|infinity))($|[^A-Za-z_]))",
                                     std::regex::icase);
  std::smatch match;
  if (std::regex_search(text, match, non_finite))
    return fmt::format("'{}' at character {}", match[2].str(), match.position(2));
  if (file.extension() == ".json" && text.find("null") != std::string::npos)
    return fmt::format("null (a non-finite number) at character {}", text.find("null"));
  return std::nullopt;
}

/// |free internal force| / |force on the attached nodes| at positions x (contact included); the
/// force on the attached nodes counts at least the solver's force floor, 1e-12 mu size^2 (a
/// ligament without pre-stretch at 0 degrees carries round-off alone).
double equilibrium_residual(const HyperelasticBody& body, const KneeModel& model,
                            const KneeContact* contact, double t, const Eigen::VectorXd& x)
{
  Eigen::VectorXd gradient;
  body.energy_gradient(x, gradient);
  if (contact)
    contact->potential().energy(x, t, &gradient);
  std::vector<char> attached(static_cast<std::size_t>(body.node_count()), 0);
  for (const std::vector<int>* set : {&model.femur_nodes, &model.tibia_nodes})
    for (int node : *set)
      attached[static_cast<std::size_t>(node)] = 1;
  double free2 = 0.0;
  double reaction2 = 0.0;
  for (int node = 0; node < body.node_count(); ++node)
    (attached[static_cast<std::size_t>(node)] ? reaction2 : free2) +=
        gradient.segment<3>(3 * node).squaredNorm();
  const Points& V = model.mesh.V;
  const double size = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const double force_floor = 1e-12 * body.material().parameters().mu_mpa * size * size;
  return std::sqrt(free2) / std::max(std::sqrt(reaction2), force_floor);
}

/// A stop message must say where: an angle, element, node, frame or step.
bool names_a_place(const std::string& message)
{
  static const std::regex place(R"((element|node|frame|step|angle|to) [-+0-9.]+)");
  return std::regex_search(message, place);
}

} // namespace

FlexionStabilitySuite::FlexionStabilitySuite(FlexionSettings base, fs::path coarse_model,
                                             fs::path fine_model,
                                             std::vector<double> static_angles_deg)
    : m_base(std::move(base))
    , m_coarse_dir(std::move(coarse_model))
    , m_fine_dir(std::move(fine_model))
    , m_static_angles(std::move(static_angles_deg))
{
  m_base.images = false;
  m_base.contact.enabled = false; // on in the contact case only
}

FlexionStabilitySuite::~FlexionStabilitySuite() = default;

std::vector<StabilityCase> FlexionStabilitySuite::cases()
{
  std::vector<StabilityCase> list;
  for (const CaseDefinition& d : definitions())
    list.push_back(d.info);
  return list;
}

const FlexionStabilitySuite::LoadedModel& FlexionStabilitySuite::model(bool fine)
{
  std::unique_ptr<LoadedModel>& slot = fine ? m_fine : m_coarse;
  if (!slot) {
    auto loaded = std::make_unique<LoadedModel>();
    loaded->dir = fine ? m_fine_dir : m_coarse_dir;
    loaded->model = load_ligament(loaded->dir, "ligament", "verify stability").model;
    loaded->axis = resolve_flexion_axis(loaded->model, m_base.axis);
    slot = std::move(loaded);
  }
  return *slot;
}

FlexionCaseResult FlexionStabilitySuite::run(const std::string& name, const fs::path& out)
{
  const std::vector<CaseDefinition> list = definitions();
  const auto found = std::find_if(list.begin(), list.end(),
                                  [&](const CaseDefinition& d) { return d.info.name == name; });
  if (found == list.end())
    fail("unknown flexion stability case '{}'", name);
  const CaseDefinition& definition = *found;
  FlexionCaseResult result;
  result.name = name;
  result.description = definition.info.description;
  result.model = definition.fine ? "fine" : "coarse";
  if (definition.fine && m_fine_dir.empty()) {
    result.outcome = Outcome::skipped;
    result.diagnostic = "no fine model given (--fine-model)";
    result.equilibrium_residual = std::numeric_limits<double>::quiet_NaN();
    return result;
  }

  FlexionSettings settings = m_base;
  settings.angles_deg = m_static_angles;
  if (definition.settings)
    definition.settings(settings);
  result.target_angle_deg = settings.angles_deg.back();
  const fs::path directory = out / name;
  const auto start = std::chrono::steady_clock::now();
  double worst_residual = 0.0;
  bool residual_measured = false;
  try {
    const LoadedModel& loaded = model(definition.fine);
    KneeModel knee = loaded.model;
    if (definition.model)
      result.model_change = definition.model(knee);
    result.tets = static_cast<int>(knee.mesh.T.rows());
    const HyperelasticBody body = ligament_body(knee, settings.material, settings.in_situ_strain);
    const BoundaryConditions conditions =
        knee_conditions(knee, loaded.axis.axis, settings.angles_deg.back());
    std::unique_ptr<KneeContact> contact;
    if (settings.contact.enabled.value_or(true))
      contact =
          std::make_unique<KneeContact>(knee, conditions, settings.contact, loaded.dir / "contact");
    ensure_directory(directory);
    // One ligament, named "ligament", written in `directory` itself: a knee of one ligament.
    FlexionOutput output({{"ligament", "", knee.distal_bone}}, knee,
                         *conditions.constraints.back().rigid, directory);
    const bool quasi_static = settings.mode == FlexionMode::quasi_static;
    const double last = settings.angles_deg.back();
    const SweepResult sweep = run_flexion_sweep(
        body, conditions, settings,
        [&](const AngleResult& angle, const HyperelasticBody& swept, const Eigen::VectorXd& x) {
          output.write_angle(0, swept, angle, x);
          if (quasi_static) {
            const double t = last > 0.0 ? angle.angle_deg / last : 0.0;
            worst_residual =
                std::max(worst_residual, equilibrium_residual(swept, knee, contact.get(), t, x));
            residual_measured = true;
          }
        },
        contact.get());
    output.finish(std::vector<std::vector<AngleResult>>{sweep.angles});
    result.angles = sweep.angles;
    result.diagnostic = sweep.failure;
    const bool all_reached = sweep.success && sweep.angles.size() == settings.angles_deg.size();
    if (all_reached)
      result.outcome = quasi_static ? Outcome::converged : Outcome::completed;
    else
      result.outcome = names_a_place(sweep.failure) ? Outcome::diagnostic : Outcome::failed;
  } catch (const Error& e) {
    result.diagnostic = e.what();
    result.outcome = names_a_place(result.diagnostic) ? Outcome::diagnostic : Outcome::failed;
  }
  result.wall_s = seconds_since(start);
  result.equilibrium_residual =
      residual_measured ? worst_residual : std::numeric_limits<double>::quiet_NaN();
  for (const AngleResult& angle : result.angles) {
    result.iterations += angle.newton_iterations;
    result.max_fiber_strain = std::max(result.max_fiber_strain, angle.max_fiber_stretch - 1.0);
    result.min_j = std::min(result.min_j, angle.min_j);
  }
  if (fs::exists(directory))
    if (const std::optional<std::string> bad = first_non_finite_value(directory)) {
      result.non_finite = *bad;
      result.outcome = Outcome::failed;
    }
  return result;
}

std::optional<std::string> first_non_finite_value(const fs::path& directory)
{
  std::set<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory))
    if (entry.is_regular_file())
      files.insert(entry.path());
  for (const fs::path& file : files) {
    const std::string extension = file.extension().string();
    std::optional<std::string> found;
    if (extension == ".vtu")
      found = check_data_set(read_vtu(file));
    else if (extension == ".vtp")
      found = check_data_set(read_vtp(file));
    else if (extension == ".csv" || extension == ".json" || extension == ".svg" ||
             extension == ".pvd" || extension == ".md")
      found = check_text(file);
    if (found)
      return file.filename().string() + ": " + *found;
  }
  return std::nullopt;
}

int inject_slivers(TetMesh& mesh, int count, double volume_fraction, const std::vector<int>& fixed)
{
  std::vector<std::vector<int>> elements_of(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e)
    for (int i = 0; i < 4; ++i)
      elements_of[static_cast<std::size_t>(mesh.T(e, i))].push_back(static_cast<int>(e));
  std::vector<char> locked(static_cast<std::size_t>(mesh.V.rows()), 0);
  for (int node : fixed)
    locked[static_cast<std::size_t>(node)] = 1;

  int made = 0;
  const Eigen::Index stride = std::max<Eigen::Index>(1, mesh.T.rows() / std::max(1, count));
  for (Eigen::Index e = stride / 2; e < mesh.T.rows() && made < count; e += stride) {
    for (int i = 0; i < 4; ++i) {
      const int node = mesh.T(e, i);
      if (locked[static_cast<std::size_t>(node)])
        continue;
      const Eigen::Vector3d p = mesh.V.row(node); // restored if the move is refused
      std::vector<double> before;
      for (int other : elements_of[static_cast<std::size_t>(node)])
        before.push_back(signed_volume(mesh, other));
      mesh.V.row(node) = toward_opposite_face(mesh, e, i, volume_fraction).transpose();
      bool valid = true;
      for (std::size_t k = 0; k < before.size(); ++k) {
        const int other = elements_of[static_cast<std::size_t>(node)][k];
        // The others keep at least the sliver's share of their volume: one sliver per move.
        if (other != e && signed_volume(mesh, other) < volume_fraction * before[k])
          valid = false;
      }
      if (valid) {
        for (int k = 0; k < 4; ++k) // no later move may change this sliver
          locked[static_cast<std::size_t>(mesh.T(e, k))] = 1;
        ++made;
        break;
      }
      mesh.V.row(node) = p.transpose();
    }
  }
  return made;
}

namespace {

std::string reached(const FlexionCaseResult& r)
{
  if (r.outcome == Outcome::skipped)
    return "-";
  return fmt::format("{:g} / {:g}", r.angles.empty() ? 0.0 : r.angles.back().angle_deg,
                     r.target_angle_deg);
}

std::string residual_text(double value)
{
  return std::isfinite(value) ? fmt::format("{:.1e}", value) : "-";
}

} // namespace

std::string flexion_stability_table(const std::vector<FlexionCaseResult>& results)
{
  std::string table =
      "| case | set-up | tets | outcome | deg reached | iterations | wall s | max "
      "fiber strain | worst J | equilibrium residual | diagnostic |\n"
      "| --- | --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n";
  for (const FlexionCaseResult& r : results) {
    std::string note = r.diagnostic.empty() ? "-" : r.diagnostic;
    if (!r.model_change.empty())
      note = r.model_change + (r.diagnostic.empty() ? "" : "; " + r.diagnostic);
    if (!r.non_finite.empty())
      note += "; NON-FINITE: " + r.non_finite;
    table += fmt::format("| {} | {} | {} | {} | {} | {} | {:.1f} | {:.1f} % | {:.3f} | {} | {} |\n",
                         r.name, r.description, r.tets, to_string(r.outcome), reached(r),
                         r.iterations, r.wall_s, 100.0 * r.max_fiber_strain, r.min_j,
                         residual_text(r.equilibrium_residual), note);
  }
  return table;
}

std::string flexion_stability_csv(const std::vector<FlexionCaseResult>& results)
{
  auto quoted = [](std::string text) {
    std::string out = "\"";
    for (char c : text)
      out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  std::string csv = "case,model,tets,outcome,last_angle_deg,target_angle_deg,iterations,wall_s,"
                    "max_fiber_strain,min_j,equilibrium_residual,diagnostic\n";
  for (const FlexionCaseResult& r : results)
    csv += fmt::format("{},{},{},{},{},{},{},{:.3f},{:.6g},{:.6g},{},{}\n", r.name, r.model, r.tets,
                       to_string(r.outcome), r.angles.empty() ? 0.0 : r.angles.back().angle_deg,
                       r.target_angle_deg, r.iterations, r.wall_s, r.max_fiber_strain, r.min_j,
                       std::isfinite(r.equilibrium_residual)
                           ? fmt::format("{:.3e}", r.equilibrium_residual)
                           : std::string(),
                       quoted(r.diagnostic));
  return csv;
}

} // namespace ligsim::sim
