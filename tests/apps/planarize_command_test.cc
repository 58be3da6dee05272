// The command line as a user runs it: bad input gives a one-line error naming the file and
// the offending line / face / vertex, exit code 1, and no output file.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"

namespace gproj {
namespace {

namespace fs = std::filesystem;

class PlanarizeCommandTest : public CommandTest {
 protected:
  // Runs planarize on `input`; expects exit 1, an error containing every `parts`, and no output.
  void ExpectRefused(const std::string& input, const std::vector<std::string>& parts,
                     const std::string& extra = "", const std::string& command = "planarize") {
    const fs::path out = dir_ / "out.obj";
    const CommandRun r = Gproj(command + " " + input + " -o " + out.string() + " --report " +
                               (dir_ / "r.json").string() + " " + extra);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    for (const std::string& part : parts) EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(dir_ / "r.json"));
    // One line of error.
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
};

const char* kQuad2x1 =
    "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0.1\nv 2 1 0\n"
    "f 1 2 5 4\nf 2 3 6 5\n";

// 39 variables: 6 vertices and 2 face normals (24), 8 corner-angle and 7 edge-length slacks.
TEST_F(PlanarizeCommandTest, PlanarizesAValidMeshAndWritesReport) {
  const std::string in = Write("in.obj", kQuad2x1);
  const CommandRun r = Gproj("planarize " + in + " -o " + (dir_ / "out.obj").string() +
                             " --report " + (dir_ / "r.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out.obj"));
  const std::string report = Slurp(dir_ / "r.json");
  for (const char* key : {"\"converged\": true", "\"iterations\"", "\"seconds\"",
                          "\"variables\": 39", "\"history\"", "\"max_planarity\""})
    EXPECT_NE(report.find(key), std::string::npos) << key;
  EXPECT_NE(r.out.find("max planarity"), std::string::npos);
  EXPECT_NE(r.out.find("panels: non-convex quads 0 -> 0"), std::string::npos) << r.out;
  EXPECT_NE(report.find("\"non_convex_quads\""), std::string::npos);
  EXPECT_NE(report.find("\"shape_change\""), std::string::npos);
  EXPECT_NE(r.out.find("wrote"), std::string::npos);
}

TEST_F(PlanarizeCommandTest, HoldsTheVerticesOfAFixedFileAndRefusesBadIds) {
  const std::string in = Write("in.obj", kQuad2x1);
  const std::string fixed = Write("fixed.txt", "# the left side\n0\n3 # top left\n");
  const CommandRun r =
      Gproj("planarize " + in + " -o " + (dir_ / "out.obj").string() + " --fixed " + fixed);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PolyMesh out = ReadMesh((dir_ / "out.obj").string());
  EXPECT_EQ(out.point(out.vertex_handle(0)), PolyMesh::Point(0, 0, 0));
  EXPECT_EQ(out.point(out.vertex_handle(3)), PolyMesh::Point(0, 1, 0));
  const std::string bad = Write("bad.txt", "0\n6\n");
  const CommandRun refused =
      Gproj("planarize " + in + " -o " + (dir_ / "out2.obj").string() + " --fixed " + bad);
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("bad.txt:2"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "out2.obj"));
  const CommandRun both = Gproj("planarize " + in + " -o " + (dir_ / "out3.obj").string() +
                                " --fix-boundary --glide-boundary");
  EXPECT_EQ(both.exit_code, 1);
  EXPECT_NE(both.err.find("both fixed and gliding"), std::string::npos) << both.err;
}

TEST_F(PlanarizeCommandTest, WritesFaceValuesAndAColouredHeatmap) {
  const std::string in = Write("in.obj", kQuad2x1);
  const CommandRun r =
      Gproj("planarize " + in + " -o " + (dir_ / "out.obj").string() + " --face-values " +
            (dir_ / "f.csv").string() + " --heatmap " + (dir_ / "h.ply").string() + " --picture " +
            (dir_ / "p.svg").string() + " --report " + (dir_ / "r.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream csv(Slurp(dir_ / "f.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "face,planarity,planarity_abs,kink_deg,min_angle_deg");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 2);
  const std::string ply = Slurp(dir_ / "h.ply");
  EXPECT_NE(ply.find("property uchar red"), std::string::npos);
  EXPECT_EQ(ReadMesh((dir_ / "h.ply").string()).n_faces(), 2u);
  EXPECT_NE(Slurp(dir_ / "r.json").find("\"colour_scale\""), std::string::npos);
  EXPECT_NE(Slurp(dir_ / "p.svg").find("colour: planarity per face"), std::string::npos);
  const CommandRun wrong = Gproj("planarize " + in + " -o " + (dir_ / "o2.obj").string() +
                                 " --heatmap " + (dir_ / "h.obj").string());
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find("--heatmap"), std::string::npos) << wrong.err;
  EXPECT_FALSE(fs::exists(dir_ / "o2.obj"));
}

