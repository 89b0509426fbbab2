#include "common/error.hpp"
#include "pipeline/render/gl_driver.hpp"
#include "pipeline/render/ligament_picture.hpp"
#include "pipeline/render/line_plot_picture.hpp"
#include "pipeline/render/offscreen_display.hpp"
#include "pipeline/render/window_png.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCubeSource.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using ligsim::render::LigamentPicture;
using ligsim::render::LinePlot;
using ligsim::render::OffscreenDisplay;
using ligsim::render::PictureCamera;

namespace {

/// Sets (or unsets, with nullopt) an environment variable for one scope.
class ScopedEnv {
public:
  ScopedEnv(const char* name, std::optional<std::string> value)
      : m_name(name)
  {
    if (const char* old = std::getenv(name))
      m_old = old;
    if (value)
      ::setenv(name, value->c_str(), 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv()
  {
    if (m_old)
      ::setenv(m_name.c_str(), m_old->c_str(), 1);
    else
      ::unsetenv(m_name.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
  std::string m_name;
  std::optional<std::string> m_old;
};

/// True while a process with this id exists (zombies included: an unreaped Xvfb counts).
bool process_exists(pid_t pid)
{
  return fs::exists("/proc/" + std::to_string(pid));
}

/// True while a process with this id runs (exists and is not a zombie).
bool process_runs(pid_t pid)
{
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line))
    return false;
  const size_t name_end = line.rfind(')');
  return name_end != std::string::npos && name_end + 2 < line.size() && line[name_end + 2] != 'Z';
}

/// Xvfb processes whose parent is this process (running or not yet reaped).
int xvfb_children()
{
  int n = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line) || line.find("(Xvfb)") == std::string::npos)
      continue;
    std::istringstream fields(line.substr(line.rfind(')') + 2));
    char state = 0;
    pid_t parent = 0;
    fields >> state >> parent;
    n += parent == ::getpid() ? 1 : 0;
  }
  return n;
}

/// A fresh folder for one test's files, removed at the end of the test (set
/// LIGSIM_KEEP_TEST_PICTURES=1 to keep them for a look).
class TestDir {
public:
  explicit TestDir(const std::string& name)
      : m_path(fs::temp_directory_path() /
               ("ligsim_render_test_" + name + "_" + std::to_string(::getpid())))
  {
    fs::remove_all(m_path);
    fs::create_directories(m_path);
  }
  ~TestDir()
  {
    if (!std::getenv("LIGSIM_KEEP_TEST_PICTURES")) {
      std::error_code ignored;
      fs::remove_all(m_path, ignored);
    }
  }
  TestDir(const TestDir&) = delete;
  TestDir& operator=(const TestDir&) = delete;
  const fs::path& path() const { return m_path; }

private:
  fs::path m_path;
};

/// A box of tets along x with "strain_energy_density" = energy_per_mm * (centroid x) and fibers
/// along x.
vtkSmartPointer<vtkUnstructuredGrid>
box_ligament(const Eigen::Vector3i& cells, const Eigen::Vector3d& size_mm, double energy_per_mm)
{
  const ligsim::TetMesh mesh = ligsim::sim::structured_box_mesh(cells, size_mm);
  vtkNew<vtkPoints> points;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    points->InsertNextPoint(mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2));
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  vtkNew<vtkDoubleArray> energy;
  energy->SetName("strain_energy_density");
  vtkNew<vtkDoubleArray> fiber;
  fiber->SetName("fiber_direction");
  fiber->SetNumberOfComponents(3);
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    const vtkIdType ids[4] = {mesh.T(e, 0), mesh.T(e, 1), mesh.T(e, 2), mesh.T(e, 3)};
    grid->InsertNextCell(VTK_TETRA, 4, ids);
    double x = 0.0;
    for (int k = 0; k < 4; ++k)
      x += mesh.V(mesh.T(e, k), 0) / 4.0;
    energy->InsertNextValue(energy_per_mm * x);
    fiber->InsertNextTuple3(1.0, 0.0, 0.0);
  }
  grid->GetCellData()->AddArray(energy);
  grid->GetCellData()->AddArray(fiber);
  return grid;
}

struct Png {
  vtkSmartPointer<vtkImageData> image;
  int width = 0, height = 0;
  /// RGB at column `x`, row `y` counted from the top.
  std::array<int, 3> rgb(int x, int y) const
  {
    const auto* p =
        static_cast<const unsigned char*>(image->GetScalarPointer(x, height - 1 - y, 0));
    return {p[0], p[1], p[2]};
  }
  /// How many pixels of the (2 r + 1)^2 patch around (x, y) satisfy `test`.
  template <class Test> int count(int x, int y, int r, Test test) const
  {
    int n = 0;
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
        n += test(rgb(x + dx, y + dy)) ? 1 : 0;
    return n;
  }
};

