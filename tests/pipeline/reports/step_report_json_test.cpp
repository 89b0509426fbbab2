/// A step's report as JSON: each counter under its own name (the indefinite and the saddle
/// iterations were once written under one key).

#include "pipeline/reports/step_report_json.hpp"

#include <gtest/gtest.h>

using ligsim::reports::to_json;
using ligsim::sim::StepReport;

TEST(StepReportJson, EachFigureIsWrittenUnderItsOwnName)
{
  StepReport step;
  step.step = 3;
  step.load_factor = 0.75;
  step.converged = true;
  step.iterations = 11;
  step.substeps = 2;
  step.cutbacks = 1;
  step.linear_iterations = 140;
  step.factorizations = 9;
  step.projected_elements = 17;
  step.indefinite_iterations = 4;
  step.line_search_backtracks = 6;
  step.saddle_iterations = 2;
  step.shifted_iterations = 5;
  step.negative_eigenvalues = 1;
  step.instability = "a buckling mode";
  const nlohmann::json json = to_json(step);
  EXPECT_EQ(json.at("step"), 3);
  EXPECT_EQ(json.at("load_factor"), 0.75);
  EXPECT_EQ(json.at("newton_iterations"), 11);
  EXPECT_EQ(json.at("cg_iterations"), 140);
  EXPECT_EQ(json.at("factorizations"), 9);
  EXPECT_EQ(json.at("projected_elements"), 17);
  EXPECT_EQ(json.at("indefinite_iterations"), 4);
  EXPECT_EQ(json.at("line_search_backtracks"), 6);
  EXPECT_EQ(json.at("saddle_iterations"), 2);
  EXPECT_EQ(json.at("shifted_iterations"), 5);
  EXPECT_EQ(json.at("negative_eigenvalues"), 1);
  EXPECT_EQ(json.at("instability"), "a buckling mode");
  EXPECT_FALSE(json.contains("floor")) << "said only where the step converged at the floor";
}