TEST_F(PlanarizeCommandTest, ANetWritesStarPlanarityFaceValuesAndHeatmap) {
  const std::string grid = (dir_ / "h.obj").string();
  ASSERT_EQ(Gproj("grid --surface hyperboloid --nu 9 --nv 9 --noise 0.05 -o " + grid).exit_code, 0);
  const CommandRun r = Gproj("anet " + grid + " -o " + (dir_ / "a.obj").string() +
                             " --face-values " + (dir_ / "a.csv").string() + " --heatmap " +
                             (dir_ / "a.ply").string() + " --report " + (dir_ / "r.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream csv(Slurp(dir_ / "a.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "face,star_planarity,kink_deg,min_angle_deg");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 64);
  EXPECT_EQ(ReadMesh((dir_ / "a.ply").string()).n_faces(), 64u);
  EXPECT_NE(Slurp(dir_ / "r.json").find("\"star planarity\""), std::string::npos);
  const CommandRun wrong = Gproj("anet " + grid + " -o " + (dir_ / "b.obj").string() +
                                 " --heatmap " + (dir_ / "b.off").string());
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_FALSE(fs::exists(dir_ / "b.obj"));
}

// A jittered grid's boundary is not asymptotic: held or kept on its loops, no A-net fits it,
// and the exit-3 message says why.
TEST_F(PlanarizeCommandTest, ANetWithTheWholeBoundaryHeldSaysWhyItMissesTheTolerance) {
  const std::string grid = (dir_ / "h.obj").string();
  ASSERT_EQ(Gproj("grid --surface hyperboloid --nu 9 --nv 9 --noise 0.05 -o " + grid).exit_code, 0);
  for (const char* control : {" --fix-boundary", " --glide-boundary", ""}) {
    const CommandRun r = Gproj("anet " + grid + " -o " + (dir_ / "a.obj").string() + control);
    const bool noted = r.err.find("over-determines") != std::string::npos;
    if (*control != '\0') {
      EXPECT_EQ(r.exit_code, 3) << control << r.err;
      EXPECT_TRUE(noted) << control << r.err;
    } else {
      EXPECT_EQ(r.exit_code, 0) << r.err;
      EXPECT_FALSE(noted) << r.err;
    }
  }
}

TEST_F(PlanarizeCommandTest, ChecksEveryOutputPathBeforeWorking) {
  const std::string in = Write("in.obj", kQuad2x1);
  const std::string missing = (dir_ / "missing" / "x").string();
  const CommandRun out =
      Gproj("planarize " + in + " -o " + missing + ".obj --report " + (dir_ / "r.json").string());
  EXPECT_EQ(out.exit_code, 1) << out.err;
  EXPECT_NE(out.err.find("--output"), std::string::npos) << out.err;
  EXPECT_NE(out.err.find("does not exist"), std::string::npos) << out.err;
  EXPECT_FALSE(fs::exists(dir_ / "r.json")) << "the report was written for a refused run";
  for (const auto& [option, extra] : std::vector<std::pair<std::string, std::string>>{
           {"--report", "--report " + missing}, {"--picture", "--picture " + missing}}) {
    const CommandRun r =
        Gproj("planarize " + in + " -o " + (dir_ / "out.obj").string() + " " + extra);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.obj")) << "the mesh was written before the check";
  }
  const CommandRun stl = Gproj("planarize " + in + " -o " + (dir_ / "out.stl").string());
  EXPECT_EQ(stl.exit_code, 1);
  EXPECT_NE(stl.err.find(".stl"), std::string::npos) << stl.err;
}

