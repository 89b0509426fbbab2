#include "pipeline/view/live_window.hpp"
#include "pipeline/view/view_style.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/pvd_file.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/render/picture_parts.hpp"
#include "pipeline/render/window_png.hpp"
#include "stages/io/vtk_convert.hpp"

#include <X11/Xlib.h>
#include <fmt/format.h>
#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkLookupTable.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkQuadricDecimation.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSliderRepresentation2D.h>
#include <vtkSliderWidget.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <future>
#include <map>
#include <optional>

namespace ligsim::cli {

namespace fs = std::filesystem;

namespace {

constexpr double kKeyStepDeg = 5.0;

double now_s()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// The faces of a tet mesh that belong to one tet only, each with its tet.
std::vector<std::pair<std::array<int, 3>, int>> boundary_faces(const TetMesh& mesh)
{
  static constexpr std::array<std::array<int, 3>, 4> kFaces = {
      {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
  // Per face (sorted corners): its corners as its tet orders them, its tet, how many tets.
  struct Seen {
    std::array<int, 3> face;
    int element;
    int count;
  };
  std::map<std::array<int, 3>, Seen> seen;
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e)
    for (const std::array<int, 3>& f : kFaces) {
      const std::array<int, 3> face = {mesh.T(e, f[0]), mesh.T(e, f[1]), mesh.T(e, f[2])};
      std::array<int, 3> key = face;
      std::sort(key.begin(), key.end());
      auto [entry, added] = seen.try_emplace(key, Seen{face, static_cast<int>(e), 0});
      ++entry->second.count;
    }
  std::vector<std::pair<std::array<int, 3>, int>> faces;
  for (const auto& [key, face] : seen)
    if (face.count == 1)
      faces.push_back({face.face, face.element});
  return faces;
}

/// A bone with at most kDisplayTriangles triangles (quadric decimation): the bones are drawn at
/// every frame, and a segmented tibia's 60,000 triangles cost a software renderer more than the
/// ligament's frame costs the solver.
vtkSmartPointer<vtkPolyData> for_display(vtkPolyData* bone)
{
  constexpr double kDisplayTriangles = 8000.0;
  auto shown = vtkSmartPointer<vtkPolyData>::New();
  const vtkIdType cells = bone->GetNumberOfPolys();
  if (cells <= kDisplayTriangles) {
    shown->ShallowCopy(bone);
    return shown;
  }
  vtkNew<vtkQuadricDecimation> decimate;
  decimate->SetInputData(bone);
  decimate->SetTargetReduction(1.0 - kDisplayTriangles / static_cast<double>(cells));
  decimate->Update();
  shown->ShallowCopy(decimate->GetOutput());
  return shown;
}

/// Frames per second over the last second's events.
class Rate {
public:
  void tick(double t)
  {
    m_times.push_back(t);
    while (m_times.size() > 2 && m_times.back() - m_times.front() > 1.0)
      m_times.pop_front();
  }
  double per_second() const
  {
    return m_times.size() < 2 ? 0.0 : (m_times.size() - 1) / (m_times.back() - m_times.front());
  }

private:
  std::deque<double> m_times;
};

} // namespace

void require_display()
{
  const char* name = std::getenv("DISPLAY");
  Display* display = name && *name ? XOpenDisplay(name) : nullptr;
  if (!display)
    fail("ligsim view needs an X display and {}; without a screen run it under a virtual one: "
         "xvfb-run -a -s \"-screen 0 1280x1024x24\" ligsim view ...",
         name && *name ? fmt::format("DISPLAY={} does not answer", name) : "DISPLAY is not set");
  XCloseDisplay(display);
}

struct LiveWindow::Scene {
  sim::LiveKnee& knee;
  LiveWindowOptions options;
  vtkNew<vtkRenderWindow> window;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkActor> femur;
  /// The bones as drawn (femur, tibia, fibula if any) and the ligaments' names, for the
  /// recorded series.
  std::vector<vtkSmartPointer<vtkPolyData>> bones_shown;
  std::vector<std::string> names;
  std::vector<vtkSmartPointer<vtkPolyData>> surfaces;
  std::vector<std::vector<int>> face_elements;
  vtkNew<vtkLookupTable> colours;
  vtkNew<vtkTextActor> overlay;
  vtkNew<vtkSliderRepresentation2D> slider_look;
  vtkNew<vtkSliderWidget> slider;
  double target_deg = 0.0;
  Rate drawn;
  std::deque<double> compute_s; ///< the last frames' computing times
  double computing_s = 0.0;     ///< all frames' computing time
  std::string csv;
  std::vector<PvdDataSet> series; ///< the recorded frames' files, for frames.pvd
  int recorded = 0;
  int screenshots = 0;
  std::string error;

