#include "gproj/problems/run/construction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "gproj/problems/run/registry.h"
#include "gproj/problems/run/shared_options.h"

namespace gproj {
namespace {

TEST(SolverKindTest, NamesRoundTripAndAnyOtherNameIsRefused) {
  for (SolverKind kind : {SolverKind::kGuidedProjection, SolverKind::kCeres, SolverKind::kDirect})
    EXPECT_EQ(SolverKindFromName(SolverKindName(kind)), kind);
  EXPECT_STREQ(SolverKindName(SolverKind::kGuidedProjection), "gp");
  EXPECT_THROW(SolverKindFromName("ceres-bfgs"), std::invalid_argument);
  EXPECT_THROW(SolverKindFromName(""), std::invalid_argument);
}

TEST(ConstructionTest, FinishReportsTheMethodTheMeasuresAndTheTime) {
  const Construction build(ConstructionMethod::kClosedForm, "mirror images");
  const RunReport report = build.Finish({{"gap", 1.0}}, {{"gap", 0.0}}, true);
  EXPECT_EQ(report.solver, SolverKind::kDirect);
  EXPECT_EQ(report.method, "closed form");
  EXPECT_EQ(report.termination, "constructed directly (mirror images)");
  EXPECT_TRUE(report.converged);
  EXPECT_FALSE(report.failed);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(ValueOf(report.initial, "gap"), 1.0);
  EXPECT_EQ(ValueOf(report.final, "gap"), 0.0);
}

TEST(ConstructionTest, ABfgsFitIsReportedAsCeres) {
  const RunReport report =
      Construction(ConstructionMethod::kBfgs, "lengths").Finish({}, {{"error", 1e-3}}, false);
  EXPECT_EQ(report.solver, SolverKind::kCeres);
  EXPECT_EQ(report.method, "BFGS");
  EXPECT_FALSE(report.converged);
  EXPECT_FALSE(report.failed);
}

TEST(ConstructionTest, ANonFiniteMeasureFailsTheRun) {
  const RunReport report =
      Construction(ConstructionMethod::kJetFit, "jet fit").Finish({}, {{"x", NAN}}, true);
  EXPECT_TRUE(report.failed);
  EXPECT_FALSE(report.converged);
}

// Every solver choice in the registry is a value of SolverKind, by its name or by a word the
// problem documents (combescure's "propagation" for a direct solve).
TEST(SolverKindTest, TheRegistrysSolverChoicesAreSolverKinds) {
  int seen = 0;
  for (const ProblemSpec& spec : Registry::Builtin().problems())
    for (const OptionSpec& option : spec.options) {
      if (option.name != "solver" && !(spec.name == "combescure" && option.name == "method"))
        continue;
      ++seen;
      for (const std::string& choice : option.choices)
        if (choice != "propagation") EXPECT_NO_THROW(SolverKindFromName(choice)) << spec.name;
    }
  EXPECT_EQ(seen, 6);  // planarize, anet, hnet, weingarten, marionette, combescure
}

struct Settings {
  SolverKind solver = SolverKind::kDirect;
};

TEST(SolverKindTest, AChoiceOptionStoresTheKindAndItsDefaultIsTheSettingsOwn) {
  OptionSchema<Settings> schema;
  AddSolverChoice<Settings>(
      &schema, "method", "how", [](Settings& s) -> SolverKind& { return s.solver; },
      {{"propagation", SolverKind::kDirect}, {"gp", SolverKind::kGuidedProjection}});
  ASSERT_EQ(schema.specs().size(), 1u);
  EXPECT_EQ(schema.specs()[0].default_value, "propagation");
  EXPECT_EQ(schema.specs()[0].choices, (std::vector<std::string>{"propagation", "gp"}));
  EXPECT_EQ(schema.Apply({{"method", "gp"}}).solver, SolverKind::kGuidedProjection);
  EXPECT_EQ(schema.Apply({{"method", "propagation"}}).solver, SolverKind::kDirect);
  EXPECT_THROW(CompleteOptions(schema.specs(), {{"method", "ceres"}}), OptionError);
}

}  // namespace
}  // namespace gproj