TEST_F(PlanarizeCommandTest, AStalledRunIsNotConvergence) {
  // Fixed soft weights stall far above the tolerance: the step tolerance is met, the asked
  // planarity is not, so the exit code is 3 and the report says converged: false.
  const std::string in = Write("in.obj", kQuad2x1);
  const CommandRun r =
      Gproj("planarize " + in + " -o " + (dir_ / "out.obj").string() +
            " --soft-decay 1 --soft-floor 1 --closeness 10 --report " + (dir_ / "r.json").string());
  EXPECT_EQ(r.exit_code, 3) << r.err << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "out.obj"));
  const std::string report = Slurp(dir_ / "r.json");
  EXPECT_NE(report.find("\"converged\": false"), std::string::npos) << report;
  EXPECT_NE(r.err.find("tolerance"), std::string::npos) << r.err;
}

TEST_F(PlanarizeCommandTest, ReportHasTheSharedSchema) {
  const std::string in = Write("in.obj", kQuad2x1);
  for (const char* solver : {"gp", "ceres"}) {
    const CommandRun r =
        Gproj("planarize " + in + " -o " + (dir_ / "out.obj").string() + " --solver " + solver +
              " --tolerance 1e-6 --report " + (dir_ / "r.json").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string report = Slurp(dir_ / "r.json");
    for (const char* key :
         {"\"command\": \"planarize\"", "\"solver\"", "\"failed\": false", "\"termination\"",
          "\"initial\"", "\"final\"", "\"history\"", "\"families\"", "\"step\"", "\"energy\""})
      EXPECT_NE(report.find(key), std::string::npos) << solver << " " << key;
  }
}

TEST_F(PlanarizeCommandTest, CeresSolverPathWorks) {
  const std::string in = Write("in.obj", kQuad2x1);
  const CommandRun r =
      Gproj("planarize " + in + " -o " + (dir_ / "out.off").string() + " --solver ceres");
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "out.off"));
}

TEST_F(PlanarizeCommandTest, RefusesEmptyFile) {
  const std::string in = Write("empty.obj", "");
  ExpectRefused(in, {"empty.obj", "empty"});
}

TEST_F(PlanarizeCommandTest, RefusesUnreadableFile) {
  ExpectRefused((dir_ / "missing.obj").string(), {"missing.obj"});
  fs::create_directories(dir_ / "folder.obj");
  ExpectRefused((dir_ / "folder.obj").string(), {"folder.obj"});
}

