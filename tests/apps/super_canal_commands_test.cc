// `gproj combescure`, `gproj invert`, `gproj canal` and `gproj beams` as a user runs them, on
// the shipped data.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/circle.h"

namespace gproj {
namespace {

class SuperCanalCommandTest : public CommandTest {};

TEST_F(SuperCanalCommandTest, CombescureByEveryMethodKeepsEdgesParallelAndQuadsCircular) {
  for (const std::string method : {"direct", "gp", "ceres"}) {
    const CommandRun r =
        Gproj("combescure " + Data("revolution_13x17.obj") + " -o " + Path("out.obj") +
              " --solver " + method +
              " --row-lengths 0.1,0.12,0.14,0.16,0.18,0.2,0.2,0.18,0.16,0.14,0.12,0.1,0.1,0.1,"
              "0.1,0.1 --column-scale 0.6 --report " +
              Path("r.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
    const nlohmann::json report = Json("r.json");
    EXPECT_TRUE(report["converged"].get<bool>());
    EXPECT_EQ(report["options"]["solver"], method);
    EXPECT_EQ(report["solver"], method);
    EXPECT_LT(report["final"]["max_edge_parallelism_angle"].get<double>(), 1e-10) << method;
    EXPECT_LT(report["final"]["max_planarity"].get<double>(), 1e-10) << method;
    EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10) << method;
    EXPECT_NE(r.out.find("edge-parallelism angle"), std::string::npos) << r.out;
  }
}

TEST_F(SuperCanalCommandTest, EveryCommandChecksItsOutputsBeforeWorking) {
  const std::string in = Data("revolution_13x17.obj");
  const std::string missing = Path("missing/x.obj");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"combescure " + in + " -o " + missing, "--output"},
      {"invert " + in + " --centre 0,0,5 -o " + missing, "--output"},
      {"invert " + in + " --centre 0,0,5 -o " + Path("out.obj") + " --report " + missing,
       "--report"},
      {"canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2 -o " +
           Path("out.obj") + " --strip " + missing,
       "--strip"},
      {"grid -o " + missing, "--output"},
      {"grid -o " + Path("out.stl"), ".stl"}};
  for (const auto& [command, option] : cases) {
    ExpectOneLineError(Gproj(command), option);
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out.obj")) << command;
  }
}

TEST_F(SuperCanalCommandTest, CombescureRefusesWrongLengthCountAndNonPlanarReference) {
  ExpectOneLineError(Gproj("combescure " + Data("revolution_13x17.obj") + " -o " + Path("out.obj") +
                           " --row-lengths 1,2,3"),
                     "needs 16 edge lengths");
  ExpectOneLineError(Gproj("combescure " + Data("noisy_grid_21x21.obj") + " -o " + Path("out.obj")),
                     "not planar");
  EXPECT_FALSE(Exists("out.obj"));
}

TEST_F(SuperCanalCommandTest, InvertKeepsCircularityAndSolvesTheMRevolutionCentre) {
  CommandRun r = Gproj("invert " + Data("revolution_13x17.obj") + " -o " + Path("out.obj") +
                       " --centre 4,0.5,0.3 --ratio 9 --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(Json("r.json")["final"]["max_concyclicity"].get<double>(), 1e-10);
  // Four points of the circle z = 1, r = 2 (a parallel of a surface of revolution).
  r = Gproj("invert " + Data("revolution_13x17.obj") + " -o " + Path("out.obj") +
            " --m-revolution 2,0,1,0,2,1,-2,0,1,0,-2,1 --t 0.5 --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json m = Json("r.json")["m_revolution"];
  EXPECT_EQ(m["centres"].size(), 2u);
  EXPECT_LT(m["image_side_angle"].get<double>(), 1e-10);
  EXPECT_NEAR(m["image_diagonals"][0].get<double>(), m["image_diagonals"][1].get<double>(), 1e-10);
  ExpectOneLineError(Gproj("invert " + Data("revolution_13x17.obj") + " -o " + Path("bad.obj") +
                           " --m-revolution 2,0,1,0,2,1,-2,0,1.3,0,-2,1 --t 0.5"),
                     "not coplanar");
  EXPECT_FALSE(Exists("bad.obj"));
}

// 000 §5.1 in one step from the shipped designer curve: a circular mesh through the curve's
// own points and P2, P3, with planar arches; P2 off the circle is refused, nothing written.
TEST_F(SuperCanalCommandTest, MRevolutionFromACurveAndTwoPoints) {
  const std::string points =
      " --p2=-0.6840402866513374,1.8793852415718169,0 --p3 1,1.7320508075688772,0";
  const CommandRun r =
      Gproj("mrevolution " + Data("m_revolution_curve.txt") + points + " --t 1 -o " +
            Path("m.obj") + " --revolution " + Path("rev.obj") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10);
  EXPECT_LT(report["initial"]["max_concyclicity"].get<double>(), 1e-10);  // of revolution
  EXPECT_LT(report["final"]["curve_roundtrip"].get<double>(), 1e-12);
  EXPECT_LT(report["final"]["far_meridian_miss"].get<double>(), 1e-10);
  EXPECT_LT(report["final"]["arch_planarity"].get<double>(), 1e-10);
  const PolyMesh mesh = ReadMesh(Path("m.obj"));
  EXPECT_EQ(mesh.n_faces(), 20u * 16u);
  EXPECT_TRUE(Exists("rev.obj"));
  // As the demo runs it: no --revolution, a picture.
  const CommandRun demo = Gproj("mrevolution " + Data("m_revolution_curve.txt") + points +
                                " --t 1 -o " + Path("d.obj") + " --picture " + Path("d.svg"));
  EXPECT_EQ(demo.exit_code, 0) << demo.err;
  EXPECT_TRUE(Exists("d.obj"));
  EXPECT_TRUE(Exists("d.svg"));
  ExpectOneLineError(Gproj("mrevolution " + Data("m_revolution_curve.txt") +
                           " --p2 -0.5,3,0 --p3 1,1.7320508075688772,0 -o " + Path("bad.obj")),
                     "--p3 is");
  EXPECT_FALSE(Exists("bad.obj"));
}

// 000 §5.2: a C-canal surface whose cross-section scales the first arc's edges; BFGS makes its
// own lengths the asked ones (exit 0), or says how far it got (exit 3, result written).
TEST_F(SuperCanalCommandTest, CCanalMeetsTheAskedLengths) {
  const std::string base =
      "canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2";
  const CommandRun r = Gproj(
      base +
      " --section-scales "
      "1.0000,1.0479,1.0841,1.0997,1.0909,1.0598,1.0141,0.9649,0.9243,0.9022,0.9041,0.9294 -o " +
      Path("c.obj") + " --report " + Path("c.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("c.json");
  EXPECT_LT(report["final"]["max_length_error"].get<double>(), 1e-9);
  EXPECT_GT(report["initial"]["max_length_error"].get<double>(), 1e-3);
  EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10);
  for (const auto& l : report["lengths"]) EXPECT_NEAR(l.get<double>(), 2.0, 1e-8);
  const CommandRun far = Gproj(
      base +
      " --section-scales "
      "1.0000,1.0959,1.1683,1.1995,1.1819,1.1197,1.0282,0.9298,0.8486,0.8045,0.8082,0.8589 -o " +
      Path("far.obj"));
  EXPECT_EQ(far.exit_code, 3) << far.err << far.out;
  EXPECT_NE(far.err.find("max_length_error"), std::string::npos) << far.err;
  EXPECT_TRUE(Exists("far.obj"));
  ExpectOneLineError(Gproj(base + " --section-scales 1,1 -o " + Path("bad.obj")),
                     "one scale per segment");
  EXPECT_FALSE(Exists("bad.obj"));
}

TEST_F(SuperCanalCommandTest, CanalBuildsACircularMeshAndSmoothingLowersTheEnergy) {
  const std::string base =
      "canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2 --segments 8 -o " +
      Path("out.obj") + " --strip " + Path("strip.obj") + " --report " + Path("r.json");
  CommandRun r = Gproj(base);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json report = Json("r.json");
  EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10);
  EXPECT_LT(report["strip"]["max_concyclicity"].get<double>(), 1e-10);
  EXPECT_TRUE(Exists("strip.obj"));
  const double before = report["final"]["smoothness_energy"].get<double>();
  r = Gproj(base + " --smooth");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = Json("r.json");
  EXPECT_LT(report["final"]["smoothness_energy"].get<double>(), 0.5 * before);
  EXPECT_GT(report["history"].size(), 1u);
  EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10);
}

// 000 §3.3: the normal at P_0 at a fixed angle to a reference plane; the smoothing turns it
// along the cone only, and the report gives the angle reached.
TEST_F(SuperCanalCommandTest, CanalNormalAtAFixedAngleToAPlane) {
  const std::string base = "canal " + Data("canal_curve.txt") +
                           " --first-point -0.5,0.5,2 --length 2 --smooth -o " + Path("out.obj") +
                           " --report " + Path("r.json");
  const CommandRun r = Gproj(base + " --normal-angle 25 --reference-plane 0,0.2,1");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("onto that cone"), std::string::npos) << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_NEAR(report["frame"]["normal_angle_deg"].get<double>(), 25.0, 1e-9);
  const auto& n = report["frame"]["normal"];
  const Eigen::Vector3d normal(n[0].get<double>(), n[1].get<double>(), n[2].get<double>());
  EXPECT_NEAR(
      std::asin(normal.normalized().dot(Eigen::Vector3d(0, 0.2, 1).normalized())) * 180 / M_PI,
      25.0, 1e-9);
  EXPECT_LT(report["final"]["smoothness_energy"].get<double>(),
            report["initial"]["smoothness_energy"].get<double>());
  EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10);
  // With no normal given, the run on the cone starts from the free smoothing's normal moved onto
  // it: at the free optimum's own angle it ends where the free run does (the default normal's
  // nearest on the cone ended at F = 4.1, exit 3).
  ASSERT_EQ(Gproj(base).exit_code, 0);
  const nlohmann::json free = Json("r.json");
  const auto& f = free["frame"]["normal"];
  const double free_angle = std::asin(f[2].get<double>()) * 180 / M_PI;
  const CommandRun same = Gproj(base + " --normal-angle " + std::to_string(free_angle));
  ASSERT_EQ(same.exit_code, 0) << same.err << same.out;
  EXPECT_LE(Json("r.json")["final"]["smoothness_energy"].get<double>(),
            free["final"]["smoothness_energy"].get<double>() * 1.001);
  // A reference plane's normal of any size (not overflowing at 1e300).
  ASSERT_EQ(
      Gproj(base + " --normal-angle 30 --reference-plane 1e300,1e300,1e300 --max-iterations 2000")
          .exit_code,
      0);
  EXPECT_NEAR(Json("r.json")["frame"]["normal_angle_deg"].get<double>(), 30.0, 1e-9);
  const nlohmann::json n1 = Json("r.json")["frame"]["normal"];
  EXPECT_NEAR(std::asin((n1[0].get<double>() + n1[1].get<double>() + n1[2].get<double>()) /
                        std::sqrt(3.0)) *
                  180 / M_PI,
              30.0, 1e-9);
  ExpectOneLineError(Gproj(base + " --reference-plane 0,0,1"), "--normal-angle");
  ExpectOneLineError(Gproj(base + " --normal-angle 90"), "--normal-angle");
  ExpectOneLineError(Gproj(base + " --normal-angle 10 --reference-plane 0,0,0"),
                     "--reference-plane");
}

