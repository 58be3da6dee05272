// `gproj weingarten` as a user runs it, on the shipped B-spline.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "apps/command_test_util.h"
#include "gproj/geometry/surface/bspline_surface.h"
#include "gproj/problems/weingarten/helical_fit.h"

namespace gproj {
namespace {

namespace fs = std::filesystem;

class WeingartenCommandTest : public CommandTest {};

TEST_F(WeingartenCommandTest, OptimisesTheShippedSurfaceAndWritesEveryOutput) {
  const CommandRun r =
      Gproj("weingarten " + Data("freeform_10x10.json") + " -o " + Path("out.json") +
            " --max-iterations 6 --molds 12 --diagram " + Path("d.svg") + " --curvature " +
            Path("c.csv") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["variables"].get<int>(), 3 * 100 + 12 * 400);
  EXPECT_LT(report["final"]["misalignment"].get<double>(),
            0.5 * report["initial"]["misalignment"].get<double>());
  EXPECT_LE(report["molds"]["clusters"].get<int>(), 12);
  // Measured between the samples too, and checked for folds.
  EXPECT_EQ(report["dense_check"]["samples"], nlohmann::json::array({40, 40}));
  EXPECT_GT(report["dense_check"]["misalignment"].get<double>(), 0.0);
  EXPECT_GT(report["min_normal_cosine"]["final"].get<double>(), 0.9);
  EXPECT_NE(r.out.find("between the samples (40 x 40 check grid)"), std::string::npos) << r.out;
  EXPECT_EQ(report["history"].size(), 7u);
  EXPECT_NE(Slurp(dir_ / "d.svg").find("<svg"), std::string::npos);
  EXPECT_NE(Slurp(dir_ / "c.csv").find("H_before,K_before,H_after,K_after,mold"),
            std::string::npos);
  // The output is a valid B-spline the command reads back.
  const CommandRun again =
      Gproj("weingarten " + Path("out.json") + " -o " + Path("out2.json") + " --max-iterations 1");
  EXPECT_EQ(again.exit_code, 0) << again.err;
}

// A generated bicubic wavy surface that fig1 folds when every step is kept: by default the
// folding steps are refused and the result is regular (exit 0); with --allow-folds the result
// folds and the command says so and exits 3.
TEST_F(WeingartenCommandTest, RefusesStepsThatFoldUnlessAllowed) {
  WriteBSplineJson(MakeWavyBSpline(11, 11, 3, 1.4), Path("wavy.json"));
  const CommandRun guarded = Gproj("weingarten " + Path("wavy.json") + " -o " + Path("out.json") +
                                   " --report " + Path("r.json"));
  ASSERT_EQ(guarded.exit_code, 0) << guarded.err << guarded.out;
  EXPECT_GT(Json("r.json")["min_normal_cosine"]["final"].get<double>(), 0.5);
  const CommandRun folding =
      Gproj("weingarten " + Path("wavy.json") + " -o " + Path("folded.json") + " --allow-folds");
  EXPECT_EQ(folding.exit_code, 3) << folding.err << folding.out;
  EXPECT_NE(folding.err.find("the result folds"), std::string::npos) << folding.err;
}

// 003 Fig. 4 as a user runs it: a surface near a helical one (its profile changing along the
// turn), with geodesic parallel isolines; the report and the log give the deviation from the
// nearest helical surface before and after, and it falls.
TEST_F(WeingartenCommandTest, GeodesicParallelIsolinesReportTheHelicalDeviation) {
  weingarten::HelicalTestSurface spec;
  spec.profile_drift = 0.1;
  WriteBSplineJson(weingarten::MakeHelicalBSpline(10, 12, 4, spec), Path("helical.json"));
  const CommandRun r = Gproj("weingarten " + Path("helical.json") + " -o " + Path("out.json") +
                             " --preset fig4c --closeness 0.01 --fairness 0.01 "
                             "--max-iterations 30 --report " +
                             Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json h = Json("r.json")["helical_deviation"];
  EXPECT_LT(h["final"]["max_percent"].get<double>(),
            h["initial"]["max_percent"].get<double>() / 3.0);
  EXPECT_NEAR(h["final"]["pitch"].get<double>(), 0.4, 0.02);
  EXPECT_NE(r.out.find("deviation from the nearest helical surface"), std::string::npos) << r.out;
}

// 003 §4.2 on the shipped surface: the input and the result paneled alike (8 × 8 panels,
// 3 √64 = 24 molds asked), the report's panels object, the two pictures, the log lines.
TEST_F(WeingartenCommandTest, PanelsTheInputAndTheResultAlike) {
  const CommandRun r =
      Gproj("weingarten " + Data("freeform_10x10.json") + " -o " + Path("out.json") +
            " --max-iterations 6 --panels 8,8 --panel-tolerance 0.05,5 --panel-picture " +
            Path("panels.svg") + " --seam-histograms " + Path("seams.svg") + " --report " +
            Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json panels = Json("r.json")["panels"];
  EXPECT_EQ(panels["count"].get<int>(), 64);
  EXPECT_EQ(panels["molds"].get<int>(), 24);
  for (const char* which : {"initial", "final"}) {
    const nlohmann::json& p = panels[which];
    EXPECT_LE(p["molds"].get<int>(), 24) << which;
    EXPECT_GT(p["mean_gap"].get<double>(), 0.0) << which;
    EXPECT_LE(p["mean_gap"].get<double>(), p["max_gap"].get<double>()) << which;
    EXPECT_LE(p["mean_kink_deg"].get<double>(), p["max_kink_deg"].get<double>()) << which;
    EXPECT_TRUE(p.contains("molds_needed")) << which;
  }
  EXPECT_EQ(panels["tolerance"]["max_gap"].get<double>(), 0.05);
  EXPECT_NE(r.out.find("panels: 64 (8 x 8), 24 molds asked"), std::string::npos) << r.out;
  const std::string picture = Slurp(dir_ / "panels.svg");
  EXPECT_NE(picture.find("one colour per mold"), std::string::npos);
  const std::string seams = Slurp(dir_ / "seams.svg");
  EXPECT_NE(seams.find("Gaps at the seams"), std::string::npos);
  EXPECT_NE(seams.find("Kinks at the seams"), std::string::npos);
}

TEST_F(WeingartenCommandTest, PanelOptionsAreChecked) {
  const std::string base =
      "weingarten " + Data("freeform_10x10.json") + " -o " + Path("out.json") + " ";
  const CommandRun lone = Gproj(base + "--panel-tolerance 0.1,2");
  EXPECT_EQ(lone.exit_code, 1);
  EXPECT_NE(lone.err.find("need --panels NU,NV"), std::string::npos) << lone.err;
  const CommandRun zero = Gproj(base + "--panels 0,4");
  EXPECT_EQ(zero.exit_code, 1);
  EXPECT_NE(zero.err.find("--panels"), std::string::npos) << zero.err;
  EXPECT_FALSE(Exists("out.json"));
}

// Without --tolerance the preset's iterations are the ask (exit 0); with one, the run stops as
// soon as it is met, and one it cannot meet gives exit 3 with the result and report written.
// A property of the surface found while sampling it is an input error that names the file.
TEST_F(WeingartenCommandTest, ADegenerateSurfaceIsRefusedNamingTheFile) {
  nlohmann::json surface = nlohmann::json::parse(Slurp(Data("freeform_10x10.json")));
  for (auto& row : surface["control_points"])
    for (auto& p : row) p = {p[0].get<double>(), 0.0, 0.0};  // every point on one line
  const std::string path = Write("line.json", surface.dump());
  const CommandRun r = Gproj("weingarten " + path + " -o " + Path("out.json"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("gproj weingarten: " + path + ": the surface is degenerate", 0), 0u)
      << r.err;
  EXPECT_FALSE(Exists("out.json"));
}

TEST_F(WeingartenCommandTest, ToleranceStopsTheRunAndDecidesTheExitCode) {
  const std::string base = "weingarten " + Data("freeform_10x10.json") + " --max-iterations 6";
  const CommandRun met = Gproj(base + " -o " + Path("met.json") + " --tolerance 0.3 --report " +
                               Path("met_report.json"));
  ASSERT_EQ(met.exit_code, 0) << met.err << met.out;
  const nlohmann::json report = Json("met_report.json");
  EXPECT_TRUE(report["converged"].get<bool>());
  EXPECT_EQ(report["target"].get<std::string>(), "misalignment");
  EXPECT_LE(report["final"]["misalignment"].get<double>(), 0.3);
  EXPECT_LT(report["iterations"].get<int>(), 6) << "the run did not stop at the tolerance";

  const CommandRun missed = Gproj(base + " -o " + Path("missed.json") +
                                  " --tolerance 1e-6 --report " + Path("missed_report.json"));
  EXPECT_EQ(missed.exit_code, 3) << missed.err;
  EXPECT_NE(missed.err.find("tolerance 1.0e-06 not reached (misalignment"), std::string::npos)
      << missed.err;
  EXPECT_TRUE(Exists("missed.json"));
  EXPECT_FALSE(Json("missed_report.json")["converged"].get<bool>());
  EXPECT_EQ(Json("missed_report.json")["iterations"].get<int>(), 6);
}

// With refinement the curvature table holds the input's and the result's H and K at the same
// (last level's) samples.
// --refine-method refit: the second level on a net 1.4 times as dense (003 §4.1.1), named in the
// report.
TEST_F(WeingartenCommandTest, RefitRefinementGoesToANetOnePointFourTimesAsDense) {
  const CommandRun r =
      Gproj("weingarten " + Data("freeform_10x10.json") + " -o " + Path("out.json") +
            " --refine 1 --refine-method refit " + "--max-iterations 1 --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["refine_method"], "refit");
  ASSERT_EQ(report["levels"].size(), 2u);
  EXPECT_EQ(report["levels"][1]["control_points"], nlohmann::json::array({14, 14}));
  EXPECT_EQ(Gproj("weingarten " + Data("freeform_10x10.json") + " -o " + Path("x.json") +
                  " --refine-method spline")
                .exit_code,
            1);
}

TEST_F(WeingartenCommandTest, RefinedRunWritesBeforeAndAfterAtTheSameSamples) {
  const CommandRun r = Gproj("weingarten " + Data("freeform_10x10.json") + " -o " +
                             Path("out.json") + " --refine 1 --max-iterations 2 --curvature " +
                             Path("c.csv") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  ASSERT_EQ(report["levels"].size(), 2u);
  EXPECT_EQ(report["history"].back()["level"].get<int>(), 1);
  const int samples = report["samples"][0].get<int>() * report["samples"][1].get<int>();
  std::istringstream csv(Slurp(dir_ / "c.csv"));
  std::string line;
  std::getline(csv, line);  // header
  int rows = 0;
  double max_before = 0.0, max_after = 0.0;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
    ASSERT_EQ(v.size(), 7u) << line;
    max_before = std::max(max_before, std::abs(v[3]));
    max_after = std::max(max_after, std::abs(v[5]));
    ++rows;
  }
  EXPECT_EQ(rows, samples);
  // Same surface scale before and after (a small optimisation): H of the same order.
  EXPECT_GT(max_before, 0.2 * max_after);
  EXPECT_LT(max_before, 5.0 * max_after);
}

// 003 Fig. 3 from the command line: the shipped bump made CMC (H = −0.1) with the boundary held,
// control points as the only unknowns, 3 samples per control point (a fixed relation's
// default): the relation holds between the samples as at them, away from the corners.
TEST_F(WeingartenCommandTest, Fig3PresetMakesTheShippedBumpCmc) {
  const CommandRun r =
      Gproj("weingarten " + Data("bump_14x14.json") + " -o " + Path("cmc.json") +
            " --preset fig3 --linear 1,0,0.1 --no-auxiliaries --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["variables"].get<int>(), 3 * 196);
  EXPECT_EQ(report["steps"].get<std::string>(), "projected");
  EXPECT_EQ(report["samples"], nlohmann::json::array({42, 42}));
  EXPECT_LE(report["final"]["max_relation_residual"].get<double>(), 1e-3);
  EXPECT_LE(report["dense_check"]["max_relation_residual_interior"].get<double>(), 1e-3);
  EXPECT_NE(r.out.find("max residual"), std::string::npos);
  ExpectOneLineError(Gproj("weingarten " + Data("bump_14x14.json") + " -o " + Path("x.json") +
                           " --no-auxiliaries"),
                     "without curvature auxiliaries");
  EXPECT_FALSE(Exists("x.json"));
}

// The Ceres path on a bi-degree (4,4) surface: every sample's definitions touch 25 control
// points and the auxiliary (12 rows × 87 unknowns per residual block).
TEST_F(WeingartenCommandTest, CeresSolverPathRunsOnTheShippedSurface) {
  const CommandRun r =
      Gproj("weingarten " + Data("freeform_10x10.json") + " -o " + Path("out.json") +
            " --solver ceres --max-iterations 3 --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["solver"].get<std::string>(), "ceres");
  EXPECT_GE(report["history"].size(), 2u);
  EXPECT_LT(report["history"].back()["energy"].get<double>(),
            report["history"].front()["energy"].get<double>());
}

TEST_F(WeingartenCommandTest, ChecksEveryOutputPathBeforeOptimising) {
  for (const std::string option : {"--report", "--diagram", "--curvature", "--picture"}) {
    const CommandRun r = Gproj("weingarten " + Data("freeform_10x10.json") + " -o " +
                               Path("out.json") + " " + option + " " + Path("missing/x"));
    EXPECT_EQ(r.exit_code, 1) << option << ": " << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("iter"), std::string::npos) << "the solve started before the check";
    EXPECT_FALSE(fs::exists(dir_ / "out.json"));
  }
  const CommandRun mesh = Gproj("weingarten " + Data("freeform_10x10.json") + " -o " +
                                Path("out.json") + " --surface-mesh " + Path("s.stl"));
  EXPECT_EQ(mesh.exit_code, 1);
  EXPECT_NE(mesh.err.find("--surface-mesh"), std::string::npos) << mesh.err;
  // The result is a B-spline (JSON), not a mesh.
  ExpectOneLineError(Gproj("weingarten " + Data("freeform_10x10.json") + " -o " + Path("out.obj")),
                     "--output " + Path("out.obj") + ": the file is written as .json");
  EXPECT_FALSE(Exists("out.obj"));
}

TEST_F(WeingartenCommandTest, RefusesBadSplinesAndPresets) {
  const std::string bad = Write(
      "bad.json", R"({"degree": [2, 2], "knots_u": [0, 0, 0, 1, 1], "knots_v": [0, 0, 0, 1, 1, 1],)"
                  R"( "control_points": [[[0,0,0],[0,1,0],[0,2,0]],[[1,0,0],[1,1,0],[1,2,0]],)"
                  R"([[2,0,0],[2,1,0],[2,2,0]]]})");
  ExpectOneLineError(Gproj("weingarten " + bad + " -o " + Path("out.json")), "knots_u");
  ExpectOneLineError(Gproj("weingarten " + Data("freeform_10x10.json") + " -o " + Path("out.json") +
                           " --preset fig99"),
                     "--preset: 'fig99' is not one of fig1, fig2b");
  EXPECT_FALSE(Exists("out.json"));
}

}  // namespace
}  // namespace gproj
