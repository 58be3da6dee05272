// `gproj anet --net diagonal` as a user runs it: a generated net whose diagonals are asymptotic
// (`gproj grid --diagonal`), against the edge net's run on the same mesh.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/nets/anet.h"

namespace gproj {
namespace {

class NetsCommandTest : public CommandTest {};

TEST_F(NetsCommandTest, DiagonalNetOfATurnedEnneperGrid) {
  const CommandRun grid = Gproj(
      "grid --surface enneper --diagonal --nu 17 --nv 17 --noise 0.05 "
      "--seed 9 -o " +
      Path("grid.obj"));
  ASSERT_EQ(grid.exit_code, 0) << grid.err;
  EXPECT_NE(grid.out.find("diagonals along the net"), std::string::npos) << grid.out;
  const CommandRun diagonal =
      Gproj("anet " + Path("grid.obj") + " --net diagonal -o " + Path("d.obj") + " --report " +
            Path("d.json") + " --heatmap " + Path("d.ply"));
  ASSERT_EQ(diagonal.exit_code, 0) << diagonal.err << diagonal.out;
  const nlohmann::json d = Json("d.json");
  EXPECT_EQ(d["net"], "diagonal");
  EXPECT_EQ(d["options"]["net"], "diagonal");
  EXPECT_EQ(d["colour_scale"]["measure"], "diagonal star planarity");
  EXPECT_LE(d["final"]["max_star_planarity"].get<double>(), 1e-9);
  EXPECT_EQ(d["final"]["non_convex_quads"], 0);
  EXPECT_LT(d["final"]["max_displacement"].get<double>(), 0.01);
  EXPECT_NE(diagonal.out.find("max diagonal star planarity"), std::string::npos);
  EXPECT_EQ(diagonal.err.find("far from"), std::string::npos) << diagonal.err;
  // The written mesh: the input's quads, diagonal stars planar.
  const PolyMesh input = ReadMesh(Path("grid.obj")), result = ReadMesh(Path("d.obj"));
  ASSERT_EQ(result.n_faces(), input.n_faces());
  EXPECT_LE(nets::MeasureStarPlanarity(result, input, nets::NetKind::kDiagonals).max_star_planarity,
            1e-8);

  // The edge net of the same mesh is another problem: it moves the mesh far.
  const CommandRun edges =
      Gproj("anet " + Path("grid.obj") + " -o " + Path("e.obj") + " --report " + Path("e.json"));
  EXPECT_NE(edges.err.find("far from an A-net"), std::string::npos) << edges.err;
  EXPECT_GT(Json("e.json")["final"]["max_displacement"].get<double>(), 0.05);
  EXPECT_EQ(Json("e.json")["net"], "edges");
}

// hnet --net diagonal: the H-net of each diagonal mesh (one per colour), its vertices the
// input's of that colour; the edge net of the same mesh does not settle.
TEST_F(NetsCommandTest, HNetOfTheDiagonalMeshes) {
  ASSERT_EQ(Gproj("grid --surface hyperboloid --diagonal --nu 13 --nv 13 --noise 0.03 -o " +
                  Path("grid.obj"))
                .exit_code,
            0);
  const PolyMesh input = ReadMesh(Path("grid.obj"));
  for (int colour : {0, 1}) {
    const std::string out = "h" + std::to_string(colour);
    const CommandRun run = Gproj("hnet " + Path("grid.obj") + " --net diagonal --diagonal-colour " +
                                 std::to_string(colour) + " -o " + Path(out + ".json") +
                                 " --report " + Path(out + "_report.json"));
    ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
    EXPECT_NE(run.out.find("diagonal mesh of colour " + std::to_string(colour)), std::string::npos)
        << run.out;
    const nlohmann::json report = Json(out + "_report.json");
    EXPECT_EQ(report["net"], "diagonal");
    EXPECT_LE(report["final"]["max_tangent_angle_deg"].get<double>(), 1e-6);
    const nlohmann::json hnet = Json(out + ".json");
    ASSERT_EQ(hnet["input_vertices"].size(), hnet["vertices"].size());
    EXPECT_EQ(hnet["input_vertices"], report["input_vertices"]);
    // Each H-net vertex near its input vertex (the A-net step moves them a little).
    for (std::size_t k = 0; k < hnet["vertices"].size(); ++k) {
      const auto& p = input.point(PolyMesh::VertexHandle(hnet["input_vertices"][k].get<int>()));
      const auto& q = hnet["vertices"][k];
      const double d = std::hypot(q[0].get<double>() - p[0], q[1].get<double>() - p[1],
                                  q[2].get<double>() - p[2]);
      EXPECT_LT(d, 0.05) << k;
    }
  }
  EXPECT_EQ(Json("h0.json")["vertices"].size() + Json("h1.json")["vertices"].size(),
            input.n_vertices() - 4);  // the four corners are on no ring
  // A held vertex of the other colour is named with the option that takes it.
  const CommandRun fixed = Gproj("hnet " + Path("grid.obj") + " --net diagonal --fixed " +
                                 Write("fixed.txt", "1\n") + " -o " + Path("f.json"));
  EXPECT_EQ(fixed.exit_code, 1);
  ExpectOneLineError(fixed, "--fixed: vertex 1 is not on the diagonal mesh of colour 0");
  EXPECT_NE(fixed.err.find("--diagonal-colour 1"), std::string::npos) << fixed.err;
  EXPECT_FALSE(Exists("f.json"));
}

// A real mesh: ArchGeo's complete01 (holes, singular vertices), an A-net on its diagonals to
// 5e-6 as shipped. anet --net diagonal finishes it without moving it; the edge net cannot be
// reached near it; each diagonal mesh extends to an H-net (the rings of singular vertices open).
TEST_F(NetsCommandTest, ArchGeoSampleIsAnANetOnItsDiagonals) {
  const std::string mesh = std::string(GPROJ_SOURCE_DIR) + "/tests/data/archgeo_complete01.obj";
  const CommandRun diagonal =
      Gproj("anet " + mesh + " --net diagonal -o " + Path("d.obj") + " --report " + Path("d.json"));
  ASSERT_EQ(diagonal.exit_code, 0) << diagonal.err;
  const nlohmann::json d = Json("d.json");
  EXPECT_LT(d["initial"]["max_star_planarity"].get<double>(), 1e-5);
  EXPECT_LE(d["final"]["max_star_planarity"].get<double>(), 1e-9);
  EXPECT_LE(d["iterations"].get<int>(), 5);
  EXPECT_LT(d["final"]["max_displacement"].get<double>(), 1e-5);
  EXPECT_EQ(d["final"]["non_convex_quads"], 0);
  const CommandRun edges =
      Gproj("anet " + mesh + " -o " + Path("e.obj") + " --report " + Path("e.json"));
  EXPECT_EQ(edges.exit_code, 3);
  EXPECT_GT(Json("e.json")["initial"]["max_star_planarity"].get<double>(), 0.1);

  const CommandRun refused =
      Gproj("hnet " + mesh + " --net diagonal --diagonal-colour 1 -o " + Path("r.json"));
  EXPECT_EQ(refused.exit_code, 1);
  ExpectOneLineError(refused, "not simply connected");
  EXPECT_NE(refused.err.find("8 rings of singular vertices"), std::string::npos) << refused.err;
  for (int colour : {0, 1}) {
    const std::string out = "h" + std::to_string(colour);
    const CommandRun hnet = Gproj("hnet " + mesh +
                                  " --net diagonal --allow-not-simply-connected "
                                  "--diagonal-colour " +
                                  std::to_string(colour) + " -o " + Path(out + ".json") +
                                  " --report " + Path(out + "_r.json"));
    ASSERT_EQ(hnet.exit_code, 0) << hnet.err << hnet.out;
    const nlohmann::json r = Json(out + "_r.json");
    EXPECT_LE(r["final"]["max_tangent_angle_deg"].get<double>(), 1e-8);
    EXPECT_EQ(r["final"]["non_convex_quads"], 0);
    EXPECT_LT(r["final"]["max_reference_distance"].get<double>(), 1e-3);
    EXPECT_EQ(r["open_rings"].size(), colour == 0 ? 0u : 8u);
  }
}

// Quads of a written H-net file whose bilinear patch folds: its normal x_u × x_v, sampled on a
// 9 × 9 grid, turns 90° or more away from the normal at the patch's centre somewhere.
int CountFoldedPatches(const nlohmann::json& hnet) {
  int folded = 0;
  for (const auto& face : hnet["faces"]) {
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c) p[k][c] = hnet["vertices"][face[k].get<int>()][c];
    auto normal = [&p](double u, double v) {
      const Eigen::Vector3d xu = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
      const Eigen::Vector3d xv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
      return Eigen::Vector3d(xu.cross(xv));
    };
    const Eigen::Vector3d centre = normal(0.5, 0.5);
    bool folds = false;
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) folds = folds || !(normal(i / 8.0, j / 8.0).dot(centre) > 0.0);
    folded += folds;
  }
  return folded;
}

