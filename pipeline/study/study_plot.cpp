#include "pipeline/study/study_plot.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "pipeline/render/window_png.hpp"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlotLine.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <array>
#include <cmath>

namespace ligsim::study {

namespace {

/// Distinct colours (RGB 0-255), cycled.
constexpr std::array<std::array<unsigned char, 3>, 8> kColours = {{{31, 119, 180},
                                                                   {214, 39, 40},
                                                                   {44, 160, 44},
                                                                   {255, 127, 14},
                                                                   {148, 103, 189},
                                                                   {140, 86, 75},
                                                                   {227, 119, 194},
                                                                   {90, 90, 90}}};

bool drawable(double value, bool log)
{
  return std::isfinite(value) && (!log || value > 0.0);
}

void style_text(vtkTextProperty* text, int size, bool bold)
{
  text->SetColor(0.0, 0.0, 0.0);
  text->SetFontSize(size);
  text->SetBold(bold);
}

void write_png(const PlotSpec& spec, const std::filesystem::path& png)
{
  constexpr int width = 1100, height = 750, font = 18;
  vtkNew<vtkContextView> view;
  render::prepare_offscreen_window(view->GetRenderWindow(), width, height);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(spec.title);
  style_text(chart->GetTitleProperties(), font + 4, true);
  chart->SetShowLegend(true);
  style_text(chart->GetLegend()->GetLabelProperties(), font - 4, false);
  std::size_t drawn = 0;
  for (const PlotSeries& series : spec.series) {
    vtkNew<vtkTable> table;
    vtkNew<vtkDoubleArray> xs;
    xs->SetName("x");
    vtkNew<vtkDoubleArray> ys;
    ys->SetName(series.name.c_str());
    for (std::size_t i = 0; i < series.x.size() && i < series.y.size(); ++i)
      if (drawable(series.x[i], spec.log_x) && drawable(series.y[i], spec.log_y)) {
        xs->InsertNextValue(series.x[i]);
        ys->InsertNextValue(series.y[i]);
      }
    if (xs->GetNumberOfTuples() == 0)
      continue;
    table->AddColumn(xs);
    table->AddColumn(ys);
    // A single point is drawn as a marker (VTK's line needs two).
    auto* line = vtkPlotPoints::SafeDownCast(
        chart->AddPlot(xs->GetNumberOfTuples() > 1 ? vtkChart::LINE : vtkChart::POINTS));
    if (!line)
      fail<Error>("VTK could not make a line plot for '{}'", png.string());
    line->SetInputData(table, 0, 1);
    const auto& colour = kColours[drawn % kColours.size()];
    line->SetColor(colour[0], colour[1], colour[2], 255);
    line->SetWidth(2.5f);
    line->SetMarkerStyle(vtkPlotPoints::CIRCLE);
    line->SetMarkerSize(8.0f);
    ++drawn;
  }
  vtkAxis* bottom = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* left = chart->GetAxis(vtkAxis::LEFT);
  bottom->SetTitle(spec.x_label);
  left->SetTitle(spec.y_label);
  bottom->SetLogScale(spec.log_x);
  left->SetLogScale(spec.log_y);
  for (vtkAxis* axis : {bottom, left}) {
    style_text(axis->GetTitleProperties(), font, false);
    style_text(axis->GetLabelProperties(), font - 3, false);
  }
  render::write_window_png(view->GetRenderWindow(), png);
}

} // namespace

void write_plot(const PlotSpec& spec, const std::filesystem::path& stem, bool png)
{
  bool any = false;
  for (const PlotSeries& series : spec.series)
    for (std::size_t i = 0; i < series.x.size() && i < series.y.size(); ++i)
      any = any || (drawable(series.x[i], spec.log_x) && drawable(series.y[i], spec.log_y));
  if (!any)
    fail("the plot '{}' has no point that can be drawn ({})", spec.title, stem.string());
  write_text_atomically(stem.string() + ".svg", svg_line_plot(spec));
  if (png)
    write_png(spec, stem.string() + ".png");
}

} // namespace ligsim::study
