#include "problems/marionette_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "input_error_test_util.h"

namespace gproj {
namespace {

const std::string kData = std::string(GPROJ_SOURCE_DIR) + "/examples/data/";

// The message of the InputError MakeMarionetteRun throws.
std::string ErrorOf(const MarionetteRunOptions& options) {
  return InputErrorOf([&] { MakeMarionetteRun(options); });
}

TEST(MarionetteRunTest, RefusesMissingOrConflictingInputs) {
  MarionetteRunOptions options;
  EXPECT_EQ(ErrorOf(options), "give a plan view (or --closed-strip FILE)");
  options.plan = kData + "marionette_plan_21x21.obj";
  EXPECT_EQ(ErrorOf(options),
            "give the guide curves (--row and --column heights, or --guides) or a target (--fit)");
  options.closed_strip = kData + "marionette_closed_strip.txt";
  EXPECT_EQ(ErrorOf(options), "give either a plan or --closed-strip, not both");
  options.closed_strip.clear();
  options.guides = kData + "marionette_valence6_guides.txt";
  options.row = {1, 2};
  EXPECT_EQ(ErrorOf(options), "give either --guides or --row/--column, not both");
}

TEST(MarionetteRunTest, ValenceSixGuidesLiftThePlanDirectlyAndByGuidedProjection) {
  MarionetteRunOptions options;
  options.plan = kData + "marionette_plan_valence6.obj";
  options.guides = kData + "marionette_valence6_guides.txt";
  for (const char* solver : {"direct", "gp"}) {
    options.solver = solver;
    const std::unique_ptr<MarionetteRun> run = MakeMarionetteRun(options);
    EXPECT_NE(run->Description().find("6 patches"), std::string::npos);
    const RunReport report = run->Run(nullptr);
    EXPECT_EQ(report.solver, solver);
    EXPECT_TRUE(report.converged);
    EXPECT_LE(ValueOf(report.final, run->ToleranceMeasure()), 1e-12);
    EXPECT_EQ(run->Result().n_vertices(), 181u);
    EXPECT_EQ(run->Facts()["design_dimension"].get<int>(), 31);
  }
}

TEST(MarionetteRunTest, ClosedStripReportsItsClosingLift) {
  MarionetteRunOptions options;
  options.closed_strip = kData + "marionette_closed_strip.txt";
  const std::unique_ptr<MarionetteRun> run = MakeMarionetteRun(options);
  const RunReport report = run->Run(nullptr);
  EXPECT_EQ(report.solver, "direct");
  EXPECT_TRUE(report.converged);
  EXPECT_LE(ValueOf(report.final, "max_planarity"), 1e-12);
  options.lift.tolerance = 1e-300;
  EXPECT_FALSE(MakeMarionetteRun(options)->Run(nullptr).converged);
}

}  // namespace
}  // namespace gproj