  Scene(sim::LiveKnee& live, LiveWindowOptions chosen)
      : knee(live)
      , options(std::move(chosen))
  {
  }

  void update_actors()
  {
    const Eigen::Isometry3d pose = knee.femur_pose();
    vtkNew<vtkMatrix4x4> matrix;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        matrix->SetElement(i, j, pose.matrix()(i, j));
    femur->SetUserMatrix(matrix);
    for (std::size_t l = 0; l < surfaces.size(); ++l) {
      const Eigen::VectorXd& x = knee.ligament(l).positions();
      vtkPoints* points = surfaces[l]->GetPoints();
      for (vtkIdType n = 0; n < points->GetNumberOfPoints(); ++n)
        points->SetPoint(n, x(3 * n), x(3 * n + 1), x(3 * n + 2));
      points->Modified();
      const Eigen::VectorXd& strain = knee.fiber_strain(l);
      auto* values = vtkDoubleArray::SafeDownCast(surfaces[l]->GetCellData()->GetScalars());
      for (std::size_t f = 0; f < face_elements[l].size(); ++f)
        values->SetValue(static_cast<vtkIdType>(f), 100.0 * strain[face_elements[l][f]]);
      values->Modified();
    }
  }

  /// Frames the simulation computes per second (the last 30 frames' computing times).
  double simulated_per_second() const
  {
    double total = 0.0;
    for (double s : compute_s)
      total += s;
    return total > 0.0 ? compute_s.size() / total : 0.0;
  }

  /// The overlay's lines and the frames.csv row of the frame just drawn.
  void update_text()
  {
    const sim::LiveFrame& frame = knee.last();
    std::string text =
        fmt::format("flexion {:.1f} deg (slider {:.1f})", frame.angle_deg, frame.target_deg);
    std::string row = fmt::format("{},{:.4f},{:.4f},{:.4f}", frame.frame, frame.time_s,
                                  frame.angle_deg, frame.target_deg);
    for (const sim::LiveLigament& l : frame.ligaments) {
      text += fmt::format("\n{} {:.1f} N, {:.2f} % over 2 mm", l.name, l.femur_force_n,
                          l.regional_peak_pct);
      row += fmt::format(",{:.1f},{:.2f}", l.femur_force_n, l.regional_peak_pct);
    }
    text += fmt::format("\n{} solves | {:.0f} frames/s drawn, {:.0f} simulated | contact {}",
                        frame.solves, drawn.per_second(), simulated_per_second(),
                        knee.contact() ? "on" : "off");
    row += fmt::format(",{},{:.2f},{:.2f},{:.4f}", frame.solves, drawn.per_second(),
                       simulated_per_second(), frame.wall_s);
    overlay->SetInput(text.c_str());
    std::string flat = text;
    std::replace(flat.begin(), flat.end(), '\n', '|');
    csv += row + ",\"" + flat + "\"\n";
  }

  /// The simulation's part of a frame: one frame towards `target`.
  void compute(double target)
  {
    knee.advance(target);
    computing_s += knee.last().wall_s;
    compute_s.push_back(knee.last().wall_s);
    if (compute_s.size() > 30)
      compute_s.pop_front();
  }

  /// Draws the frame computed last (recording it when asked) while the next one, towards
  /// `next_target`, is computed on another thread: drawing and simulation overlap.
  void frame(std::optional<double> next_target)
  {
    update_actors();
    drawn.tick(now_s());
    update_text();
    const double time_s = knee.last().time_s; // before the next frame's computing changes it
    std::future<void> next;
    if (next_target)
      next = std::async(std::launch::async, [this, target = *next_target] { compute(target); });
    if (!options.record.empty()) {
      render::write_window_png(window,
                               options.record / fmt::format("frame_{:05d}.png", ++recorded));
      record_series(time_s);
    } else {
      window->Render();
    }
    if (next.valid())
      next.get();
  }

  /// The frame just drawn (at simulated `time`) as VTK files in `record`/series: each ligament's
  /// surface with its fiber strain and the femur in its pose (the tibia and fibula once), for
  /// frames.pvd.
  void record_series(double time)
  {
    const fs::path folder = options.record / "series";
    if (recorded == 1)
      ensure_directory(folder);
    for (std::size_t l = 0; l < surfaces.size(); ++l) {
      const std::string file = fmt::format("series/{}_{:05d}.vtp", names[l], recorded);
      write_vtk(surfaces[l], options.record / file);
      series.push_back({time, static_cast<int>(l), file});
    }
    vtkNew<vtkTransform> pose;
    pose->SetMatrix(femur->GetUserMatrix());
    vtkNew<vtkTransformPolyDataFilter> moved;
    moved->SetInputData(bones_shown[0]);
    moved->SetTransform(pose);
    moved->Update();
    const std::string femur_file = fmt::format("series/femur_{:05d}.vtp", recorded);
    write_vtk(moved->GetOutput(), options.record / femur_file);
    const int parts = static_cast<int>(surfaces.size());
    series.push_back({time, parts, femur_file});
    static constexpr std::array<const char*, 2> kFixed = {"tibia", "fibula"};
    for (std::size_t b = 1; b < bones_shown.size(); ++b) {
      const std::string file = fmt::format("series/{}.vtp", kFixed[b - 1]);
      if (recorded == 1)
        write_vtk(bones_shown[b], options.record / file);
      series.push_back({time, parts + static_cast<int>(b), file});
    }
  }

