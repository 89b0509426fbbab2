#include "pipeline/render/line_plot_picture.hpp"

#include "common/error.hpp"
#include "pipeline/render/window_png.hpp"

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlotLine.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>

namespace ligsim::render {

namespace {

void style_text(vtkTextProperty* text, int size, bool bold)
{
  text->SetColor(0.0, 0.0, 0.0);
  text->SetFontSize(size);
  text->SetBold(bold);
}

} // namespace

void render_line_plot_png(const LinePlot& plot, const std::filesystem::path& png)
{
  if (plot.x.empty() || plot.x.size() != plot.y.size())
    fail("the plot '{}' needs as many y values as x values, at least one (got {} and {})",
         plot.title, plot.x.size(), plot.y.size());
  for (size_t i = 0; i < plot.x.size(); ++i)
    if (!std::isfinite(plot.x[i]) || !std::isfinite(plot.y[i]))
      fail("the plot '{}' has a non-finite point {} ({}, {})", plot.title, i, plot.x[i], plot.y[i]);

  vtkNew<vtkContextView> view;
  prepare_offscreen_window(view->GetRenderWindow(), plot.width, plot.height);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);

  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> xs;
  xs->SetName("x");
  vtkNew<vtkDoubleArray> ys;
  ys->SetName("y");
  for (size_t i = 0; i < plot.x.size(); ++i) {
    xs->InsertNextValue(plot.x[i]);
    ys->InsertNextValue(plot.y[i]);
  }
  table->AddColumn(xs);
  table->AddColumn(ys);

  const int font = std::max(10, plot.height / 36);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetShowLegend(false);
  chart->SetTitle(plot.title);
  style_text(chart->GetTitleProperties(), font + font / 3, true);
  auto* line = vtkPlotLine::SafeDownCast(chart->AddPlot(vtkChart::LINE));
  if (!line)
    fail<Error>("VTK could not make a line plot for '{}'", png.string());
  line->SetInputData(table, 0, 1);
  line->SetColor(0.10, 0.25, 0.60);
  line->SetWidth(std::max(2.0f, static_cast<float>(plot.height) / 300.0f));
  line->SetMarkerStyle(vtkPlotPoints::CIRCLE);
  line->SetMarkerSize(std::max(6.0f, static_cast<float>(plot.height) / 80.0f));

  vtkAxis* bottom = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* left = chart->GetAxis(vtkAxis::LEFT);
  bottom->SetTitle(plot.x_label);
  left->SetTitle(plot.y_label);
  for (vtkAxis* axis : {bottom, left}) {
    style_text(axis->GetTitleProperties(), font, false);
    style_text(axis->GetLabelProperties(), font - font / 5, false);
  }

  write_window_png(view->GetRenderWindow(), png);
}

} // namespace ligsim::render
