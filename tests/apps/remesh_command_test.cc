// `gproj remesh` as a user runs it, on the shipped triangle mesh.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"
#include "triangulated_surface_util.h"

namespace gproj {
namespace {

class RemeshCommandTest : public CommandTest {};

// `mesh` without the faces whose centroid lies over one of two discs in the plan (two holes in
// the monkey saddle), and without the vertices left unused.
PolyMesh WithTwoHoles(const PolyMesh& mesh) {
  PolyMesh holed;
  std::vector<int> index(mesh.n_vertices(), -1);
  for (auto f : mesh.faces()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (auto v : mesh.fv_range(f)) c += Eigen::Vector3d(mesh.point(v).data()) / mesh.valence(f);
    if (std::hypot(c.x() - 0.45, c.y() - 0.2) < 0.2 || std::hypot(c.x() + 0.3, c.y() + 0.45) < 0.2)
      continue;
    std::vector<PolyMesh::VertexHandle> corners;
    for (auto v : mesh.fv_range(f)) {
      if (index[v.idx()] < 0) index[v.idx()] = holed.add_vertex(mesh.point(v)).idx();
      corners.push_back(holed.vertex_handle(index[v.idx()]));
    }
    holed.add_face(corners);
  }
  return holed;
}

// The shipped monkey saddle remeshed along its asymptotic directions: quads only, one vertex of
// valence 6 at the flat point (004 Theorem 6), every other inner vertex of valence 4; the
// report, the field and the picture written.
TEST_F(RemeshCommandTest, MonkeySaddleAlongItsAsymptoticDirections) {
  const CommandRun r =
      Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("quads.obj") +
            " --edge-length 0.15 --field " + Path("field.obj") + " --picture " + Path("quads.svg") +
            " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["command"], "remesh");
  ASSERT_EQ(report["singularities"].size(), 1u);
  EXPECT_EQ(report["singularities"][0]["index"].get<double>(), -0.5);
  EXPECT_EQ(report["inner_valences"]["6"].get<int>(), 1);
  EXPECT_EQ(report["inner_valences"].size(), 2u) << report["inner_valences"].dump();
  EXPECT_EQ(report["final"]["odd_inner_vertices"].get<double>(), 0.0);
  EXPECT_GT(report["final"]["area_covered"].get<double>(), 0.75);
  EXPECT_LT(report["final"]["mean_alignment_deg"].get<double>(), 3.0);
  const PolyMesh quads = ReadMesh(Path("quads.obj"));
  EXPECT_EQ(static_cast<double>(quads.n_faces()), report["final"]["quads"].get<double>());
  for (auto f : quads.faces()) EXPECT_EQ(quads.valence(f), 4u);
  EXPECT_NE(Slurp(dir_ / "quads.svg").find("<circle"), std::string::npos);
  EXPECT_NE(Slurp(dir_ / "field.obj").find("\nl "), std::string::npos);
  EXPECT_NE(r.out.find("inner valences: 4:"), std::string::npos) << r.out;
}

// The two-command pipeline of 004 Fig. 4 (remesh, then hnet with the triangles as reference), on
// the shipped mesh and on the same quads with two holes cut out (no exact extension: the
// vertices and weights are optimised together).
TEST_F(RemeshCommandTest, TrianglesToHNetWithAndWithoutHoles) {
  const CommandRun remesh = Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " +
                                  Path("quads.obj") + " --edge-length 0.12");
  ASSERT_EQ(remesh.exit_code, 0) << remesh.err;
  const CommandRun hnet =
      Gproj("hnet " + Path("quads.obj") + " --reference " + Data("monkey_saddle_tri.obj") + " -o " +
            Path("h.json") + " --report " + Path("h_report.json"));
  ASSERT_EQ(hnet.exit_code, 0) << hnet.err << hnet.out;
  const nlohmann::json report = Json("h_report.json");
  EXPECT_LT(report["final"]["max_tangent_angle_deg"].get<double>(), 0.01);
  EXPECT_GT(report["final"]["w_min"].get<double>(), 0.0);
  EXPECT_LT(report["final"]["max_reference_distance"].get<double>(), 0.005);
  EXPECT_LT(report["final"]["max_displacement"].get<double>(), 0.02);
  // Two holes.
  WriteMeshAtomically(WithTwoHoles(ReadMesh(Path("quads.obj"))), Path("holed.obj"));
  const std::string holed_hnet = "hnet " + Path("holed.obj") + " --reference " +
                                 Data("monkey_saddle_tri.obj") + " -o " + Path("hh.json") +
                                 " --report " + Path("hh_report.json");
  ExpectOneLineError(Gproj(holed_hnet), "not simply connected");
  const CommandRun joint = Gproj(holed_hnet + " --allow-not-simply-connected");
  ASSERT_EQ(joint.exit_code, 0) << joint.err << joint.out;
  const nlohmann::json r = Json("hh_report.json");
  ASSERT_EQ(r["rounds"].size(), 2u);
  EXPECT_GT(r["rounds"][0]["max_tangent_angle_deg"].get<double>(), 0.05);  // propagated
  EXPECT_LT(r["final"]["max_tangent_angle_deg"].get<double>(), 1e-4);
  EXPECT_GT(r["final"]["w_min"].get<double>(), 0.0);
  EXPECT_EQ(r["simply_connected"], false);
  EXPECT_TRUE(r["worst_edges"].is_array());
  EXPECT_NE(joint.out.find("optimised the vertices and weights together"), std::string::npos);
}

// The triangles themselves with two holes: `remesh` cuts through the holes and the quads close
// up around them (3 boundary loops, Euler characteristic −1), then `hnet
// --allow-not-simply-connected` makes them an H-net with the same holes.
TEST_F(RemeshCommandTest, TrianglesWithHolesToHNet) {
  WriteMeshAtomically(WithTwoHoles(ReadMesh(Data("monkey_saddle_tri.obj"))), Path("holed_tri.obj"));
  const CommandRun remesh = Gproj("remesh " + Path("holed_tri.obj") + " -o " + Path("quads.obj") +
                                  " --edge-length 0.12 --report " + Path("r.json"));
  ASSERT_EQ(remesh.exit_code, 0) << remesh.err << remesh.out;
  EXPECT_NE(remesh.out.find("3 boundary loops, cut through the holes"), std::string::npos)
      << remesh.out;
  EXPECT_EQ(Json("r.json")["boundary_loops"], 3);
  const PolyMesh quads = ReadMesh(Path("quads.obj"));
  int used = 0;
  for (auto v : quads.vertices()) used += !quads.is_isolated(v);
  EXPECT_EQ(used - static_cast<long>(quads.n_edges()) + static_cast<long>(quads.n_faces()), -1);
  const CommandRun hnet = Gproj("hnet " + Path("quads.obj") + " --reference " +
                                Path("holed_tri.obj") + " -o " + Path("h.json") + " --report " +
                                Path("h_report.json") + " --allow-not-simply-connected");
  ASSERT_EQ(hnet.exit_code, 0) << hnet.err << hnet.out;
  const nlohmann::json report = Json("h_report.json");
  EXPECT_EQ(report["simply_connected"], false);
  EXPECT_LT(report["final"]["max_tangent_angle_deg"].get<double>(), 0.01);
  EXPECT_GT(report["final"]["w_min"].get<double>(), 0.0);
  EXPECT_LT(report["final"]["max_reference_distance"].get<double>(), 0.005);
}

// The shipped two-hole saddle: at its default edge length (3 mean triangle edges) the quads
// around one hole meet the outer ones at a single corner, which is no valid net (exit 3, named);
// at 0.1 they close up around both holes.
TEST_F(RemeshCommandTest, QuadsOfAnotherTopologyAreNamed) {
  const std::string base = "remesh " + Data("saddle_two_holes_tri.obj") + " -o " + Path("q.obj") +
                           " --report " + Path("r.json");
  const CommandRun coarse = Gproj(base);
  EXPECT_EQ(coarse.exit_code, 3) << coarse.err << coarse.out;
  EXPECT_NE((coarse.out + coarse.err).find("meet at a corner only (pinched)"), std::string::npos)
      << coarse.out << coarse.err;
  EXPECT_GT(Json("r.json")["final"]["pinched_vertices"].get<double>(), 0.0);
  const CommandRun fine = Gproj(base + " --edge-length 0.1");
  ASSERT_EQ(fine.exit_code, 0) << fine.err << fine.out;
  const nlohmann::json r = Json("r.json");
  EXPECT_EQ(r["final"]["pieces"].get<double>(), 1.0);
  EXPECT_EQ(r["final"]["pinched_vertices"].get<double>(), 0.0);
  EXPECT_EQ(r["final"]["euler_characteristic"].get<double>(), -1.0);
}

// Quads that are not a valid net are written with exit 3 and the reasons: here asymptotic
// directions on a surface with K > 0 on half of it.
TEST_F(RemeshCommandTest, InvalidNetExitsThreeWithTheReasons) {
  std::vector<Eigen::Vector2d> uv;
  WriteMeshAtomically(Triangulate(
                          [](double x, double y) {
                            return Eigen::Vector3d(x, y, std::sin(3 * x) * std::sin(3 * y) / 3);
                          },
                          -1, 1, -1, 1, 30, &uv, 4),
                      Path("egg_crate.obj"));
  const CommandRun r = Gproj("remesh " + Path("egg_crate.obj") + " -o " + Path("q.obj") +
                             " --report " + Path("r.json"));
  EXPECT_EQ(r.exit_code, 3) << r.err << r.out;
  EXPECT_NE((r.out + r.err).find("not a valid net"), std::string::npos) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("K >= 0 on"), std::string::npos) << r.out << r.err;
  EXPECT_TRUE(Exists("q.obj"));
  EXPECT_EQ(Json("r.json")["converged"], false);
}