TEST_F(SuperCanalCommandTest, CanalSmoothingCutShortExitsThreeWithTheResultWritten) {
  const CommandRun r =
      Gproj("canal " + Data("canal_curve.txt") +
            " --first-point -0.5,0.5,2 --length 2 --smooth --max-iterations 2 -o " +
            Path("out.obj") + " --report " + Path("r.json"));
  EXPECT_EQ(r.exit_code, 3) << r.err << r.out;
  EXPECT_NE(r.err.find("gproj canal: not converged ("), std::string::npos) << r.err;
  EXPECT_TRUE(Exists("out.obj"));
  const nlohmann::json report = Json("r.json");
  EXPECT_FALSE(report["converged"].get<bool>());
  EXPECT_FALSE(report["failed"].get<bool>());
  EXPECT_EQ(report["solver"], "ceres");
  EXPECT_EQ(report["method"], "BFGS");
  EXPECT_EQ(report["iterations"], 2);
  EXPECT_EQ(report["history"].size(), 3u);
  EXPECT_LT(report["final"]["smoothness_energy"].get<double>(),
            report["initial"]["smoothness_energy"].get<double>());
  EXPECT_NE(r.err.find("result was written"), std::string::npos) << r.err;
}

TEST_F(SuperCanalCommandTest, ReportsFollowTheSharedSchema) {
  const std::string in = Data("revolution_13x17.obj");
  // The command, its solver and its construction method (null: an iterative solver).
  const std::vector<std::array<std::string, 3>> cases = {
      {"invert " + in + " --centre 4,0.5,0.3 --ratio 9", "direct", "closed form"},
      {"combescure " + in + " --column-scale 0.5", "direct", "propagation"},
      {"combescure " + in + " --column-scale 0.5 --solver gp", "gp", ""},
      {"canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2", "direct",
       "closed form"}};
  for (const auto& [command, solver, method] : cases) {
    const CommandRun r = Gproj(command + " -o " + Path("out.obj") + " --report " + Path("r.json"));
    ASSERT_EQ(r.exit_code, 0) << command << "\n" << r.err;
    const nlohmann::json report = Json("r.json");
    EXPECT_EQ(report["solver"], solver) << command;
    EXPECT_EQ(report.value("method", ""), method) << command;
    EXPECT_EQ(report["output"], Path("out.obj")) << command;
    for (const char* key : {"command", "converged", "failed", "termination", "iterations",
                            "seconds", "variables", "initial", "final", "history"})
      EXPECT_TRUE(report.contains(key)) << command << ": " << key;
    EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10) << command;
    EXPECT_TRUE(report["initial"].contains("max_planarity")) << command;
  }
}

