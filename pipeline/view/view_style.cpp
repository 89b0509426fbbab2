#include "pipeline/view/view_style.hpp"

#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>

namespace ligsim::cli {

vtkStandardNewMacro(ViewStyle);

void ViewStyle::OnKeyPress()
{
  if (on_key)
    on_key(Interactor->GetKeySym() ? Interactor->GetKeySym() : "");
}

void ViewStyle::OnLeftButtonDown()
{
  const int* at = Interactor->GetEventPosition();
  m_dragging = on_press && on_press(at[0], at[1]);
  if (!m_dragging)
    vtkInteractorStyleTrackballCamera::OnLeftButtonDown();
}

void ViewStyle::OnMouseMove()
{
  if (!m_dragging) {
    vtkInteractorStyleTrackballCamera::OnMouseMove();
    return;
  }
  const int* at = Interactor->GetEventPosition();
  if (on_drag)
    on_drag(at[0], at[1]);
}

void ViewStyle::OnLeftButtonUp()
{
  if (!m_dragging) {
    vtkInteractorStyleTrackballCamera::OnLeftButtonUp();
    return;
  }
  m_dragging = false;
  if (on_release)
    on_release();
}

} // namespace ligsim::cli
