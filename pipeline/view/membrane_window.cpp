#include "pipeline/view/membrane_window.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "pipeline/render/membrane_frame.hpp"
#include "pipeline/render/picture_parts.hpp"
#include "pipeline/render/window_png.hpp"
#include "pipeline/view/view_style.hpp"
#include "sim/membrane/output/tear_path.hpp"

#include <fmt/format.h>
#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataSetMapper.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnstructuredGrid.h>

#include <chrono>
#include <cmath>

namespace ligsim::cli {

namespace {

using membrane::TearSimulation;
using membrane::Vec2;

struct Player {
  TearSimulation& simulation;
  const MembraneWindowOptions& options;
  vtkNew<vtkRenderWindow> window;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkNew<vtkDataSetMapper> mapper;
  vtkNew<vtkLookupTable> colours;
  vtkNew<vtkTextActor> overlay;
  int drawn = 0;
  int screenshots = 0;
  bool paused = false;
  bool hand_done = false; ///< the scripted hand has let go
  double stepping_s = 0.0;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

  Player(TearSimulation& played, const MembraneWindowOptions& chosen)
      : simulation(played)
      , options(chosen)
  {
    window->SetSize(options.width, options.width);
    window->SetMultiSamples(0);
    window->SetWindowName("ligsim view");
    renderer = render::add_white_renderer(window);
    renderer->UseFXAAOff();
    colours->SetRange(0.0, 1.0); // the criterion tears at 1
    colours->SetHueRange(0.15, 0.0);
    colours->SetSaturationRange(0.1, 1.0);
    colours->SetValueRange(1.0, 0.8);
    colours->Build();
    mapper->SetLookupTable(colours);
    mapper->SetScalarModeToUseCellFieldData();
    mapper->SelectColorArray("criterion");
    mapper->UseLookupTableScalarRangeOn();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    render::add_scale_bar(renderer, colours, "tearing criterion c", 14, 0.86, 0.12);
    overlay->GetTextProperty()->SetFontSize(16);
    overlay->GetTextProperty()->SetColor(0.1, 0.1, 0.1);
    overlay->SetDisplayPosition(10, 10);
    renderer->AddViewProp(overlay);
    show();
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetPosition(0.0, 0.0, 1.0);
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    renderer->ResetCamera();
    camera->SetParallelScale(camera->GetParallelScale() * 1.3); // room for the pulled sides
  }

  /// The membrane as it is now, with the overlay's figures.
  void show()
  {
    const membrane::TearMetrics& metrics = simulation.metrics();
    mapper->SetInputData(render::membrane_frame(
        simulation,
        simulation.tearing().element_criterion(simulation.mesh(), simulation.elements())));
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& hand = simulation.hand();
    const std::string held =
        hand ? fmt::format("\nhand at ({:.2f}, {:.2f}) mm, {} nodes", hand->position().x(),
                           hand->position().y(), hand->nodes().size())
             : "";
    overlay->SetInput(
        fmt::format("{}: {:.3f} s, step {}\n{} tearing events, {} elements, load {:.3g} N{}\n"
                    "{:.2f} ms per step | {:.0f} frames/s drawn{}",
                    simulation.scene().name, simulation.time_s(), metrics.steps,
                    metrics.events.size(), simulation.mesh().triangle_count(),
                    simulation.current_load_n(), held,
                    metrics.steps > 0 ? 1000.0 * stepping_s / metrics.steps : 0.0,
                    wall > 0.0 ? drawn / wall : 0.0,
                    simulation.finished() ? " | finished" : (paused ? " | paused" : ""))
            .c_str());
  }

  /// The scripted hand for the step about to be taken: it takes the sheet at the script's start,
  /// follows it, and lets go after its end.
  void follow_script()
  {
    if (!options.hand || hand_done)
      return;
    const ViewScript& script = *options.hand;
    const double t = simulation.time_s() + simulation.scene().solver.time_step_s;
    if (t < script.start_s())
      return;
    const Vec2 at(script.at(t, 0), script.at(t, 1));
    if (t > script.end_s()) {
      simulation.release();
      hand_done = true;
    } else if (!simulation.hand()) {
      if (!simulation.grab(at, kHandRadiusMm, kHandPickMm, kHandSpeedMmPerS))
        fail("view: the script's hand at ({}, {}) mm at {} s is not on the sheet (no free node "
             "within {} mm)",
             at.x(), at.y(), t, kHandPickMm);
    } else {
      simulation.move_hand(at);
    }
  }

