#pragma once
/// @brief The live windows' mouse and keys: VTK's trackball camera for the mouse, the keys
/// handed to the window's own handler instead of VTK's letters (wireframe, stereo, quit), and the
/// left button handed to a window that takes it (a hand pulling a membrane) where it does.

#include <vtkInteractorStyleTrackballCamera.h>

#include <functional>
#include <string>

namespace ligsim::cli {

class ViewStyle : public vtkInteractorStyleTrackballCamera {
public:
  static ViewStyle* New();
  // clang-format off
  vtkTypeMacro(ViewStyle, vtkInteractorStyleTrackballCamera)
      // clang-format on

      /// Called with the key's symbol ("Right", "s", "space").
      std::function<void(const std::string&)> on_key;
  /// Called with the display position of a left button press; true takes the drag (then
  /// on_drag follows the mouse and on_release ends it) instead of turning the camera.
  std::function<bool(int x, int y)> on_press;
  std::function<void(int x, int y)> on_drag;
  std::function<void()> on_release;

  void OnKeyPress() override;
  void OnChar() override {}
  void OnLeftButtonDown() override;
  void OnMouseMove() override;
  void OnLeftButtonUp() override;

private:
  bool m_dragging = false;
};

} // namespace ligsim::cli