  void screenshot()
  {
    const fs::path folder = options.record.empty() ? fs::current_path() : options.record;
    const fs::path png = folder / fmt::format("screenshot_{:03d}.png", ++screenshots);
    render::write_window_png(window, png);
    log_info("view: " + png.string());
  }

  void write_csv() const
  {
    if (options.record.empty())
      return;
    std::string header = "frame,time_s,angle_deg,target_deg";
    for (const sim::LiveLigament& l : knee.last().ligaments)
      header += fmt::format(",{0}_femur_force_n,{0}_regional_peak_pct", l.name);
    header += ",solves,drawn_fps,simulated_fps,frame_wall_s,overlay\n";
    write_text_atomically(options.record / "frames.csv", header + csv);
    if (!series.empty())
      write_pvd(options.record / "frames.pvd", series);
  }
};

LiveWindow::LiveWindow(sim::LiveKnee& knee, const sim::KneeModel& bones,
                       const Eigen::Vector3d& view_axis, LiveWindowOptions options)
    : m_scene(std::make_unique<Scene>(knee, std::move(options)))
{
  Scene& s = *m_scene;
  if (!s.options.record.empty())
    ensure_directory(s.options.record);
  s.window->SetSize(s.options.width, s.options.height);
  s.window->SetMultiSamples(0); // FXAA smooths the edges; multisampled buffers read back black
  s.window->SetWindowName("ligsim view");
  s.renderer = render::add_white_renderer(s.window);
  s.renderer->UseFXAAOff(); // a full-screen pass per frame: a tenth of a frame on llvmpipe
  s.bones_shown.push_back(for_display(io::to_polydata(*bones.femur)));
  s.bones_shown.push_back(for_display(io::to_polydata(*bones.tibia)));
  if (bones.fibula)
    s.bones_shown.push_back(for_display(io::to_polydata(*bones.fibula)));
  s.femur = render::add_bone(s.renderer, s.bones_shown[0], 1.0);
  for (std::size_t b = 1; b < s.bones_shown.size(); ++b)
    render::add_bone(s.renderer, s.bones_shown[b], 1.0);
  s.colours->SetRange(0.0, s.options.strain_range_pct);
  s.colours->SetHueRange(0.667, 0.0);
  s.colours->Build();
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
  for (std::size_t l = 0; l < knee.ligament_count(); ++l) {
    const TetMesh& mesh = knee.ligament(l).body().mesh();
    auto surface = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> points;
    points->SetNumberOfPoints(mesh.V.rows());
    vtkNew<vtkCellArray> triangles;
    std::vector<int> elements;
    for (const auto& [face, element] : boundary_faces(mesh)) {
      triangles->InsertNextCell({face[0], face[1], face[2]});
      elements.push_back(element);
    }
    surface->SetPoints(points);
    surface->SetPolys(triangles);
    vtkNew<vtkDoubleArray> strain;
    strain->SetName("fiber strain (%)");
    strain->SetNumberOfValues(static_cast<vtkIdType>(elements.size()));
    surface->GetCellData()->SetScalars(strain);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(surface);
    mapper->SetLookupTable(s.colours);
    mapper->SetScalarModeToUseCellData();
    mapper->UseLookupTableScalarRangeOn();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    s.renderer->AddActor(actor);
    s.surfaces.push_back(surface);
    s.names.push_back(knee.ligament(l).name());
    s.face_elements.push_back(std::move(elements));
    low = low.cwiseMin(mesh.V.colwise().minCoeff().transpose());
    high = high.cwiseMax(mesh.V.colwise().maxCoeff().transpose());
  }
  render::add_scale_bar(s.renderer, s.colours, "fiber strain (%)", 14, 0.88, 0.1);
  s.overlay->GetTextProperty()->SetFontSize(16);
  s.overlay->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
  s.overlay->SetDisplayPosition(10, 60);
  s.renderer->AddViewProp(s.overlay);

  // A side view along the flexion axis, framed on the ligaments with room for the femur's turn.
  const Eigen::Vector3d centre = 0.5 * (low + high);
  const double size = std::max((high - low).norm(), 20.0);
  vtkCamera* camera = s.renderer->GetActiveCamera();
  camera->SetFocalPoint(centre.data());
  const Eigen::Vector3d eye = centre + 4.0 * size * view_axis.normalized();
  camera->SetPosition(eye.data());
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (std::abs(up.dot(view_axis.normalized())) > 0.9)
    up = Eigen::Vector3d::UnitY();
  camera->SetViewUp(up.data());
  const double half = 0.6 * size;
  std::array<double, 6> bounds = {centre.x() - half, centre.x() + half, centre.y() - half,
                                  centre.y() + half, centre.z() - half, centre.z() + half};
  s.renderer->ResetCamera(bounds.data());

  s.slider_look->SetMinimumValue(0.0);
  s.slider_look->SetMaximumValue(knee.max_angle_deg());
  s.slider_look->SetValue(0.0);
  s.slider_look->SetTitleText("flexion (deg)");
  s.slider_look->GetPoint1Coordinate()->SetCoordinateSystemToNormalizedDisplay();
  s.slider_look->GetPoint1Coordinate()->SetValue(0.1, 0.06);
  s.slider_look->GetPoint2Coordinate()->SetCoordinateSystemToNormalizedDisplay();
  s.slider_look->GetPoint2Coordinate()->SetValue(0.6, 0.06);
  s.update_actors();
  s.update_text();
  s.csv.clear(); // the settled state is frame 0, not a frame of the run
}

LiveWindow::~LiveWindow() = default;

int LiveWindow::run_script(const ViewScript& script)
{
  Scene& s = *m_scene;
  const int frames =
      std::max(1, static_cast<int>(std::ceil(script.end_s() / s.knee.time_step_s() - 1e-9)));
  Progress progress("view frames", static_cast<std::size_t>(frames));
  const double start = now_s();
  const auto target = [&](int f) { return script.at(f * s.knee.time_step_s()); };
  s.compute(target(1));
  for (int f = 1; f <= frames; ++f) {
    s.slider_look->SetValue(s.knee.last().target_deg);
    s.frame(f < frames ? std::optional<double>(target(f + 1)) : std::nullopt);
    progress.advance();
  }
  progress.finish();
  const double wall = now_s() - start;
  log_info(fmt::format("view: {} frames in {:.2f} s: {:.1f} frames/s drawn{}, {:.1f} computed "
                       "(the simulation alone)",
                       frames, wall, frames / wall, s.options.record.empty() ? "" : " and recorded",
                       frames / s.computing_s));
  s.write_csv();
  return frames;
}

void LiveWindow::run_interactive()
{
  Scene& s = *m_scene;
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(s.window);
  vtkNew<ViewStyle> style;
  style->on_key = [&](const std::string& key) {
    if (key == "Right" || key == "Up")
      s.target_deg = std::min(s.knee.max_angle_deg(), s.target_deg + kKeyStepDeg);
    else if (key == "Left" || key == "Down")
      s.target_deg = std::max(0.0, s.target_deg - kKeyStepDeg);
    else if (key == "r")
      s.target_deg = 0.0;
    else if (key == "c")
      s.knee.set_contact(!s.knee.contact());
    else if (key == "s")
      s.screenshot();
    else if (key == "q" || key == "Escape")
      interactor->TerminateApp();
    s.slider_look->SetValue(s.target_deg);
  };
  interactor->SetInteractorStyle(style);
  s.slider->SetInteractor(interactor);
  s.slider->SetRepresentation(s.slider_look);
  s.slider->SetAnimationModeToJump();
  s.slider->EnabledOn();
  vtkNew<vtkCallbackCommand> moved;
  moved->SetClientData(&s);
  moved->SetCallback([](vtkObject* caller, unsigned long, void* data, void*) {
    auto* scene = static_cast<Scene*>(data);
    auto* widget = static_cast<vtkSliderWidget*>(caller);
    scene->target_deg =
        static_cast<vtkSliderRepresentation*>(widget->GetRepresentation())->GetValue();
  });
  s.slider->AddObserver(vtkCommand::InteractionEvent, moved);
  vtkNew<vtkCallbackCommand> tick;
  tick->SetClientData(&s);
  tick->SetCallback([](vtkObject* caller, unsigned long, void* data, void*) {
    auto* scene = static_cast<Scene*>(data);
    try {
      if (scene->knee.last().frame == 0)
        scene->compute(scene->target_deg);
      scene->frame(scene->target_deg);
    } catch (const std::exception& e) {
      scene->error = e.what();
      static_cast<vtkRenderWindowInteractor*>(caller)->TerminateApp();
    }
  });
  interactor->AddObserver(vtkCommand::TimerEvent, tick);
  interactor->Initialize();
  interactor->CreateRepeatingTimer(1);
  s.window->Render();
  interactor->Start();
  s.write_csv();
  if (!s.error.empty())
    fail<SolverError>("{}", s.error);
}

} // namespace ligsim::cli
