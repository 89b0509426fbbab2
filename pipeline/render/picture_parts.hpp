#pragma once
/// @brief The parts every knee picture shares: the white scene, the camera check, the bones, the
/// colour bar and the caption, so that the one-ligament and whole-knee pictures look alike.

#include "pipeline/render/ligament_picture.hpp"

#include <vtkSmartPointer.h>

#include <string>

class vtkActor;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;
class vtkScalarBarActor;
class vtkScalarsToColors;

namespace ligsim::render {

/// Throws InputError unless the camera has a finite focal point, a view direction, an up
/// direction across it and a positive view height.
void check_camera(const PictureCamera& camera);

/// A white, anti-aliased renderer added to `window`.
vtkSmartPointer<vtkRenderer> add_white_renderer(vtkRenderWindow* window);

/// A bone surface (mm) in kBoneColour at `opacity`.
vtkSmartPointer<vtkActor> add_bone(vtkRenderer* renderer, vtkPolyData* bone, double opacity);

/// The colour bar of `colours` at the right of the picture, from `left` (a fraction of the width)
/// `width` wide, in `font` points, on a light background where it overlaps the scene.
vtkSmartPointer<vtkScalarBarActor> add_scale_bar(vtkRenderer* renderer, vtkScalarsToColors* colours,
                                                 const char* title, int font, double left,
                                                 double width);

/// The caption at the top left of a picture `height` pixels high (nothing when empty).
void add_caption(vtkRenderer* renderer, const std::string& caption, int height);

} // namespace ligsim::render