// ArchGeo's sample optimised as an H-net on its edges (its diagonals, not its edges, are the
// asymptotic ones): no H-net exists near it, and the joint solve of vertices and weights pulls
// quads towards folding. The vertex updates keep the A-net step's corner bounds: the run ends at
// exit 3 with no patch folded (counted here independently) and names the quads held at the
// bound; with --allow-folds the same run folds hundreds and the log names them.
TEST_F(NetsCommandTest, HNetJointSolveKeepsTheCornerBounds) {
  const std::string base = "hnet " + std::string(GPROJ_SOURCE_DIR) +
                           "/tests/data/archgeo_complete01.obj --allow-not-simply-connected";
  const CommandRun bounded =
      Gproj(base + " -o " + Path("b.json") + " --report " + Path("b_r.json"));
  ASSERT_EQ(bounded.exit_code, 3) << bounded.err;
  const nlohmann::json b = Json("b_r.json");
  const size_t at_bound = b["faces_at_angle_bound"].size();
  EXPECT_GT(at_bound, 100u);
  EXPECT_NE(bounded.err.find(std::to_string(at_bound) +
                             " quads sit on their corner-angle bound (--min-angle 5)"),
            std::string::npos)
      << bounded.err;
  EXPECT_EQ(CountFoldedPatches(Json("b.json")), 0);
  EXPECT_EQ(b["final"]["non_convex_quads"], 0);
  EXPECT_GT(b["final"]["min_corner_angle_deg"].get<double>(), 4.5);
  EXPECT_EQ(bounded.err.find("not convex"), std::string::npos) << bounded.err;

  const CommandRun folds =
      Gproj(base + " --allow-folds -o " + Path("f.json") + " --report " + Path("f_r.json"));
  ASSERT_EQ(folds.exit_code, 3) << folds.err;
  const nlohmann::json f = Json("f_r.json");
  const int folded = CountFoldedPatches(Json("f.json"));
  EXPECT_GT(folded, 100);
  // Folds squash some patches to slivers where the two counts part on rounding.
  EXPECT_NEAR(f["final"]["non_convex_quads"].get<int>(), folded, 0.05 * folded);
  EXPECT_NE(folds.err.find(std::to_string(f["final"]["non_convex_quads"].get<int>()) +
                           " quads are not convex"),
            std::string::npos)
      << folds.err;
  EXPECT_TRUE(f["faces_at_angle_bound"].empty());
}