TEST_F(PlanarizeCommandTest, RefusesNonFiniteCoordinates) {
  const std::string in = Write("nan.obj", "v 0 0 0\nv 1 0 nan\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  ExpectRefused(in, {"nan.obj:2", "vertex 1", "non-finite"});
  const std::string inf = Write("inf.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 inf 0\n0 1 0\n4 0 1 2 3\n");
  ExpectRefused(inf, {"inf.off:5", "non-finite"});
}

TEST_F(PlanarizeCommandTest, RefusesFaceIndexOutOfRange) {
  const std::string in = Write("range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 9\n");
  ExpectRefused(in, {"range.obj:5", "face 0", "vertex 8"});
}

// Polygon meshes are taken (tests/apps/polygon_planarize_command_test.cc), but not a mesh of
// triangles only, nor a circular run with a face that is not a quad.
TEST_F(PlanarizeCommandTest, RefusesTriangleMeshesAndCircularNonQuads) {
  const std::string mixed =
      Write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3\n");
  ExpectRefused(mixed, {"mixed.obj: face 1 has 3 vertices; a circular mesh is made of quads"},
                "--circular");
  const std::string tri = Write("tri.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  ExpectRefused(tri, {"tri.obj: every face is a triangle", "gproj dual"});
}

TEST_F(PlanarizeCommandTest, RefusesDegenerateFaces) {
  const std::string repeated = Write("rep.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3 2\n");
  ExpectRefused(repeated, {"rep.obj:4", "face 0"});
  const std::string collinear =
      Write("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3 4\n");
  ExpectRefused(collinear, {"line.obj:5", "face 0", "degenerate"});
}

TEST_F(PlanarizeCommandTest, RefusesNonManifoldEdges) {
  // Three quads share the edge 1-2.
  const std::string in =
      Write("nm.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 -1 0\nv 1 -1 0\nv 0 0 1\nv 1 0 1\n"
            "f 1 2 4 3\nf 2 1 5 6\nf 1 2 8 7\n");
  ExpectRefused(in, {"nm.obj:11", "face 2", "non-manifold"});
}

TEST_F(PlanarizeCommandTest, RefusesInvalidOptionValues) {
  const std::string in = Write("in.obj", kQuad2x1);
  ExpectRefused(in, {"--tolerance"}, "--tolerance -1");
  ExpectRefused(in, {"--solver"}, "--solver newton");
  ExpectRefused(in, {"--max-iterations"}, "--max-iterations many");
  ExpectRefused(in, {"closeness"}, "--closeness nan");
}

// A 2 × 2-quad grid along the rulings of z = x y: an exact A-net.
const char* kHypar3x3 =
    "v -1 -1 1\nv -1 0 0\nv -1 1 -1\nv 0 -1 0\nv 0 0 0\nv 0 1 0\nv 1 -1 -1\nv 1 0 0\nv 1 1 1\n"
    "f 1 4 5 2\nf 2 5 6 3\nf 4 7 8 5\nf 5 8 9 6\n";

TEST_F(PlanarizeCommandTest, ANetUsesTheSharedRunLayer) {
  // A jittered hypar grid: one iteration cannot make the stars planar, so the run ends with
  // exit 3 and converged: false; the report has the shared keys and the star measures.
  const std::string in = Write("hypar.obj",
                               "v -1 -1 1\nv -1 0 0.05\nv -1 1 -1\nv 0 -1 0\nv 0 0 0.04\n"
                               "v 0 1 0\nv 1 -1 -1\nv 1 0 0\nv 1 1 1\n"
                               "f 1 4 5 2\nf 2 5 6 3\nf 4 7 8 5\nf 5 8 9 6\n");
  const CommandRun r = Gproj("anet " + in + " -o " + (dir_ / "a.obj").string() +
                             " --max-iterations 1 --report " + (dir_ / "r.json").string());
  EXPECT_EQ(r.exit_code, 3) << r.err << r.out;
  const std::string report = Slurp(dir_ / "r.json");
  for (const char* key : {"\"command\": \"anet\"", "\"converged\": false", "\"failed\": false",
                          "\"max_star_planarity\"", "\"families\""})
    EXPECT_NE(report.find(key), std::string::npos) << key;
  const CommandRun bad = Gproj("anet " + in + " -o " + (dir_ / "missing" / "a.obj").string());
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--output"), std::string::npos) << bad.err;
}

TEST_F(PlanarizeCommandTest, HNetWritesPatchesSurfaceAndReport) {
  const std::string in = Write("hypar.obj", kHypar3x3);
  const CommandRun r =
      Gproj("hnet " + in + " -o " + (dir_ / "h.json").string() + " --surface-mesh " +
            (dir_ / "s.obj").string() + " --samples 4 --picture " + (dir_ / "p.svg").string() +
            " --report " + (dir_ / "r.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
  const std::string hnet = Slurp(dir_ / "h.json");
  for (const char* key : {"\"vertices\"", "\"faces\"", "\"weights\""})
    EXPECT_NE(hnet.find(key), std::string::npos) << key;
  // 4 patches sampled 5 × 5, welded along their common edges: 9 × 9 distinct vertices, every
  // inner vertex in 6 triangles (one piece, no seams).
  const PolyMesh surface = ReadMesh((dir_ / "s.obj").string());
  EXPECT_EQ(surface.n_vertices(), 81u);
  EXPECT_EQ(surface.n_faces(), 4u * 2u * 16u);
  std::set<std::array<double, 3>> distinct;
  for (auto v : surface.vertices()) {
    const auto& p = surface.point(v);
    distinct.insert({p[0], p[1], p[2]});
    if (!surface.is_boundary(v)) EXPECT_EQ(surface.valence(v), 6u) << "vertex " << v.idx();
  }
  EXPECT_EQ(distinct.size(), 81u);
  const nlohmann::json report = nlohmann::json::parse(Slurp(dir_ / "r.json"));
  EXPECT_EQ(report["command"], "hnet");
  EXPECT_TRUE(report["converged"].get<bool>());
  EXPECT_LT(report["final"]["max_tangent_angle_deg"].get<double>(), 1e-3);
  EXPECT_LE(report["final"]["weight_change"].get<double>(), 1e-6);
  // The report names what its tolerance bounds (as the service's and Python's do).
  EXPECT_EQ(report["tolerance_measure"], "weight_change");
  EXPECT_LE(report["final"]["weight_change"].get<double>(), report["tolerance"].get<double>());
  EXPECT_GE(report["rounds"].size(), 2u);
  EXPECT_TRUE(report["simply_connected"].get<bool>());
  EXPECT_EQ(Slurp(dir_ / "p.svg").rfind("<svg", 0), 0u);
}

// The cross-check from the command line: A-net and H-net by Ceres' Levenberg–Marquardt on the
// same rows, judged by the same tolerances.
TEST_F(PlanarizeCommandTest, ANetAndHNetRunTheCeresCrossCheck) {
  const std::string jittered = Write("jittered.obj",
                                     "v -1 -1 1\nv -1 0 0.05\nv -1 1 -1\nv 0 -1 0\nv 0 0 0.04\n"
                                     "v 0 1 0\nv 1 -1 -1\nv 1 0 0\nv 1 1 1\n"
                                     "f 1 4 5 2\nf 2 5 6 3\nf 4 7 8 5\nf 5 8 9 6\n");
  const CommandRun a =
      Gproj("anet " + jittered + " -o " + (dir_ / "a.obj").string() +
            " --solver ceres --tolerance 1e-6 --report " + (dir_ / "a.json").string());
  EXPECT_EQ(a.exit_code, 0) << a.err << a.out;
  const nlohmann::json anet = nlohmann::json::parse(Slurp(dir_ / "a.json"));
  EXPECT_EQ(anet["solver"], "ceres");
  EXPECT_LE(anet["final"]["max_star_planarity"].get<double>(), 1e-6);
  EXPECT_GT(anet["initial"]["max_star_planarity"].get<double>(), 1e-3);

  const std::string hypar = Write("hypar.obj", kHypar3x3);
  const CommandRun h = Gproj("hnet " + hypar + " -o " + (dir_ / "h.json").string() +
                             " --solver ceres --report " + (dir_ / "h_report.json").string());
  EXPECT_EQ(h.exit_code, 0) << h.err << h.out;
  const nlohmann::json hnet = nlohmann::json::parse(Slurp(dir_ / "h_report.json"));
  EXPECT_TRUE(hnet["converged"].get<bool>());
  EXPECT_LT(hnet["final"]["max_tangent_angle_deg"].get<double>(), 1e-3);
}

// One round cannot show the weights settled: exit 3, the patches and the report written.
TEST_F(PlanarizeCommandTest, HNetWithoutSettledWeightsExitsThree) {
  const std::string in = Write("hypar.obj", kHypar3x3);
  const CommandRun r = Gproj("hnet " + in + " -o " + (dir_ / "h.json").string() +
                             " --rounds 1 --report " + (dir_ / "r.json").string());
  EXPECT_EQ(r.exit_code, 3) << r.err << r.out;
  EXPECT_NE(r.err.find("not reached (weight_change"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "h.json"));
  const nlohmann::json report = nlohmann::json::parse(Slurp(dir_ / "r.json"));
  EXPECT_FALSE(report["converged"].get<bool>());
  EXPECT_EQ(report["status"], "NO_CONVERGENCE");
  EXPECT_EQ(report["termination"],
            "NO_CONVERGENCE: the problem's tolerance is not met (maximum number of rounds "
            "reached)");
}

TEST_F(PlanarizeCommandTest, ANetRefusesOddValenceAndNonQuads) {
  // Three quads around vertex 1: inner valence 3.
  const std::string odd =
      Write("odd.obj",
            "v 0 0 0\nv 1 0 0\nv 0.8 0.9 0.1\nv -0.5 0.9 0\nv -1 0 0.1\nv -0.5 -0.9 0\n"
            "v 0.8 -0.9 0.1\nf 1 2 3 4\nf 1 4 5 6\nf 1 6 7 2\n");
  const CommandRun r = Gproj("anet " + odd + " -o " + (dir_ / "a.obj").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("odd.obj: vertex 0 has valence 3"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "a.obj"));
  const std::string tri = Write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const CommandRun t = Gproj("hnet " + tri + " -o " + (dir_ / "h.json").string());
  EXPECT_EQ(t.exit_code, 1);
  EXPECT_NE(t.err.find("tri.obj:4: face 0 has 3 vertices"), std::string::npos) << t.err;
  EXPECT_FALSE(fs::exists(dir_ / "h.json"));
}

using MarionetteCommandTest = PlanarizeCommandTest;

// A 2 × 2-face plan view in grid order (z ignored).
const char* kPlan2x2 =
    "v 0 0 0\nv 0 1 0\nv 0 2 0\nv 1 0.1 0\nv 1.1 1 0\nv 1 2.1 0\nv 2 0 0\nv 2 1.2 0\nv 2.1 2 0\n"
    "f 1 4 5 2\nf 2 5 6 3\nf 4 7 8 5\nf 5 8 9 6\n";

TEST_F(MarionetteCommandTest, LiftsFromGuideCurvesWithBothSolvers) {
  const std::string plan = Write("plan.obj", kPlan2x2);
  for (const char* solver : {"direct", "gp"}) {
    const CommandRun r = Gproj("marionette " + plan + " -o " + (dir_ / "m.obj").string() +
                               " --row 0,0.5,0.2 --column 0,0.3,0.1 --solver " + solver +
                               " --report " + (dir_ / "r.json").string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(Slurp(dir_ / "r.json").find("max_planarity"), std::string::npos);
    EXPECT_NE(Slurp(dir_ / "m.obj").find("v 1.1 1 0."), std::string::npos) << "x, y kept";
  }
}

TEST_F(MarionetteCommandTest, RefusesDegeneratePlanAndIncompatibleGuides) {
  // Vertex (0, 1) moved onto the line through (0, 0) and (1, 0): face 0 is degenerate.
  std::string text = kPlan2x2;
  text.replace(text.find("v 0 1 0"), 7, "v 0.5 0.05 0");
  const std::string bad = Write("bad.obj", text);
  ExpectRefused(bad, {"bad.obj: face 0 has a degenerate plan view"}, "--row 0,0,0 --column 0,0,0",
                "marionette");
  const std::string plan = Write("plan.obj", kPlan2x2);
  const CommandRun r = Gproj("marionette " + plan + " -o " + (dir_ / "m.obj").string() +
                             " --row 0,0.5,0.2 --column 1,0.3,0.1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("incompatible guide curves"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "m.obj"));
}

TEST_F(PlanarizeCommandTest, HelpExplainsEveryOption) {
  const CommandRun r = Gproj("planarize --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option : {"--output", "--report", "--solver", "--max-iterations", "--tolerance",
                             "--closeness", "--fairness", "--linear-solver"})
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
}

}  // namespace
}  // namespace gproj
