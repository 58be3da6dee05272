// `gproj planarize` on polygon meshes as a user runs it: the duals of generated triangle meshes
// (hexagons, with pentagons and quads along the border), checked with an independent planarity
// measure, for convexity, and for how far the vertices moved; and what it refuses.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/polygon_shape.h"

namespace gproj {
namespace {

class PolygonPlanarizeTest : public CommandTest {
 protected:
  // A triangular lattice of n × n vertices (valence 6 inside) of spacing 1 / n over
  // z = height(x, y), written as OBJ.
  std::string Lattice(const std::string& name, int n,
                      const std::function<double(double, double)>& height) {
    std::ofstream obj(Path(name));
    obj.precision(17);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5 * j - 0.75 * n) / n, y = (j * std::sqrt(3.0) / 2 - 0.4 * n) / n;
        obj << "v " << x << ' ' << y << ' ' << height(x, y) << '\n';
      }
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const int a = j * n + i + 1, b = a + 1, c = a + n, d = c + 1;
        obj << "f " << a << ' ' << b << ' ' << c << "\nf " << b << ' ' << d << ' ' << c << '\n';
      }
    return Path(name);
  }

  // The largest distance of a face's corners from their least-squares plane (by an SVD of the
  // centred corners), over the faces of ≥ 4 corners, divided by the mean edge length.
  static double IndependentPlanarity(const PolyMesh& mesh) {
    double edges = 0.0;
    for (auto e : mesh.edges()) edges += mesh.calc_edge_length(e);
    const double mean_edge = edges / mesh.n_edges();
    double worst = 0.0;
    for (auto f : mesh.faces()) {
      if (mesh.valence(f) < 4) continue;
      Eigen::MatrixXd p(mesh.valence(f), 3);
      int k = 0;
      for (auto v : mesh.fv_range(f)) {
        const auto& q = mesh.point(v);
        p.row(k++) << q[0], q[1], q[2];
      }
      const Eigen::MatrixXd centred = p.rowwise() - p.colwise().mean();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centred.transpose() * centred);
      const Eigen::Vector3d normal = eigen.eigenvectors().col(0);
      worst = std::max(worst, (centred * normal).cwiseAbs().maxCoeff());
    }
    return worst / mean_edge;
  }

  static double MaxMove(const PolyMesh& a, const PolyMesh& b) {
    double worst = 0.0;
    for (auto v : a.vertices()) worst = std::max(worst, (a.point(v) - b.point(v)).norm());
    return worst;
  }
};