TEST_F(NetsCommandTest, DiagonalGridNotForRevolution) {
  const CommandRun run = Gproj("grid --surface revolution --diagonal -o " + Path("p.obj"));
  EXPECT_EQ(run.exit_code, 1);
  ExpectOneLineError(run, "--diagonal");
  EXPECT_FALSE(Exists("p.obj"));
  const CommandRun net = Gproj("anet " + Path("p.obj") + " --net diagonals -o " + Path("x.obj"));
  EXPECT_EQ(net.exit_code, 1);
  ASSERT_EQ(Gproj("grid --surface hypar --nu 5 --nv 5 -o " + Path("g.obj")).exit_code, 0);
  const CommandRun colour =
      Gproj("hnet " + Path("g.obj") + " --diagonal-colour 1 -o " + Path("h.json"));
  EXPECT_EQ(colour.exit_code, 1);
  ExpectOneLineError(colour, "--diagonal-colour chooses a diagonal mesh: it needs --net diagonal");
  EXPECT_FALSE(Exists("h.json"));
}

// The largest planarity of the rings of the inner vertices (each ring's diagonal distance /
// its mean edge): the faces of the diagonal meshes.
double MaxRingPlanarity(const PolyMesh& quads) {
  double worst = 0.0;
  for (auto v : quads.vertices()) {
    if (quads.is_boundary(v) || quads.valence(v) != 4) continue;
    std::vector<Eigen::Vector3d> p;
    for (auto w : quads.vv_ccw_range(v)) p.emplace_back(quads.point(w).data());
    const Eigen::Vector3d d1 = p[2] - p[0], d2 = p[3] - p[1];
    const Eigen::Vector3d n = d1.cross(d2);
    const double mean = 0.25 * ((p[1] - p[0]).norm() + (p[2] - p[1]).norm() + (p[3] - p[2]).norm() +
                                (p[0] - p[3]).norm());
    // The distance between the two diagonals' lines.
    worst = std::max(worst, std::abs((p[1] - p[0]).dot(n)) / n.norm() / mean);
  }
  return worst;
}