TEST_F(SuperCanalCommandTest, CanalRefusesBadCurveFilesAndLengths) {
  const std::string curve = Write("curve.txt", "0 0 0\n1 0 0\n2 0.5 x\n");
  ExpectOneLineError(
      Gproj("canal " + curve + " --first-point 0,1,0 --length 1 -o " + Path("out.obj")),
      "curve.txt:3: 'x' is not a number");
  ExpectOneLineError(Gproj("canal " + Data("canal_curve.txt") +
                           " --first-point -0.5,0.5,2 --lengths 1,2 -o " + Path("out.obj")),
                     "one value per curve point (13)");
  ExpectOneLineError(Gproj("canal " + Data("canal_curve.txt") +
                           " --first-point -0.5,0.5,2 --length 50 -o " + Path("out.obj")),
                     "shorter than the circle's diameter");
  EXPECT_FALSE(Exists("out.obj"));
}

// 000 §4.3 from the command line: beams on the inverted surface of revolution (circular, no
// symmetry left). Planar beams, a parallel offset at the height, axes written as OBJ segments,
// the height gaps lowered by the optimisation; a non-circular mesh and a wrong axes format are
// refused with nothing written; a gap tolerance that is not met exits 3.
TEST_F(SuperCanalCommandTest, BeamsOnACircularMeshArePlanarWithAParallelOffset) {
  ASSERT_EQ(Gproj("invert " + Data("revolution_13x17.obj") + " --centre 2,-1,3 -o " +
                  Path("circular.obj"))
                .exit_code,
            0);
  const CommandRun r =
      Gproj("beams " + Path("circular.obj") + " --height 0.05 -o " + Path("beams.obj") +
            " --axes " + Path("axes.obj") + " --offset " + Path("offset.obj") + " --picture " +
            Path("beams.svg") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  const nlohmann::json& f = report["final"];
  EXPECT_LT(f["max_beam_planarity"].get<double>(), 1e-10);
  EXPECT_LT(f["max_offset_angle"].get<double>(), 1e-10);
  EXPECT_LT(f["max_offset_distance_error"].get<double>(), 1e-10);
  EXPECT_LE(f["max_height_gap"].get<double>(), report["initial"]["max_height_gap"].get<double>());
  EXPECT_EQ(report["command"], "beams");
  const std::string axes = Slurp(dir_ / "axes.obj");
  EXPECT_NE(axes.find("\nl 1 2\n"), std::string::npos);
  EXPECT_NE(Slurp(dir_ / "beams.svg").find("<svg"), std::string::npos);
  EXPECT_NE(r.out.find("height gaps at the nodes"), std::string::npos) << r.out;
  // The offset is a mesh gproj reads back, with the input's size.
  EXPECT_EQ(
      Gproj("beams " + Path("offset.obj") + " --height 0.05 -o " + Path("again.obj")).exit_code, 0);

  ExpectOneLineError(
      Gproj("beams " + Data("noisy_grid_21x21.obj") + " --height 0.05 -o " + Path("out.obj")),
      "not inscribed in a circle");
  ExpectOneLineError(Gproj("beams " + Path("circular.obj") + " --height 0.05 -o " +
                           Path("out.obj") + " --axes " + Path("axes.txt")),
                     "--axes");
  ExpectOneLineError(Gproj("beams " + Path("circular.obj") + " --height 0 -o " + Path("out.obj")),
                     "--height");
  ExpectOneLineError(Gproj("beams " + Path("circular.obj") + " --height 1e300 -o " +
                           Path("out.obj") + " --report " + Path("out.json")),
                     "times the mean edge length");
  EXPECT_FALSE(Exists("out.json"));
  EXPECT_FALSE(Exists("out.obj"));
  const CommandRun strict = Gproj("beams " + Path("circular.obj") + " --height 0.05 -o " +
                                  Path("strict.obj") + " --gap-tolerance 1e-9");
  EXPECT_EQ(strict.exit_code, 3) << strict.err << strict.out;
  EXPECT_NE(strict.err.find("max_height_gap"), std::string::npos) << strict.err;
  EXPECT_TRUE(Exists("strict.obj"));
}

// 000 §4.1 from the command line: the shipped line of curvature and second curve; every sphere
// equidistant from both, the mesh circular, the spheres in the report; mixing in the strip's
// options or leaving out the normal is refused with nothing written.
TEST_F(SuperCanalCommandTest, CanalFromTwoCurvesFitsSpheresAndMeshesCircularQuads) {
  const std::string curves =
      Data("canal_curve_fine.txt") + " --second-curve " + Data("canal_second_curve.txt");
  const CommandRun r = Gproj("canal " + curves + " --normal 0,0,1 --segments 6 -o " +
                             Path("two.obj") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_LT(report["final"]["max_sphere_fit"].get<double>(), 1e-10);
  EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10);
  EXPECT_LT(report["final"]["max_planarity"].get<double>(), 1e-10);
  EXPECT_LT(report["final"]["max_curve1_distance"].get<double>(), 0.05);
  EXPECT_EQ(report["spheres"].size(), 49u);
  EXPECT_GT(report["spheres"][0]["radius"].get<double>(), 0.0);
  EXPECT_NE(r.out.find("max |R_k - dist(C_k, curve 2)|"), std::string::npos) << r.out;
  ExpectOneLineError(Gproj("canal " + curves + " -o " + Path("out.obj")), "--normal");
  ExpectOneLineError(Gproj("canal " + curves + " --normal 0,0,1 --length 2 -o " + Path("out.obj")),
                     "--second-curve");
  ExpectOneLineError(Gproj("canal " + curves + " --normal 0,0,1 --psi 1 -o " + Path("out.obj")),
                     "--psi");
  ExpectOneLineError(
      Gproj("canal " + Data("canal_curve.txt") + " --length 2 -o " + Path("out.obj")),
      "--first-point");
  EXPECT_FALSE(Exists("out.obj"));
}

TEST_F(SuperCanalCommandTest, ClosedCanalClosesTheStripAndTheFrameWhereTheCurveAllows) {
  // The shipped curve lies on a sphere with an odd count: case 2, and a frame that closes.
  const std::string curve = Data("canal_closed_curve.txt");
  const CommandRun r =
      Gproj("canal " + curve +
            " --closed --first-point 3.2,-0.2,0.5 --length 0.5 --normal 1,0,0 "
            "--segments 6 -o " +
            Path("closed.obj") + " --strip " + Path("ring.obj") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("case 2"), std::string::npos) << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["final"]["closing_case"].get<double>(), 2.0);
  EXPECT_GT(report["final"]["start_point_shift"].get<double>(), 0.01);
  EXPECT_LT(report["final"]["frame_closure_deg"].get<double>(), 1e-9);
  EXPECT_LT(report["final"]["max_concyclicity"].get<double>(), 1e-10);
  EXPECT_TRUE(report["mesh"]["closed"].get<bool>());
  EXPECT_EQ(report["lengths"].size(), 21u);
  const PolyMesh mesh = ReadMesh(Path("closed.obj")), ring = ReadMesh(Path("ring.obj"));
  EXPECT_EQ(mesh.n_faces(), 126u);
  EXPECT_EQ(mesh.n_vertices(), 147u);  // a ring: no seam row
  EXPECT_EQ(ring.n_faces(), 21u);
  EXPECT_LT(MeasureCircularity(ring).max_concyclicity, 1e-10);

  // A curve whose reflections turn every frame: the strip closes, the surface cannot; exit 3.
  std::string text;
  for (int k = 0; k < 10; ++k) {
    const double t = 2.0 * M_PI * k / 10;
    text += std::to_string(3.0 * std::cos(t) + 0.3 * std::cos(2.0 * t)) + " " +
            std::to_string(3.0 * std::sin(t)) + " " + std::to_string(0.6 * std::sin(3.0 * t)) +
            "\n";
  }
  const std::string space = Write("space.txt", text);
  const CommandRun open =
      Gproj("canal " + space + " --closed --first-point 2,-1,0 --length 1 -o " + Path("open.obj"));
  EXPECT_EQ(open.exit_code, 3) << open.err << open.out;
  EXPECT_NE(open.out.find("no smooth closed cyclidic net"), std::string::npos) << open.out;
  EXPECT_NE(open.err.find("the frame comes back"), std::string::npos) << open.err;
  // A flat ellipse: the frame closes but the curvature lines across the circles do not; the
  // mesh is written open at P_0 and the run exits 3.
  std::string ellipse;
  for (int k = 0; k < 9; ++k)
    ellipse += std::to_string(3.0 * std::cos(2.0 * M_PI * k / 9)) + " " +
               std::to_string(2.0 * std::sin(2.0 * M_PI * k / 9)) + " 0\n";
  const CommandRun flat = Gproj("canal " + Write("ellipse.txt", ellipse) +
                                " --closed --first-point 3.4,0.2,0 --length 0.4 -o " +
                                Path("e.obj") + " --report " + Path("e.json"));
  EXPECT_EQ(flat.exit_code, 3) << flat.err << flat.out;
  EXPECT_NE(flat.err.find("do not close"), std::string::npos) << flat.err;
  EXPECT_FALSE(Json("e.json")["mesh"]["closed"].get<bool>());
  EXPECT_GT(Json("e.json")["final"]["seam_gap"].get<double>(), 1e-3);
  ExpectOneLineError(
      Gproj("canal " + curve + " --closed --first-point 3.2,-0.2,0.5 --length 0.5 --smooth -o " +
            Path("x.obj")),
      "--smooth");
  ExpectOneLineError(Gproj("canal " + space +
                           " --closed --first-point 3.3,-0.2,0.3 --length 0.4 -o " + Path("x.obj")),
                     "folds quad");
  EXPECT_FALSE(Exists("x.obj"));
}