// A torus with a hole (one handle): `remesh --directions principal` cuts it open around both of
// its cycles and the quads close up (Euler characteristic −1, one boundary loop); its principal
// net is conjugate, so `planarize` makes it a PQ mesh at once, every quad convex.
TEST_F(RemeshCommandTest, TorusWithAHoleToAPQMesh) {
  const PolyMesh torus = TriangulatePeriodic(
      [](double a, double b) {
        return Eigen::Vector3d((2 + std::cos(b)) * std::cos(a), (2 + std::cos(b)) * std::sin(a),
                               std::sin(b));
      },
      90, 36, 0, 2 * M_PI, 4, /*periodic_v=*/true);
  PolyMesh holed;
  std::vector<int> index(torus.n_vertices(), -1);
  for (auto f : torus.faces()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (auto v : torus.fv_range(f)) c += Eigen::Vector3d(torus.point(v).data()) / 3.0;
    if ((c - Eigen::Vector3d(3 * std::cos(2.0), 3 * std::sin(2.0), 0)).norm() < 0.45) continue;
    std::vector<PolyMesh::VertexHandle> corners;
    for (auto v : torus.fv_range(f)) {
      if (index[v.idx()] < 0) index[v.idx()] = holed.add_vertex(torus.point(v)).idx();
      corners.push_back(holed.vertex_handle(index[v.idx()]));
    }
    holed.add_face(corners);
  }
  WriteMeshAtomically(holed, Path("torus.obj"));
  const CommandRun remesh =
      Gproj("remesh " + Path("torus.obj") + " --directions principal --edge-length 0.2 -o " +
            Path("quads.obj") + " --report " + Path("r.json"));
  ASSERT_EQ(remesh.exit_code, 0) << remesh.err << remesh.out;
  EXPECT_NE(remesh.out.find("1 boundary loop, 1 handle cut open"), std::string::npos) << remesh.out;
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["handles"], 1);
  EXPECT_EQ(report["boundary_loops"], 1);
  EXPECT_EQ(report["inner_valences"].size(), 1u) << report["inner_valences"].dump();
  const PolyMesh quads = ReadMesh(Path("quads.obj"));
  int used = 0;
  for (auto v : quads.vertices()) used += !quads.is_isolated(v);
  EXPECT_EQ(used - static_cast<long>(quads.n_edges()) + static_cast<long>(quads.n_faces()), -1);
  EXPECT_GT(quads.n_faces(), 1500u);
  const CommandRun planarize = Gproj("planarize " + Path("quads.obj") + " -o " + Path("pq.obj") +
                                     " --report " + Path("p.json"));
  ASSERT_EQ(planarize.exit_code, 0) << planarize.err << planarize.out;
  const nlohmann::json p = Json("p.json");
  EXPECT_LT(p["final"]["max_planarity"].get<double>(), 1e-6);
  EXPECT_EQ(p["final"]["non_convex_quads"].get<double>(), 0.0);
  EXPECT_LT(p["final"]["max_displacement"].get<double>(), 0.01);
}

// Quads, a missing file and a bad option value are refused in one line, nothing written.
TEST_F(RemeshCommandTest, RefusesWhatItCannotRemesh) {
  ExpectOneLineError(Gproj("remesh " + Data("enneper_41x41.obj") + " -o " + Path("q.obj")),
                     "triangle mesh");
  EXPECT_FALSE(Exists("q.obj"));
  ExpectOneLineError(Gproj("remesh " + Path("missing.obj") + " -o " + Path("q.obj")),
                     "missing.obj");
  ExpectOneLineError(Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("q.obj") +
                           " --edge-length -1"),
                     "--edge-length");
  ExpectOneLineError(Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("q.obj") +
                           " --edge-length 100"),
                     "no quad");
  ExpectOneLineError(Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("q.obj") +
                           " --edge-length 0.0002"),
                     "--edge-length");
  ExpectOneLineError(Gproj("remesh " + Data("monkey_saddle_tri.obj") + " -o " + Path("q.obj") +
                           " --picture " + Path("p.png")),
                     "--picture");
  EXPECT_FALSE(Exists("q.obj"));
}

}  // namespace
}  // namespace gproj
