#pragma once
/// @brief The live windows' mouse and keys: VTK's trackball camera for the mouse, and the keys
/// handed to the window's own handler instead of VTK's letters (wireframe, stereo, quit).

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

  void OnKeyPress() override;
  void OnChar() override {}
};

} // namespace ligsim::cli