TEST_F(SuperCanalCommandTest, CanalWritesTheSmoothCyclidicSurface) {
  const CommandRun r = Gproj(
      "canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2 --segments 4 -o " +
      Path("c.obj") + " --surface " + Path("s.obj") + " --surface-segments 5 --surface-picture " +
      Path("s.svg") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["final"]["folded_quads"].get<double>(), 0.0);
  const nlohmann::json& surface = report["surface"];
  EXPECT_EQ(surface["patches"].get<double>(), 12.0);
  EXPECT_LT(surface["max_tangent_angle_deg"].get<double>(), 1e-5);
  EXPECT_LT(surface["max_face_frame_closure_deg"].get<double>(), 1e-9);
  const PolyMesh fine = ReadMesh(Path("s.obj"));
  EXPECT_EQ(fine.n_vertices(), 6u * 61u);  // (1·5 + 1) × (12·5 + 1)
  EXPECT_LT(MeasureCircularity(fine).max_concyclicity, 1e-9);
  EXPECT_TRUE(Exists("s.svg"));
  EXPECT_NE(r.out.find("smooth cyclidic surface"), std::string::npos) << r.out;

  // Closed: the fine mesh welds into a ring.
  const CommandRun closed =
      Gproj("canal " + Data("canal_closed_curve.txt") +
            " --closed --first-point 3.2,-0.2,0.5 --length 0.5 --normal 1,0,0 -o " +
            Path("cc.obj") + " --surface " + Path("cs.obj") + " --surface-segments 4");
  ASSERT_EQ(closed.exit_code, 0) << closed.err << closed.out;
  EXPECT_EQ(ReadMesh(Path("cs.obj")).n_vertices(), 5u * 84u);
  const std::string open = "canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 ";
  ExpectOneLineError(
      Gproj(open + "--length 2 --normal 0.666667,0.517638,0.005556 -o " + Path("x.obj")),
      "along the first edge");
  ExpectOneLineError(Gproj(open + "--length 2 --surface-segments 3 -o " + Path("x.obj")),
                     "--surface-segments");
  ExpectOneLineError(Gproj(open + "--length 0 -o " + Path("x.obj")), "--length");
  ExpectOneLineError(Gproj(open + "--length 2 --frame-tolerance 1 -o " + Path("x.obj")),
                     "--closed");
  // A closed strip whose closing frame turns patches through cone points: the smooth surface
  // pinches, exit 3 with the reason.
  const std::string pinched =
      Write("pinched.txt",
            "2.9999941331895998 0 -0.0059330285673002397\n"
            "2.5200632769705056 1.6195463281038918 0.16232920621342212\n"
            "1.2405409158119767 2.7164056985197247 0.28670248908223106\n"
            "-0.42466865507468721 2.9536353734280265 0.30934546098454396\n"
            "-1.9580790844175293 2.2597437254867772 0.24389463768141756\n"
            "-2.8773376890274331 0.84486257462851 0.084469244665465779\n"
            "-2.8771839112935904 -0.84481742141182881 -0.08997924800966961\n"
            "-1.9582423597782141 -2.2599321552977938 -0.24081842500382086\n"
            "-0.42466029080269302 -2.9535771986384778 -0.30991187311597984\n"
            "1.24058844112127 -2.716509764431092 -0.28550835277944253\n"
            "2.519187200910789 -1.6189833082072798 -0.18052394443252145\n");
  const CommandRun pinch = Gproj("canal " + pinched +
                                 " --closed --first-point 2.456876017858424,-0.4691432830211836,"
                                 "0.008893963253167743 --length 0.2413839908600255 -o " +
                                 Path("p.obj") + " --surface " + Path("ps.obj"));
  EXPECT_EQ(pinch.exit_code, 3) << pinch.err << pinch.out;
  EXPECT_NE(pinch.err.find("folds or pinches"), std::string::npos) << pinch.err;
  EXPECT_TRUE(Exists("ps.obj"));
  // A frame that makes the plane steps cross: crossed quads, exit 3 with the reason.
  const CommandRun crossed =
      Gproj("canal " + Data("canal_curve.txt") +
            " --first-point -0.5,0.5,2 --length 2 --psi 0.5 -o " + Path("crossed.obj"));
  EXPECT_EQ(crossed.exit_code, 3) << crossed.err << crossed.out;
  EXPECT_NE(crossed.err.find("crossed quads"), std::string::npos) << crossed.err;
  ExpectOneLineError(
      Gproj("canal " + Data("canal_curve.txt") + " --first-point -0.5,0.5,2 --length 2 -o " +
            Path("x.obj") + " --surface-picture " + Path("x.obj")),
      "--surface-picture");
  ExpectOneLineError(Gproj("canal " + Data("canal_curve_fine.txt") + " --second-curve " +
                           Data("canal_second_curve.txt") + " --normal 0,0,1 -o " + Path("x.obj") +
                           " --surface " + Path("y.obj")),
                     "--surface");
  EXPECT_FALSE(Exists("x.obj"));
  EXPECT_FALSE(Exists("y.obj"));
}