Png read_png(const fs::path& file)
{
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  Png png;
  png.image = reader->GetOutput();
  png.width = png.image->GetDimensions()[0];
  png.height = png.image->GetDimensions()[1];
  return png;
}

std::string rgb_text(const std::array<int, 3>& c)
{
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
         ")";
}

/// Only the target and no temporary sibling in `dir`.
size_t file_count(const fs::path& dir)
{
  size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir))
    ++n;
  return n;
}

} // namespace

TEST(OffscreenDisplay, StartsXvfbTwiceAndLeavesNoServer)
{
  ScopedEnv no_display("DISPLAY", std::nullopt);
  for (int round = 0; round < 2; ++round) {
    pid_t pid = 0;
    {
      OffscreenDisplay display;
      ASSERT_TRUE(display.started_server()) << "round " << round;
      pid = display.server_pid();
      ASSERT_GT(pid, 0);
      EXPECT_TRUE(process_exists(pid));
      ASSERT_NE(std::getenv("DISPLAY"), nullptr);
      EXPECT_EQ(std::getenv("DISPLAY"), display.display());
      EXPECT_EQ(display.display().rfind(':', 0), 0u) << display.display();

      // A second one finds the first one's server answering and starts nothing.
      OffscreenDisplay nested;
      EXPECT_FALSE(nested.started_server());
      EXPECT_EQ(nested.display(), display.display());
    }
    EXPECT_FALSE(process_exists(pid)) << "Xvfb " << pid << " is still there (or unreaped)";
    EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
  }
}

// libGLX_mesa unloads the driver when a window closes its X connection; LeakSanitizer then
// reports what only the driver's globals pointed to (the sanitizer suite's LigamentPicture and
// FlexionCli failures).
TEST(OffscreenDisplay, GlDriverStaysLoadedAfterItsWindowCloses)
{
  OffscreenDisplay display;
  const TestDir test_dir("driver");
  std::vector<std::string> while_open;
  {
    vtkNew<vtkRenderWindow> window;
    ligsim::render::prepare_offscreen_window(window, 64, 64);
    vtkNew<vtkRenderer> renderer;
    window->AddRenderer(renderer);
    ligsim::render::write_window_png(window, test_dir.path() / "empty.png");
    while_open = ligsim::render::loaded_gl_drivers();
  }
  if (while_open.empty())
    GTEST_SKIP() << "VTK renders without a Mesa DRI driver here";
  const std::vector<std::string> after = ligsim::render::loaded_gl_drivers();
  for (const std::string& driver : while_open)
    EXPECT_NE(std::find(after.begin(), after.end(), driver), after.end())
        << driver << " was unloaded";
}

TEST(OffscreenDisplay, ServerStopsWhenAnExceptionUnwinds)
{
  ScopedEnv no_display("DISPLAY", std::nullopt);
  pid_t pid = 0;
  EXPECT_THROW(
      {
        OffscreenDisplay display;
        pid = display.server_pid();
        ligsim::fail("a picture failed");
      },
      ligsim::InputError);
  ASSERT_GT(pid, 0);
  EXPECT_FALSE(process_exists(pid));
}

TEST(OffscreenDisplay, ServerStopsWhenItsOwnerIsKilled)
{
  // A child process starts the server, reports its pid and dies by SIGKILL (no destructor).
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(fds[0]);
    ::unsetenv("DISPLAY");
    try {
      OffscreenDisplay display;
      const pid_t server = display.server_pid();
      if (::write(fds[1], &server, sizeof server) != sizeof server)
        ::_exit(1);
      ::raise(SIGKILL); // with the display alive
    } catch (...) {
    }
    ::_exit(1);
  }
  ::close(fds[1]);
  pid_t server = 0;
  const bool reported = ::read(fds[0], &server, sizeof server) == sizeof server;
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(reported) << "the child could not start Xvfb";
  EXPECT_TRUE(WIFSIGNALED(status));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (process_runs(server) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_FALSE(process_runs(server)) << "Xvfb " << server << " outlived its owner";
}

