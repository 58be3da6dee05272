#include "gproj/problems/mesh/mesh_problem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/solver/term.h"

namespace gproj {
namespace {

// A vertex on the plane z = 0 of the problem's coordinates (the input's mean height).
struct OnMeanPlane {
  template <typename T>
  void operator()(const T* p, T* r) const {
    r[0] = p[2];
  }
};

// The smallest mesh problem: every vertex onto the plane through the input's centre, with the
// base's bounds, vertex control and result.
class Flatten : public MeshProblem {
 public:
  Flatten(const PolyMesh& mesh, const VertexControlOptions& vertices) : MeshProblem(mesh) {
    LoadInputVertices();
    auto* plane = problem_.AddTerm<1, 3>("on_plane", OnMeanPlane{});
    for (auto v : mesh.vertices()) plane->Add({this->vertices()[v]});
    AddBoundsAndControl(PanelBoundsOptions{}, vertices);
  }
  SolverOptions solver_options() const override {
    SolverOptions s;
    s.fairness_weight = 0.0;
    return s;
  }
  CeresOptions ceres_options(int max_iterations) const override {
    return CeresOptionsFor(solver_options(), max_iterations, 1.0);
  }
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override {
    const PolyMesh& mesh = MeshAt(x);
    double worst = 0.0;
    for (auto v : mesh.vertices())
      if (!std::binary_search(control_.held.begin(), control_.held.end(), v.idx()))
        worst = std::max(worst, std::abs(mesh.point(v)[2] - height_));
    return {{"max_height", worst}};
  }
  bool MeetsTolerance(const NamedValues& m) const override {
    return ValueOf(m, "max_height") <= 1e-9;
  }
  BlockItems items() const { return vertices(); }
  double height() const { return height_; }

 private:
  double height_ = norm_.center.z();
};

PolyMesh Paraboloid() {
  QuadGridOptions g;
  g.nu = g.nv = 9;
  g.noise = 0.02;
  return MakeQuadGrid(g);
}

TEST(MeshProblemTest, ItemsByIndexAndHandleAreTheVertexBlocksFirstItems) {
  const PolyMesh mesh = Paraboloid();
  Flatten flatten(mesh, {});
  const BlockItems items = flatten.items();
  EXPECT_EQ(items.size(), static_cast<int>(mesh.n_vertices()));
  EXPECT_EQ(flatten.problem().layout().block(0).name, "vertices");
  for (int v : {0, 7, 80}) {
    EXPECT_EQ(items[v], flatten.problem().layout().Item(0, v));
    EXPECT_EQ(items[mesh.vertex_handle(v)], items[v]);
  }
  EXPECT_EQ(items(3, 5), (std::array<int, 2>{items[3], items[5]}));
}

TEST(MeshProblemTest, ResultIsInInputUnitsWithHeldVerticesExact) {
  const PolyMesh mesh = Paraboloid();
  VertexControlOptions vertices;
  vertices.fixed = {0, 40};
  Flatten flatten(mesh, vertices);
  const RunReport report = flatten.Run();
  ASSERT_TRUE(report.converged) << report.termination;
  const PolyMesh out = flatten.Result();
  ASSERT_EQ(out.n_vertices(), mesh.n_vertices());
  for (auto v : out.vertices()) {
    if (v.idx() == 0 || v.idx() == 40) {
      EXPECT_EQ(out.point(v), mesh.point(v)) << v.idx();  // bit for bit
    } else {
      EXPECT_NEAR(out.point(v)[2], flatten.height(), 1e-9) << v.idx();
    }
  }
  EXPECT_TRUE(flatten.FacesAtAngleBound().empty());
  EXPECT_EQ(flatten.input().point(mesh.vertex_handle(3)), mesh.point(mesh.vertex_handle(3)));
}

}  // namespace
}  // namespace gproj
