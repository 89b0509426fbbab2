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

} // namespace ligsim::cli