// planarize --net diagonal: a noisy paraboloid grid turned by 45 degrees, whose diagonals follow
// the conjugate x and y lines: the rings of the inner vertices become planar while the mesh keeps
// its quads; with one colour the other's vertices stay where they were.
TEST_F(NetsCommandTest, PlanarDiagonalMeshes) {
  const CommandRun grid =
      Gproj("grid --diagonal --nu 15 --nv 15 --a 0.3 --b -0.2 --noise 0.05 -o " + Path("grid.obj"));
  ASSERT_EQ(grid.exit_code, 0) << grid.err;
  const PolyMesh input = ReadMesh(Path("grid.obj"));
  const double start = MaxRingPlanarity(input);
  EXPECT_GT(start, 0.01);
  const CommandRun both =
      Gproj("planarize " + Path("grid.obj") + " --net diagonal -o " + Path("p.obj") +
            " --diagonal-mesh " + Path("rings.obj") + " --report " + Path("p.json"));
  ASSERT_EQ(both.exit_code, 0) << both.err << both.out;
  EXPECT_NE(both.out.find("both diagonal meshes"), std::string::npos) << both.out;
  const nlohmann::json report = Json("p.json");
  EXPECT_EQ(report["net"], "diagonal");
  EXPECT_EQ(report["diagonal_face_centres"].size(), 13u * 13u);
  EXPECT_LT(report["final"]["max_displacement"].get<double>(), 0.01);
  const PolyMesh result = ReadMesh(Path("p.obj")), rings = ReadMesh(Path("rings.obj"));
  ASSERT_EQ(result.n_faces(), input.n_faces());
  for (auto f : result.faces()) {
    auto a = result.cfv_begin(f), b = input.cfv_begin(input.face_handle(f.idx()));
    for (; a.is_valid(); ++a, ++b) ASSERT_EQ(a->idx(), b->idx());
  }
  EXPECT_EQ(rings.n_faces(), 13u * 13u);
  const double end = MaxRingPlanarity(result);
  std::printf("rings of a turned paraboloid grid: planarity %.2e -> %.2e, moved %.2e\n", start, end,
              report["final"]["max_displacement"].get<double>());
  EXPECT_LE(end, 2e-6);
  // One diagonal mesh: the vertices of the other colour keep their place, bit for bit.
  const CommandRun one = Gproj("planarize " + Path("grid.obj") +
                               " --net diagonal --diagonal-colour 1 -o " + Path("one.obj"));
  ASSERT_EQ(one.exit_code, 0) << one.err << one.out;
  const PolyMesh moved = ReadMesh(Path("one.obj"));
  int still = 0;
  for (auto v : moved.vertices()) still += moved.point(v) == input.point(v);
  EXPECT_GE(still, static_cast<int>(input.n_vertices()) / 2 - 1);
  EXPECT_LT(still, static_cast<int>(input.n_vertices()));
  // No quad of the result folds across a diagonal (the triangles of both splits face the same
  // way), and the report says so.
  EXPECT_EQ(report["quads"]["folded"], 0);
  for (auto f : result.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto v : result.fv_range(f)) p.emplace_back(result.point(v).data());
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector3d n1 = (p[k + 1] - p[k]).cross(p[k + 2] - p[k]);
      const Eigen::Vector3d n2 = (p[k + 2] - p[k]).cross(p[(k + 3) % 4] - p[k]);
      EXPECT_GT(n1.dot(n2), 0.0) << "quad " << f.idx();
    }
  }
  // A grid whose diagonals are asymptotic (the turned hypar): its rings become planar only by
  // folding quads across their diagonals, which is no valid result (exit 3, named, written).
  ASSERT_EQ(
      Gproj("grid --surface hypar --diagonal --nu 15 --nv 15 -o " + Path("hypar.obj")).exit_code,
      0);
  const CommandRun hypar = Gproj("planarize " + Path("hypar.obj") + " --net diagonal -o " +
                                 Path("hp.obj") + " --report " + Path("hp.json"));
  EXPECT_EQ(hypar.exit_code, 3) << hypar.err << hypar.out;
  EXPECT_NE((hypar.out + hypar.err).find("fold across a diagonal"), std::string::npos)
      << hypar.out << hypar.err;
  EXPECT_GT(Json("hp.json")["quads"]["folded"].get<int>(), 0);
  // Refused: a diagonal colour without net diagonal, circular with it, the rings' output
  // without it.
  ExpectOneLineError(
      Gproj("planarize " + Path("grid.obj") + " --diagonal-colour 0 -o " + Path("x.obj")),
      "--diagonal-colour");
  ExpectOneLineError(
      Gproj("planarize " + Path("grid.obj") + " --net diagonal --circular -o " + Path("x.obj")),
      "--circular");
  EXPECT_FALSE(Exists("x.obj"));
  // The rings' output without net diagonal: a warning, nothing written for it.
  const CommandRun edges = Gproj("planarize " + Path("grid.obj") + " --diagonal-mesh " +
                                 Path("r.obj") + " -o " + Path("e.obj"));
  EXPECT_EQ(edges.exit_code, 0) << edges.err;
  EXPECT_NE(edges.err.find("--diagonal-mesh " + Path("r.obj") + " was not written"),
            std::string::npos)
      << edges.err;
  EXPECT_FALSE(Exists("r.obj"));
}

}  // namespace
}  // namespace gproj