TEST(OffscreenDisplay, MissingOpenGLIsAClearErrorAndLeavesNoServer)
{
  // Mesa then offers OpenGL 2.1 only, too little for VTK (which would crash in its first render).
  ScopedEnv old_gl("MESA_GL_VERSION_OVERRIDE", std::string("2.1"));
  ScopedEnv no_display("DISPLAY", std::nullopt);
  try {
    OffscreenDisplay display;
    FAIL() << "expected an Error";
  } catch (const ligsim::Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("OpenGL 3.2"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
  EXPECT_EQ(xvfb_children(), 0);
}

TEST(OffscreenDisplay, FakeXvfbThatFailsIsReported)
{
  const TestDir test_dir("fake_xvfb");
  const fs::path& dir = test_dir.path();
  {
    std::ofstream script(dir / "Xvfb");
    script << "#!/bin/sh\necho 'Fatal server error: no screens found' >&2\nexit 1\n";
  }
  fs::permissions(dir / "Xvfb", fs::perms::owner_all);
  ScopedEnv no_display("DISPLAY", std::nullopt);
  ScopedEnv path("PATH", dir.string());
  try {
    OffscreenDisplay display;
    FAIL() << "expected an InputError";
  } catch (const ligsim::InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no screens found"), std::string::npos) << message;
  }
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
}

TEST(OffscreenDisplay, DisplayThatDoesNotAnswerIsReplacedAndRestored)
{
  ScopedEnv dead("DISPLAY", std::string(":917"));
  pid_t pid = 0;
  {
    OffscreenDisplay display;
    EXPECT_TRUE(display.started_server());
    EXPECT_NE(display.display(), ":917");
    pid = display.server_pid();
  }
  EXPECT_FALSE(process_exists(pid));
  ASSERT_NE(std::getenv("DISPLAY"), nullptr);
  EXPECT_EQ(std::string(std::getenv("DISPLAY")), ":917");
}

TEST(OffscreenDisplay, MissingXvfbNamesThePackage)
{
  const TestDir empty("empty_path");
  ScopedEnv no_display("DISPLAY", std::nullopt);
  ScopedEnv path("PATH", empty.path().string());
  try {
    OffscreenDisplay display;
    FAIL() << "expected an InputError";
  } catch (const ligsim::InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("apt-get install xvfb"), std::string::npos) << message;
    EXPECT_NE(message.find("--no-images"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);
}

TEST(LigamentPicture, GreenLowRedHighWithBoneOnWhite)
{
  OffscreenDisplay display;
  // 20 x 4 x 4 mm along x, 1 mm hexes; energy 0 .. 1 MPa along x.
  const auto ligament = box_ligament({20, 4, 4}, {20.0, 4.0, 4.0}, 1.0 / 20.0);
  vtkNew<vtkCubeSource> bone;
  bone->SetBounds(2.0, 18.0, -10.0, -4.0, 0.0, 4.0);
  bone->Update();

  LigamentPicture picture;
  picture.ligament = ligament;
  picture.bones = {bone->GetOutput()};
  picture.caption = "flexion 45 deg";
  picture.width = 400;
  picture.height = 300;
  // Looking down -z at (10, 0, 2), 30 mm high: 10 px/mm, x = 200 + 10 (X - 10), row = 150 - 10 Y.
  PictureCamera camera;
  camera.focal_point_mm = {10.0, 0.0, 2.0};
  camera.view_direction = {0.0, 0.0, -1.0};
  camera.up = {0.0, 1.0, 0.0};
  camera.view_height_mm = 30.0;

  const TestDir test_dir("ligament");
  const fs::path& dir = test_dir.path();
  const fs::path file = dir / "flexion_045.png";
  ligsim::render::render_ligament_png(picture, camera, file);
  ASSERT_TRUE(fs::exists(file));
  EXPECT_EQ(file_count(dir), 1u);

  const Png png = read_png(file);
  ASSERT_EQ(png.width, 400);
  ASSERT_EQ(png.height, 300);
  const int r = 4, patch = (2 * r + 1) * (2 * r + 1);
  auto greenish = [](const std::array<int, 3>& c) { return c[1] > c[0] + 60; };
  auto reddish = [](const std::array<int, 3>& c) { return c[0] > c[1] + 60; };
  auto white = [](const std::array<int, 3>& c) { return c[0] > 250 && c[1] > 250 && c[2] > 250; };
  auto bone_like = [](const std::array<int, 3>& c) {
    const std::array<double, 3> expected = {255 * ligsim::render::kBoneColour.x(),
                                            255 * ligsim::render::kBoneColour.y(),
                                            255 * ligsim::render::kBoneColour.z()};
    for (int k = 0; k < 3; ++k)
      if (std::abs(c[k] - expected[k]) > 25)
        return false;
    return true;
  };
  // Low end X = 1 mm, high end X = 19 mm, Y = 2 mm; the strokes cover a minority of the pixels.
  EXPECT_GT(png.count(110, 130, r, greenish), patch / 2) << rgb_text(png.rgb(110, 130));
  EXPECT_GT(png.count(290, 130, r, reddish), patch / 2) << rgb_text(png.rgb(290, 130));
  EXPECT_GT(png.count(200, 220, r, bone_like), patch * 9 / 10) << rgb_text(png.rgb(200, 220));
  EXPECT_EQ(png.count(200, 50, r, white), patch) << rgb_text(png.rgb(200, 50));
  EXPECT_EQ(png.count(60, 250, r, white), patch) << rgb_text(png.rgb(60, 250));
  // The fiber strokes are there, along x: dark pixels on the ligament, in horizontal runs.
  auto dark = [&](int x, int y) {
    const auto c = png.rgb(x, y);
    return c[0] < 120 && c[1] < 120 && c[2] < 120;
  };
  int dark_pixels = 0, along_x = 0, along_y = 0;
  for (int x = 100; x < 300; ++x)
    for (int y = 112; y < 148; ++y)
      if (dark(x, y)) {
        ++dark_pixels;
        along_x += dark(x + 1, y) ? 1 : 0;
        along_y += dark(x, y + 1) ? 1 : 0;
      }
  EXPECT_GT(dark_pixels, 60);
  EXPECT_GT(along_x, 3 * along_y);
}

TEST(LigamentPicture, MissingArrayOrBadCameraIsAnInputError)
{
  const auto ligament = box_ligament({2, 1, 1}, {4.0, 1.0, 1.0}, 1.0);
  const TestDir dir("bad_input");
  const fs::path file = dir.path() / "x.png";
  LigamentPicture picture;
  picture.ligament = ligament;
  PictureCamera camera;
  camera.up = camera.view_direction;
  EXPECT_THROW(ligsim::render::render_ligament_png(picture, camera, file), ligsim::InputError);

  ligament->GetCellData()->RemoveArray("fiber_direction");
  EXPECT_THROW(ligsim::render::render_ligament_png(picture, PictureCamera{}, file),
               ligsim::InputError);
  EXPECT_FALSE(fs::exists(file));
}

TEST(LinePlot, RightSizeAndNotBlank)
{
  OffscreenDisplay display;
  LinePlot plot;
  plot.title = "MCL strain energy";
  plot.x_label = "flexion (deg)";
  plot.y_label = "strain energy (mJ)";
  for (int a = 0; a <= 90; a += 15) {
    plot.x.push_back(a);
    plot.y.push_back(0.01 * a * a);
  }
  plot.width = 400;
  plot.height = 300;
  const TestDir test_dir("plot");
  const fs::path& dir = test_dir.path();
  const fs::path file = dir / "energy.png";
  ligsim::render::render_line_plot_png(plot, file);
  EXPECT_EQ(file_count(dir), 1u);

  const Png png = read_png(file);
  ASSERT_EQ(png.width, 400);
  ASSERT_EQ(png.height, 300);
  std::set<std::array<int, 3>> colours;
  int bluish = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const auto c = png.rgb(x, y);
      colours.insert(c);
      bluish += (c[2] > c[0] + 60) ? 1 : 0;
    }
  EXPECT_GT(colours.size(), 2u);
  EXPECT_GT(bluish, 200) << "the line is missing";
  EXPECT_EQ(png.rgb(2, png.height - 3), (std::array<int, 3>{255, 255, 255}));
}

TEST(LinePlot, MismatchedDataIsAnInputError)
{
  LinePlot plot;
  plot.x = {0.0, 1.0};
  plot.y = {0.0};
  const TestDir dir("bad_plot");
  EXPECT_THROW(ligsim::render::render_line_plot_png(plot, dir.path() / "p.png"),
               ligsim::InputError);
}

TEST(LigamentPicture, TenThousandTetsFullSize)
{
  OffscreenDisplay display;
  // 20 x 10 x 10 hexes x 5 = 10,000 tets.
  const auto ligament = box_ligament({20, 10, 10}, {40.0, 8.0, 8.0}, 0.05);
  LigamentPicture picture;
  picture.ligament = ligament;
  picture.caption = "flexion 90 deg";
  PictureCamera camera;
  camera.focal_point_mm = {20.0, 4.0, 4.0};
  camera.view_direction = Eigen::Vector3d(-1.0, -1.0, -2.0).normalized();
  camera.up = {0.0, 1.0, 0.0};
  camera.view_height_mm = 40.0;
  const TestDir dir("large");
  const fs::path file = dir.path() / "large.png";
  const auto start = std::chrono::steady_clock::now();
  ligsim::render::render_ligament_png(picture, camera, file);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("render_seconds", std::to_string(seconds));
  const Png png = read_png(file);
  EXPECT_EQ(png.width, 1200);
  EXPECT_EQ(png.height, 900);
}