TEST_F(SuperCanalCommandTest, CyclidicMakesASmoothSurfaceOfACircularMesh) {
  const std::string input = Data("revolution_13x17.obj");
  const CommandRun r = Gproj("cyclidic " + input + " --segments 3 -o " + Path("s.obj") +
                             " --picture " + Path("s.svg") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["final"]["patches"].get<double>(), 192.0);
  EXPECT_LT(report["final"]["max_tangent_angle_deg"].get<double>(), 1e-5);
  EXPECT_LT(report["final"]["fine_max_concyclicity"].get<double>(), 1e-9);
  EXPECT_LT(report["final"]["smoothness_energy"].get<double>(),
            report["initial"]["smoothness_energy"].get<double>());
  const PolyMesh fine = ReadMesh(Path("s.obj"));
  EXPECT_EQ(fine.n_vertices(), 37u * 49u);
  EXPECT_TRUE(Exists("s.svg"));

  const CommandRun given =
      Gproj("cyclidic " + input + " --normal 0,0,1 --segments 2 -o " + Path("n.obj"));
  EXPECT_EQ(given.exit_code, 0) << given.err << given.out;
  EXPECT_NE(given.out.find("frame at vertex 0 from --normal"), std::string::npos) << given.out;

  // ψ and ψ + π give the same frame: its senses are turned towards the first edges (the other
  // sense runs the arcs the long way round and the surface wraps round).
  const CommandRun turned = Gproj("cyclidic " + input + " --normal 1,0,0 --psi 3.14 -o " +
                                  Path("f.obj") + " --report " + Path("f.json"));
  EXPECT_EQ(turned.exit_code, 0) << turned.err << turned.out;
  EXPECT_EQ(Json("f.json")["final"]["long_arcs"].get<double>(), 0.0);
  EXPECT_EQ(Json("f.json")["final"]["folded_fine_quads"].get<double>(), 0.0);
  ExpectOneLineError(Gproj("cyclidic " + Data("noisy_grid_21x21.obj") + " -o " + Path("x.obj")),
                     "is not circular");
  ExpectOneLineError(Gproj("cyclidic " + Data("monkey_saddle_tri.obj") + " -o " + Path("x.obj")),
                     "monkey_saddle_tri.obj");
  EXPECT_FALSE(Exists("x.obj"));
}

}  // namespace
}  // namespace gproj