// The centroid dual of a sphere cap (hexagons inside, pentagons and quads at the border, kept
// boundary): planar to the tolerance by an independent measure, every face convex, the
// vertices moved by a small fraction of an edge.
TEST_F(PolygonPlanarizeTest, SphereCapDualBecomesPlanarAndStaysConvex) {
  const std::string tri =
      Lattice("cap.obj", 16, [](double x, double y) { return std::sqrt(4.0 - x * x - y * y); });
  ASSERT_EQ(Gproj("dual " + tri + " -o " + Path("hex.obj") + " --boundary keep").exit_code, 0);
  const CommandRun r =
      Gproj("planarize " + Path("hex.obj") + " -o " + Path("flat.obj") +
            " --tolerance 1e-6 --face-values " + Path("f.csv") + " --report " + Path("r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const PolyMesh before = ReadMesh(Path("hex.obj")), after = ReadMesh(Path("flat.obj"));
  EXPECT_GT(IndependentPlanarity(before), 1e-4);
  EXPECT_LT(IndependentPlanarity(after), 1e-6);
  EXPECT_EQ(SummarizePolygons(after).non_convex, 0);
  EXPECT_LT(MaxMove(before, after), 0.05 * (1.0 / 16));
  const nlohmann::json report = Json("r.json");
  EXPECT_EQ(report["faces_by_corners"][6], 14 * 14);
  EXPECT_LE(report["final"]["max_planarity"].get<double>(), 1e-6);
  EXPECT_NE(r.out.find("196 hexagons"), std::string::npos) << r.out;
  // One line of face values per face of 4 or more corners.
  const std::string csv = Slurp(dir_ / "f.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + static_cast<long>(after.n_faces()));
}

// On a saddle the centroid dual's hexagons are convex, but planar hexagons there cannot all be:
// the run keeps every corner above its bound instead of folding, and says which faces hold it
// back when it stops short.
TEST_F(PolygonPlanarizeTest, SaddleDualKeepsItsCornersAndSaysWhereItStops) {
  const std::string tri =
      Lattice("saddle.obj", 14, [](double x, double y) { return 0.6 * (x * x - y * y); });
  ASSERT_EQ(Gproj("dual " + tri + " -o " + Path("hex.obj")).exit_code, 0);
  const CommandRun r = Gproj("planarize " + Path("hex.obj") + " -o " + Path("flat.obj") +
                             " --tolerance 1e-6 --report " + Path("r.json"));
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << r.err << r.out;
  const PolyMesh before = ReadMesh(Path("hex.obj")), after = ReadMesh(Path("flat.obj"));
  EXPECT_EQ(SummarizePolygons(before).non_convex, 0);
  EXPECT_EQ(SummarizePolygons(after).non_convex, 0);
  EXPECT_GE(SummarizePolygons(after).min_angle_deg, 5.0 - 1e-6);
  EXPECT_LT(IndependentPlanarity(after), 0.5 * IndependentPlanarity(before));
  if (r.exit_code == 3)  // it says how many faces are still above the tolerance
    EXPECT_NE(r.err.find("faces above the tolerance"), std::string::npos) << r.err;
}

// A real hexagonal mesh from another project (tests/data/README.md), far from planar (corners
// up to 0.1 of an edge off their plane): with the default bounds every face stays convex, and
// where planar hexagons would have to turn reflex the run stops short and names the faces held
// at their corner bound; allowed to fold, it reaches the tolerance with non-convex faces.
TEST_F(PolygonPlanarizeTest, RealHexMeshStaysConvexOrFoldsOnlyWhenAllowed) {
  const std::string in = std::string(GPROJ_SOURCE_DIR) + "/tests/data/compas_shapeop_hex_mesh.obj";
  const CommandRun r = Gproj("planarize " + in + " -o " + Path("flat.obj") +
                             " --tolerance 1e-6 --report " + Path("r.json"));
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << r.err << r.out;
  const PolyMesh before = ReadMesh(in), after = ReadMesh(Path("flat.obj"));
  EXPECT_GT(IndependentPlanarity(before), 0.05);
  EXPECT_LT(IndependentPlanarity(after), 0.1 * IndependentPlanarity(before));
  EXPECT_EQ(SummarizePolygons(after).non_convex, 0);
  EXPECT_GE(SummarizePolygons(after).min_angle_deg, 5.0 - 1e-6);
  if (r.exit_code == 3)
    EXPECT_NE(r.err.find("faces sit on their corner-angle bound"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("PQ (conjugate)"), std::string::npos) << r.err;  // not a quad mesh
  const CommandRun folds =
      Gproj("planarize " + in + " -o " + Path("folded.obj") + " --tolerance 1e-6 --allow-folds");
  ASSERT_EQ(folds.exit_code, 0) << folds.err << folds.out;
  const PolyMesh folded = ReadMesh(Path("folded.obj"));
  EXPECT_LT(IndependentPlanarity(folded), 1e-6);
  EXPECT_GT(SummarizePolygons(folded).non_convex, 0);
}

TEST_F(PolygonPlanarizeTest, RefusesCircularPolygonsAndTriangleMeshes) {
  const std::string tri = Lattice("cap.obj", 6, [](double, double) { return 0.0; });
  ASSERT_EQ(Gproj("dual " + tri + " -o " + Path("hex.obj")).exit_code, 0);
  ExpectOneLineError(Gproj("planarize " + Path("hex.obj") + " -o " + Path("c.obj") + " --circular"),
                     "hex.obj: face 0 has 6 vertices; a circular mesh is made of quads");
  ExpectOneLineError(Gproj("planarize " + tri + " -o " + Path("c.obj")),
                     "cap.obj: every face is a triangle");
  EXPECT_FALSE(Exists("c.obj"));
}

}  // namespace
}  // namespace gproj