  /// The sheet's point under the display position (x, y): where the ray through it meets the
  /// sheet's plane, z = 0 (the view may have been turned).
  Vec2 point_at(int x, int y)
  {
    const auto world_at = [&](double depth) {
      renderer->SetDisplayPoint(x, y, depth);
      renderer->DisplayToWorld();
      const double* w = renderer->GetWorldPoint();
      return Eigen::Vector3d(w[0] / w[3], w[1] / w[3], w[2] / w[3]);
    };
    const Eigen::Vector3d near = world_at(0.0), far = world_at(1.0);
    const double across = far.z() - near.z();
    const double t = std::abs(across) > 1e-12 ? -near.z() / across : 0.0;
    const Eigen::Vector3d on_sheet = near + t * (far - near);
    return Vec2(on_sheet.x(), on_sheet.y());
  }

  /// `frame_every` steps (fewer at the end), then a drawn (and recorded) frame.
  void advance()
  {
    if (paused || simulation.finished())
      return;
    const auto begin = std::chrono::steady_clock::now();
    for (int s = 0; s < simulation.scene().run.frame_every && !simulation.finished(); ++s) {
      follow_script();
      simulation.step();
    }
    stepping_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    ++drawn;
    show();
    if (!options.record.empty())
      render::write_window_png(window, options.record / fmt::format("frame_{:05d}.png", drawn));
    else
      window->Render();
  }
};

} // namespace

int play_membrane(TearSimulation& simulation, const MembraneWindowOptions& options)
{
  if (!options.record.empty())
    ensure_directory(options.record);
  Player player(simulation, options);
  if (!options.interactive) {
    Progress progress("view steps", static_cast<std::size_t>(simulation.scene().run.max_steps));
    int done = 0;
    while (!simulation.finished()) {
      player.advance();
      progress.advance(static_cast<std::size_t>(simulation.metrics().steps - done));
      done = simulation.metrics().steps;
    }
    progress.finish();
  } else {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(player.window);
    vtkNew<ViewStyle> style;
    style->on_key = [&](const std::string& key) {
      if (key == "space")
        player.paused = !player.paused;
      else if (key == "s") {
        const std::filesystem::path folder =
            options.record.empty() ? std::filesystem::current_path() : options.record;
        const auto png = folder / fmt::format("screenshot_{:03d}.png", ++player.screenshots);
        render::write_window_png(player.window, png);
        log_info("view: " + png.string());
      } else if (key == "q" || key == "Escape")
        interactor->TerminateApp();
    };
    style->on_press = [&](int x, int y) {
      return simulation.grab(player.point_at(x, y), kHandRadiusMm, kHandPickMm, kHandSpeedMmPerS);
    };
    style->on_drag = [&](int x, int y) { simulation.move_hand(player.point_at(x, y)); };
    style->on_release = [&] { simulation.release(); };
    interactor->SetInteractorStyle(style);
    vtkNew<vtkCallbackCommand> tick;
    tick->SetClientData(&player);
    tick->SetCallback([](vtkObject*, unsigned long, void* data, void*) {
      static_cast<Player*>(data)->advance();
    });
    interactor->AddObserver(vtkCommand::TimerEvent, tick);
    interactor->Initialize();
    interactor->CreateRepeatingTimer(1);
    player.window->Render();
    interactor->Start();
  }
  if (!options.record.empty())
    write_text_atomically(options.record / "tear_path.csv",
                          membrane::tear_path_csv(simulation.metrics()));
  log_info(fmt::format("view: {}: {} steps, {} tearing events, {} frames drawn",
                       simulation.scene().name, simulation.metrics().steps,
                       simulation.metrics().events.size(), player.drawn));
  return player.drawn;
}

} // namespace ligsim::cli
