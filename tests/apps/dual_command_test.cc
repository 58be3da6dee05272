// `gproj dual` as a user runs it: the shipped monkey saddle (K < 0) and a generated sphere cap
// (K > 0), both starts, both boundary rules, the report, and what it refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "apps/command_test_util.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/polygon_shape.h"

namespace gproj {
namespace {

class DualCommandTest : public CommandTest {
 protected:
  // A sphere cap of radius 2: a triangular lattice of n × n vertices (every interior vertex of
  // valence 6) of spacing 1 / n around the pole.
  std::string SphereCap(int n) {
    std::ofstream cap(Path("cap.obj"));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5 * j - 0.75 * n) / n, y = (j * std::sqrt(3.0) / 2 - 0.4 * n) / n;
        cap << "v " << x << ' ' << y << ' ' << std::sqrt(4.0 - x * x - y * y) << '\n';
      }
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const int a = j * n + i + 1, b = a + 1, c = a + n, d = c + 1;
        cap << "f " << a << ' ' << b << ' ' << c << "\nf " << b << ' ' << d << ' ' << c << '\n';
      }
    return Path("cap.obj");
  }
};

TEST_F(DualCommandTest, SphereCapDualIsConvexAndFlatterFromTheTangentPlanes) {
  const std::string cap = SphereCap(14);
  const CommandRun centroids =
      Gproj("dual " + cap + " -o " + Path("c.obj") + " --report " + Path("c.json"));
  ASSERT_EQ(centroids.exit_code, 0) << centroids.err << centroids.out;
  const CommandRun planes =
      Gproj("dual " + cap + " -o " + Path("t.obj") + " --start tangent_planes --picture " +
            Path("t.svg") + " --report " + Path("t.json"));
  ASSERT_EQ(planes.exit_code, 0) << planes.err << planes.out;
  const nlohmann::json c = Json("c.json"), t = Json("t.json");
  EXPECT_EQ(t["command"], "dual");
  EXPECT_EQ(t["converged"], true);
  EXPECT_EQ(t["faces"], 12 * 12);  // the interior vertices
  EXPECT_EQ(t["faces_by_corners"][6], 12 * 12);
  EXPECT_EQ(t["tangent_planes"]["vertices"], 2 * 13 * 13);
  EXPECT_EQ(t["final"]["non_convex_faces"], 0);
  EXPECT_LT(t["final"]["max_planarity"].get<double>(), 1e-12);
  EXPECT_GT(c["final"]["max_planarity"].get<double>(), 1e-4);
  // The written mesh is what the report measured.
  const PolyMesh written = ReadMesh(Path("t.obj"));
  EXPECT_EQ(written.n_faces(), 144u);
  EXPECT_LT(SummarizePolygons(written).max_planarity, 1e-10);
  EXPECT_EQ(SummarizePolygons(written).non_convex, 0);
  EXPECT_NE(Slurp(dir_ / "t.svg").find("<svg"), std::string::npos);
  EXPECT_NE(planes.out.find("144 hexagons"), std::string::npos) << planes.out;
  // With the boundary kept, every vertex has a face.
  const CommandRun keep = Gproj("dual " + cap + " -o " + Path("k.obj") + " --boundary keep");
  ASSERT_EQ(keep.exit_code, 0) << keep.err;
  EXPECT_EQ(ReadMesh(Path("k.obj")).n_faces(), 14u * 14u);
}

// On the monkey saddle (K < 0) the tangent-plane dual is flat but has non-convex faces: the
// report says how many.
TEST_F(DualCommandTest, MonkeySaddleTangentPlaneDualHasNonConvexFaces) {
  const CommandRun r = Gproj("dual " + Data("monkey_saddle_tri.obj") + " -o " + Path("d.obj") +
                             " --start tangent_planes --report " + Path("d.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json report = Json("d.json");
  EXPECT_GT(report["final"]["non_convex_faces"].get<int>(), 0);
  EXPECT_NE(r.out.find("non-convex"), std::string::npos) << r.out;
}

TEST_F(DualCommandTest, RefusesQuadMeshesNamingTheFileAndFace) {
  ExpectOneLineError(Gproj("dual " + Data("noisy_grid_21x21.obj") + " -o " + Path("d.obj")),
                     "noisy_grid_21x21.obj: face 0 has 4 vertices; the dual is taken of a "
                     "triangle mesh");
  EXPECT_FALSE(Exists("d.obj"));
  ExpectOneLineError(
      Gproj("dual " + Data("monkey_saddle_tri.obj") + " -o " + Path("d.obj") + " --start middle"),
      "start");
  EXPECT_FALSE(Exists("d.obj"));
}

}  // namespace
}  // namespace gproj
