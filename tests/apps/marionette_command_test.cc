// `gproj marionette` beyond regular grids, run as a user runs it: plans with singularities and
// guide files, other projections, closed strips; errors name the file line / patch / face, exit
// code 1, nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"

namespace gproj {
namespace {

namespace fs = std::filesystem;

const std::string kData = std::string(GPROJ_SOURCE_DIR) + "/examples/data/";

class MarionetteMeshCommandTest : public CommandTest {
 protected:
  using Run = CommandRun;

  // Runs `gproj marionette ARGS -o out.obj --report r.json`.
  Run Marionette(const std::string& args) {
    return Gproj("marionette " + args + " -o " + Path("out.obj") + " --report " + Path("r.json"));
  }
  nlohmann::json Report() const { return Json("r.json"); }
  // Exit 1, a one-line error containing `part`, nothing written.
  void ExpectRefused(const std::string& args, const std::string& part) {
    ExpectOneLineError(Marionette(args), part);
    EXPECT_FALSE(fs::exists(dir_ / "out.obj"));
    EXPECT_FALSE(fs::exists(dir_ / "r.json"));
  }
  // Vertices of an OBJ file.
  std::vector<std::array<double, 3>> Vertices(const std::string& name) const {
    std::vector<std::array<double, 3>> v;
    std::istringstream lines(Slurp(dir_ / name));
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("v ", 0) == 0) {
        std::istringstream in(line.substr(2));
        std::array<double, 3> p;
        in >> p[0] >> p[1] >> p[2];
        v.push_back(p);
      }
    return v;
  }
};

TEST_F(MarionetteMeshCommandTest, LiftsTheValenceSixPlanFromItsSpokesWithBothSolvers) {
  const std::string args = kData + "marionette_plan_valence6.obj --guides " + kData +
                           "marionette_valence6_guides.txt --solver ";
  std::vector<std::array<double, 3>> direct;
  for (const char* solver : {"direct", "gp"}) {
    const Run r = Marionette(args + solver);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("6 patches, 6 strips of patches (30 face strips, 0 closed): a lift "
                         "needs 31 guide values, the guides give 31"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("wrote "), std::string::npos);
    const nlohmann::json report = Report();
    EXPECT_TRUE(report["converged"].get<bool>());
    EXPECT_EQ(report["patches"].size(), 6u);
    EXPECT_EQ(report["design_dimension"].get<int>(), 31);
    EXPECT_EQ(report["patch_order"].size(), 6u);
    EXPECT_LE(report["final"]["max_relative_det"].get<double>(), 1e-12);
    EXPECT_EQ(report["iterations"].get<int>(), std::string(solver) == "gp" ? 1 : 0);
    const auto v = Vertices("out.obj");
    ASSERT_EQ(v.size(), 181u);
    EXPECT_NEAR(v[0][2], 3.0, 1e-12);  // the guide height of the singular vertex
    if (direct.empty()) {
      direct = v;
    } else {
      for (size_t k = 0; k < v.size(); ++k) EXPECT_NEAR(v[k][2], direct[k][2], 1e-10) << k;
    }
  }
}

// A plan of triangles and hexagons (002 §4.2, the shipped Kagome patch) lifted from two guide
// polylines and three isolated heights, fairness (eq. 17) fixing the rest: planar hexagons, the
// design space in the report (eq. 16 and by rank); too few heights are refused.
TEST_F(MarionetteMeshCommandTest, KagomePlanLiftsFromGuidesAndFairness) {
  const std::string holds =
      " --hold 0:0.207055,2:0.129410,6:0.353553,10:0.482963,14:0.482963,18:0.353553,22:0.129410,"
      "25:0.565685,44:0.772741,63:0.772741,82:0.565685,101:0.207055,40:0.6,70:0.6,100:0.6";
  const CommandRun r = Gproj("marionette " + Data("marionette_kagome.obj") + holds + " -o " +
                             Path("k.obj") + " --report " + Path("k.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("k.json");
  EXPECT_LT(report["final"]["max_planarity"].get<double>(), 1e-10);
  EXPECT_LT(report["final"]["max_height_error"].get<double>(), 1e-12);
  EXPECT_EQ(report["design_space"]["estimate"].get<int>(), 45);
  EXPECT_EQ(report["design_space"]["dimension"].get<int>(), 45);
  EXPECT_NE(r.out.find("72 3-gons, 25 6-gons"), std::string::npos) << r.out;
  ExpectOneLineError(Gproj("marionette " + Data("marionette_kagome.obj") + " --hold 0:1,2:1 -o " +
                           Path("bad.obj")),
                     "stay free");
  ExpectOneLineError(
      Gproj("marionette " + Data("marionette_kagome.obj") + " --row 0,1 -o " + Path("bad.obj")),
      "prescribed heights");
  EXPECT_FALSE(Exists("bad.obj"));
}

// A closed mesh of three rings (002 Figs. 7-8): each ring's a and |V| in the log and report, the
// rings lifted outward with planar quads and the inner curve kept (every a != 1).
TEST_F(MarionetteMeshCommandTest, ClosedMeshOfSeveralRings) {
  const CommandRun r = Gproj("marionette --closed-strip " + Data("marionette_closed_rings.txt") +
                             " -o " + Path("rings.obj") + " --report " + Path("rings.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("rings.json");
  EXPECT_EQ(report["rings"].get<int>(), 3);
  ASSERT_EQ(report["a"].size(), 3u);
  for (const auto& a : report["a"]) EXPECT_GT(std::abs(a.get<double>() - 1.0), 1e-3);
  EXPECT_LT(report["final"]["max_planarity"].get<double>(), 1e-10);
  EXPECT_LT(report["inner_curve_change"].get<double>(), 1e-9);
  EXPECT_NE(r.out.find("ring 2: a = "), std::string::npos) << r.out;
  const PolyMesh mesh = ReadMesh(Path("rings.obj"));
  EXPECT_EQ(mesh.n_faces(), 72u);
}

TEST_F(MarionetteMeshCommandTest, ChecksOutputPathsBeforeLifting) {
  const std::string plan = kData + "marionette_plan_valence6.obj";
  const std::string guides = kData + "marionette_valence6_guides.txt";
  for (const std::string& args : {plan + " --guides " + guides + " -o " + Path("missing/out.obj"),
                                  plan + " --guides " + guides + " -o " + Path("out.obj") +
                                      " --report " + Path("missing/r.json"),
                                  plan + " --guides " + guides + " -o " + Path("out.xyz")}) {
    const CommandRun r = Gproj("marionette " + args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
    EXPECT_EQ(r.out.find("patches:"), std::string::npos) << "work started before the check";
    EXPECT_FALSE(fs::exists(dir_ / "out.obj"));
  }
}

TEST_F(MarionetteMeshCommandTest, RefusesGuidesThatLeaveTwoPatchesUndetermined) {
  // Five of the six spokes: spoke 5 (vertices 26..30) separates patches 4 and 5.
  std::string guides;
  for (int s = 0; s < 5; ++s) guides += "guide 0 " + std::to_string(1 + 5 * s) + " 3 2 1 0 1 2\n";
  const std::string file = Write("g.txt", guides);
  ExpectRefused(
      kData + "marionette_plan_valence6.obj --guides " + file,
      "the guides do not determine patches 4, 5: 55 vertices have no value (26, 27, 28, 29, "
      "30, 131, ");
  ExpectRefused(kData + "marionette_plan_valence6.obj --guides " + file,
                "; no guide crosses strip of patches 4, 5 (a lift needs 31 values");
  // Two different heights for the singular vertex.
  const std::string clash = Write("c.txt", "# spokes\nguide 0 1 3 2 1 0 1 2\nvertex 0 2.5\n");
  ExpectRefused(kData + "marionette_plan_valence6.obj --guides " + clash,
                "incompatible guides: vertex 0 gets 3.000000 from " + clash + ":2");
}

TEST_F(MarionetteMeshCommandTest, GuideFileErrorsNameTheLine) {
  const std::string plan = kData + "marionette_plan_valence6.obj --guides ";
  ExpectRefused(plan + Write("a.txt", "\nguide 0 1 1 2 x\n"), "a.txt:2: 'x' is not a number");
  ExpectRefused(plan + Write("b.txt", "guide 0 1 1 2 3 4 5 6 7\n"),
                "b.txt:1: the polyline from vertex 0 through 1 has only 6 vertices");
  ExpectRefused(plan + Write("c.txt", "vertex 181 1\n"), "c.txt:1: '181' is not a vertex id");
  ExpectRefused(plan + Write("d.txt", "guide 0 1\n"), "d.txt:1: expected 'guide START NEXT");
}

std::string Repeat(const std::string& value, int count) {
  std::string s;
  for (int k = 0; k < count; ++k) s += (k ? "," : "") + value;
  return s;
}

TEST_F(MarionetteMeshCommandTest, CylindricalTowerWithConstantRadiiIsACylinder) {
  for (const char* solver : {"direct", "gp", "ceres"}) {
    const Run r = Marionette(kData + "marionette_tower_12x18.obj --projection cylindrical " +
                             "--axis 0,0,-5,0,0,3 --row " + Repeat("7.5", 19) + " --column " +
                             Repeat("7.5", 13) + " --solver " + solver);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto v = Vertices("out.obj");
    ASSERT_EQ(v.size(), 247u);
    for (const auto& p : v) EXPECT_NEAR(std::hypot(p[0], p[1]), 7.5, 1e-9);
    EXPECT_LE(Report()["final"]["max_relative_det"].get<double>(), 1e-12);
    EXPECT_EQ(Report()["projection"], "cylindrical");
    EXPECT_EQ(Report()["solver"], solver);
  }
}

TEST_F(MarionetteMeshCommandTest, MissedToleranceExitsThreeWithTheResultWritten) {
  const std::string tower = kData + "marionette_tower_12x18.obj --projection cylindrical --row " +
                            Repeat("7.5", 19) + " --column " + Repeat("7.5", 13);
  const Run r = Marionette(tower + " --solver gp --max-iterations 1");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("tolerance 1.0e-09 not reached (max_relative_det"), std::string::npos)
      << r.err;
  EXPECT_EQ(Vertices("out.obj").size(), 247u);
  nlohmann::json report = Report();
  EXPECT_FALSE(report["converged"].get<bool>());
  EXPECT_FALSE(report["failed"].get<bool>());
  EXPECT_EQ(report["iterations"].get<int>(), 1);
  EXPECT_GT(report["final"]["max_relative_det"].get<double>(), 1e-9);
  EXPECT_EQ(report["history"].size(), 2u);

  // The same schema for a direct mode; a tolerance below round-off is missed too.
  const Run d =
      Marionette("--closed-strip " + kData + "marionette_closed_strip.txt --tolerance 1e-300");
  EXPECT_EQ(d.exit_code, 3) << d.err;
  report = Report();
  EXPECT_EQ(report["solver"], "direct");
  EXPECT_FALSE(report["converged"].get<bool>());
  EXPECT_GT(report["initial"]["max_planarity"].get<double>(), 0.0);
  EXPECT_EQ(Vertices("out.obj").size(), 2 * report["quads"].get<size_t>());
}

TEST_F(MarionetteMeshCommandTest, RefusesBadProjectionOptions) {
  const std::string tower = kData + "marionette_tower_12x18.obj --row " + Repeat("7", 19) +
                            " --column " + Repeat("7", 13);
  ExpectRefused(tower + " --projection cylindrical --axis 0,0,1", "--axis: expects 6 numbers");
  ExpectRefused(tower + " --projection conic",
                "--projection: 'conic' is not one of vertical, cylindrical, central");
  ExpectRefused(tower + " --projection cylindrical --axis 0,0,0,0,0,0",
                "the axis direction must not be zero");
  // The tower's first vertex (10, 0, 0) at the centre: it has no line.
  ExpectRefused(tower + " --projection central --centre 10,0,0",
                "marionette_tower_12x18.obj: vertex 0 lies at the centre");
}

// Inner unit circle and an outer ellipse, optionally jittered (then a != 1).
std::string RingFile(double jitter) {
  std::ostringstream s;
  s << "# ring\n";
  for (int i = 0; i < 16; ++i) {
    const double t = 2 * M_PI * i / 16, j = jitter * std::sin(7.3 * i + 1.0);
    s << std::cos(t) << " " << std::sin(t) << " " << 0.2 * std::cos(t) + 0.1 * std::sin(3 * t)
      << " " << 1.6 * std::cos(t + j) << " " << 1.9 * std::sin(t + j) << "\n";
  }
  return s.str();
}

TEST_F(MarionetteMeshCommandTest, ClosedStripReportsAAndTheClosingHeight) {
  const Run ceres =
      Marionette("--closed-strip " + Write("s.txt", RingFile(0.1)) + " --solver ceres");
  EXPECT_EQ(ceres.exit_code, 1);
  EXPECT_NE(ceres.err.find("--solver ceres does not apply"), std::string::npos) << ceres.err;
  for (const char* other : {" --hold 1:2", " --row 1,2", " --projection central"}) {
    const Run misused = Marionette("--closed-strip " + Write("s.txt", RingFile(0.1)) + other);
    EXPECT_EQ(misused.exit_code, 1) << other;
    EXPECT_NE(misused.err.find("belong to a plan"), std::string::npos) << misused.err;
  }
  const Run r = Marionette("--closed-strip " + Write("s.txt", RingFile(0.1)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json report = Report();
  EXPECT_FALSE(report["a_is_one"].get<bool>());
  EXPECT_GT(std::abs(report["a"].get<double>() - 1.0), 1e-3);
  EXPECT_LE(report["final"]["max_planarity"].get<double>(), 1e-12);
  EXPECT_EQ(report["inner_curve_change"].get<double>(), 0.0);
  auto v = Vertices("out.obj");
  ASSERT_EQ(v.size(), 32u);
  EXPECT_NEAR(v[16][2], report["closing_height"].get<double>(), 1e-12);
  EXPECT_NE(r.out.find("(!= 1): one closing lift"), std::string::npos) << r.out;

  // Mirror-symmetric plan: a = 1, the inner curve is projected, z0* is the given one.
  const Run s =
      Marionette("--closed-strip " + Write("e.txt", RingFile(0.0)) + " --outer-height 0.7");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  report = Report();
  EXPECT_TRUE(report["a_is_one"].get<bool>());
  EXPECT_NEAR(report["closing_height"].get<double>(), 0.7, 1e-15);
  EXPECT_LE(report["final"]["max_planarity"].get<double>(), 1e-12);
  EXPECT_NE(s.out.find("the outer start height is free"), std::string::npos) << s.out;
}

TEST_F(MarionetteMeshCommandTest, ClosedStripRefusesBadLinesAndDegenerateQuads) {
  ExpectRefused("--closed-strip " + Write("s.txt", "# x\n0 0 0 1 0\n1 0 0 2\n"),
                "s.txt:3: expected 5 numbers (inner x y z, then x y of every outer curve), got 4");
  ExpectRefused("--closed-strip " + Write("n.txt", "0 0 0 1 nan\n1 0 0 2 0\n0 1 0 0 2\n"),
                "n.txt:1: 'nan' is not finite");
  // Pair 1's outer vertex on the line through inner 1 and inner 2.
  ExpectRefused("--closed-strip " + Write("d.txt", "1 0 0 2 0\n0 1 0 1 2\n-1 0 0 -2 0\n"),
                "d.txt:2: quad 1 (vertex pairs 1 and 2, lines 2 and 3) has a degenerate plan view");
  ExpectRefused("--closed-strip " + Write("t.txt", "0 0 0 1 0\n1 0 0 2 0\n"),
                "t.txt: a closed strip needs at least 3 vertex pairs, got 2");
}

// 002 §3.3 from the command line: a fit with hard constraints (a held height, the volume, a
// max height) meets them exactly; a partial target (--fit-heights) along the two guide curves
// reproduces the lift from them; constraints that leave the lift free or a solver that cannot
// take them are refused before anything is written.
TEST_F(MarionetteMeshCommandTest, FitsWithHardConstraintsAndPartialTargets) {
  ASSERT_EQ(Gproj("grid -o " + Path("plan.obj") + " --nu 9 --nv 7 --noise 0.1").exit_code, 0);
  ASSERT_EQ(Gproj("grid -o " + Path("target.obj") +
                  " --nu 9 --nv 7 --noise 0.1 --a 0.8 --b -0.5 "
                  "--wave 0.3")
                .exit_code,
            0);
  const std::string plan = Path("plan.obj");
  const Run fit = Marionette(plan + " --fit " + Path("target.obj") +
                             " --hold 30:0.5,0:0 --volume 1.25 --max-height 0.55");
  ASSERT_EQ(fit.exit_code, 0) << fit.err << fit.out;
  const nlohmann::json report = Report();
  EXPECT_LE(report["final"]["max_constraint_error"].get<double>(), 1e-12);
  EXPECT_LE(report["final"]["max_planarity"].get<double>(), 1e-12);
  EXPECT_EQ(report["hard_constraints"]["volume"].get<double>(), 1.25);
  const auto v = Vertices("out.obj");
  EXPECT_NEAR(v[30][2], 0.5, 1e-12);
  EXPECT_NEAR(v[0][2], 0.0, 1e-12);
  double top = -1e300;
  for (const auto& p : v) top = std::max(top, p[2]);
  EXPECT_LE(top, 0.55 + 1e-12);
  EXPECT_NE(fit.out.find("KKT system of the constrained fit"), std::string::npos) << fit.out;

  // Heights along row 0 and column 0 only (vertex (i, j) = i * 7 + j): the lift from them.
  std::ofstream part(dir_ / "part.txt");
  part << "# row 0 and column 0\n";
  for (int j = 0; j < 7; ++j) part << j << " " << 0.1 * j << "\n";
  for (int i = 1; i < 9; ++i) part << i * 7 << " " << 0.05 * i * i << "\n";
  part.close();
  const Run partial = Marionette(plan + " --fit-heights " + Path("part.txt"));
  ASSERT_EQ(partial.exit_code, 0) << partial.err;
  const auto lifted = Vertices("out.obj");
  const Run lift = Gproj("marionette " + plan + " --row 0,0.1,0.2,0.3,0.4,0.5,0.6 --column " +
                         "0,0.05,0.2,0.45,0.8,1.25,1.8,2.45,3.2 -o " + Path("lift.obj"));
  ASSERT_EQ(lift.exit_code, 0) << lift.err;
  const auto expected = Vertices("lift.obj");
  ASSERT_EQ(lifted.size(), expected.size());
  for (size_t k = 0; k < lifted.size(); ++k) EXPECT_NEAR(lifted[k][2], expected[k][2], 1e-10) << k;
  fs::remove(dir_ / "out.obj");
  fs::remove(dir_ / "r.json");

  std::ofstream few(dir_ / "few.txt");
  few << "0 0.1\n10 0.2\n";
  few.close();
  ExpectRefused(plan + " --fit-heights " + Path("few.txt"), "guide heights stay free");
  ExpectRefused(plan + " --fit " + Path("target.obj") + " --hold 30:0.5 --solver gp",
                "use --solver direct");
  ExpectRefused(plan + " --row 0,0,0,0,0,0,0 --column 0,0,0,0,0,0,0,0,0 --volume 1",
                "constrain a fit");
  ExpectRefused(plan + " --fit " + Path("target.obj") + " --hold 3x:1",
                "--hold: 3x is not an integer");
  std::ofstream bad(dir_ / "bad.txt");
  bad << "0 0.1\n99 0.2\n";
  bad.close();
  ExpectRefused(plan + " --fit-heights " + Path("bad.txt"), "bad.txt:2");
}

}  // namespace
}  // namespace gproj
