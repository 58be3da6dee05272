#include "gproj/problems/marionette/marionette_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "input_error_test_util.h"

namespace gproj::marionette {
namespace {

const std::string kData = std::string(GPROJ_SOURCE_DIR) + "/examples/data/";

// The message of the InputError MakeMarionetteRun throws.
std::string ErrorOf(const MarionetteRunOptions& options) {
  return InputErrorOf([&] { MakeMarionetteRun(options); });
}

TEST(MarionetteRunTest, RefusesMissingOrConflictingInputs) {
  MarionetteRunOptions options;
  EXPECT_EQ(ErrorOf(options), "give a plan view (or `closed_strip`)");
  options.plan = kData + "marionette_plan_21x21.obj";
  EXPECT_EQ(ErrorOf(options),
            "give the guide curves (`row` and `column` heights, or `guides`) or a target (`fit`, "
            "`fit_heights`)");
  options.closed_strip = kData + "marionette_closed_strip.txt";
  EXPECT_EQ(ErrorOf(options), "give either a plan or `closed_strip`, not both");
  options.closed_strip.clear();
  options.fit = kData + "marionette_plan_21x21.obj";
  options.row = {1, 2};
  EXPECT_EQ(ErrorOf(options),
            "give either a target (`fit`, `fit_heights`) or `row`/`column`, not both");
  options.fit_heights = kData + "marionette_valence6_guides.txt";
  EXPECT_EQ(ErrorOf(options), "give either `fit` or `fit_heights`, not both");
  options.fit_heights.clear();
  options.fit.clear();
  options.guides = kData + "marionette_valence6_guides.txt";
  options.row = {1, 2};
  EXPECT_EQ(ErrorOf(options), "give either `guides` or `row`/`column`, not both");
}

// The plan and the guides held in memory give the same run as their files; the names stand
// for the paths in messages.
TEST(MarionetteRunTest, InputsFromMemoryEqualInputsFromFiles) {
  MarionetteRunOptions files;
  files.plan = kData + "marionette_plan_valence6.obj";
  files.guides = kData + "marionette_valence6_guides.txt";
  MarionetteRunOptions memory;
  memory.plan = "plan";
  memory.plan_mesh = ReadMesh(files.plan);
  memory.guides = "guides";
  std::ifstream in(files.guides);
  memory.guides_text = std::string(std::istreambuf_iterator<char>(in), {});
  const std::unique_ptr<MarionetteRun> a = MakeMarionetteRun(files);
  const std::unique_ptr<MarionetteRun> b = MakeMarionetteRun(memory);
  ASSERT_TRUE(a->Run(nullptr).converged);
  ASSERT_TRUE(b->Run(nullptr).converged);
  const PolyMesh ra = a->Result(), rb = b->Result();
  ASSERT_EQ(ra.n_vertices(), rb.n_vertices());
  for (const auto v : ra.vertices()) EXPECT_EQ(ra.point(v), rb.point(v)) << "vertex " << v.idx();
  EXPECT_EQ(b->Facts()["guides"], "guides");

  memory.guides_text = "guide 0 1 nonsense\n";
  EXPECT_EQ(ErrorOf(memory).rfind("guides:1: ", 0), 0u) << ErrorOf(memory);
  PolyMesh triangle;
  triangle.add_face(triangle.add_vertex({0, 0, 0}), triangle.add_vertex({1, 0, 0}),
                    triangle.add_vertex({0, 1, 0}));
  memory.plan_mesh = triangle;
  // A plan with polygons other than quads takes prescribed heights, not guides (002 §4.2).
  EXPECT_EQ(ErrorOf(memory),
            "plan: a plan of polygons is lifted from prescribed heights (`hold` VERTEX:HEIGHT) and "
            "fairness; guides, rows, columns and fits need quads");
}

// A closed strip whose outer ring runs against the inner one has self-crossing plan quads: refused
// like a folded grid plan, lifted with a warning when allowed.
TEST(MarionetteRunTest, FoldedClosedStripIsRefusedUnlessAllowed) {
  const auto path = std::filesystem::temp_directory_path() / "gproj_folded_strip.txt";
  {
    std::ofstream out(path);
    for (int i = 0; i < 12; ++i) {
      const double a = 2 * M_PI * i / 12, b = (i < 3 ? -1.0 : 1.0) * a;
      out << std::cos(a) << " " << std::sin(a) << " " << 0.1 * std::sin(3 * a) << " "
          << 2 * std::cos(b) << " " << 2 * std::sin(b) << "\n";
    }
  }
  MarionetteRunOptions options;
  options.closed_strip = path.string();
  const std::string error = ErrorOf(options);
  EXPECT_NE(error.find("gproj_folded_strip.txt: "), std::string::npos) << error;
  EXPECT_NE(error.find("quads of the plan view overlap or are not convex"), std::string::npos)
      << error;
  options.allow_folded_plan = true;
  EXPECT_NE(MakeMarionetteRun(options)->Description().find("warning: "), std::string::npos);
}

TEST(MarionetteRunTest, FoldedPlanViewIsRefusedNamingTheFacesUnlessAllowed) {
  // A 6 × 6 plan grid with vertex 14 = (2, 2) pushed across its neighbours to (3.6, 2.3).
  const auto path = std::filesystem::temp_directory_path() / "gproj_folded_plan.obj";
  {
    std::ofstream out(path);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        out << "v " << (i * 6 + j == 14 ? 3.6 : i) << " " << (i * 6 + j == 14 ? 2.3 : j) << " 0\n";
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j)
        out << "f " << i * 6 + j + 1 << " " << (i + 1) * 6 + j + 1 << " " << (i + 1) * 6 + j + 2
            << " " << i * 6 + j + 2 << "\n";
  }
  MarionetteRunOptions options;
  options.plan = path.string();
  options.row = {0, 0.1, 0.2, 0.3, 0.4, 0.5};
  options.column = {0, 0.2, 0.3, 0.1, 0.2, 0.4};
  const std::string error = ErrorOf(options);
  EXPECT_NE(error.find("gproj_folded_plan.obj: 2 quads of the plan view overlap or are not "
                       "convex in x, y: faces 11, 12"),
            std::string::npos)
      << error;
  options.allow_folded_plan = true;
  const std::unique_ptr<MarionetteRun> run = MakeMarionetteRun(options);
  EXPECT_NE(run->Description().find("warning: 2 quads"), std::string::npos) << run->Description();
  EXPECT_TRUE(run->Run(nullptr).converged);
  options.plan = kData + "marionette_plan_21x21.obj";  // a valid plan passes without a word
  options.row.assign(21, 0.0);
  options.column.assign(21, 0.0);
  EXPECT_EQ(MakeMarionetteRun(options)->Description().find("warning"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(MarionetteRunTest, ValenceSixGuidesLiftThePlanDirectlyAndByGuidedProjection) {
  MarionetteRunOptions options;
  options.plan = kData + "marionette_plan_valence6.obj";
  options.guides = kData + "marionette_valence6_guides.txt";
  for (const SolverKind solver : {SolverKind::kDirect, SolverKind::kGuidedProjection}) {
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
  EXPECT_EQ(report.solver, SolverKind::kDirect);
  EXPECT_TRUE(report.converged);
  EXPECT_LE(ValueOf(report.final, "max_planarity"), 1e-12);
  options.lift.tolerance = 1e-300;
  EXPECT_FALSE(MakeMarionetteRun(options)->Run(nullptr).converged);
}

}  // namespace
}  // namespace gproj::marionette
