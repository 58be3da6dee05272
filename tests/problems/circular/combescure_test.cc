#include "gproj/problems/circular/combescure.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/mesh/mobius.h"
#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/problems/mesh/planarity_measures.h"

namespace gproj::circular {
namespace {

PolyMesh Revolution(int nu, int nv, double jitter = 0.0) {
  ParametricGridOptions o;
  o.nu = nu;
  o.nv = nv;
  o.jitter = jitter;
  return MakeParametricGrid(RevolutionSurface, o);
}

// Lengths that vary smoothly along both polylines (a genuine transformation, not a scaling).
CombescureLengths Varied(const PolyMesh& mesh, const GridShape& shape) {
  CombescureLengths l = ReferenceLengths(mesh, shape);
  for (size_t j = 0; j < l.row.size(); ++j) l.row[j] *= 1.0 + 0.4 * std::sin(0.5 * j);
  for (size_t i = 0; i < l.column.size(); ++i) l.column[i] *= 0.8 + 0.05 * i;
  l.origin = Eigen::Vector3d(1.0, -2.0, 0.5);
  return l;
}

double MaxVertexDistance(const PolyMesh& a, const PolyMesh& b) {
  double d = 0.0;
  for (auto v : a.vertices()) d = std::max(d, (a.point(v) - b.point(v)).norm());
  return d;
}

TEST(CombescureTest, ReferenceLengthsGiveTheReferenceBack) {
  const PolyMesh mesh = Revolution(7, 9);
  const GridShape shape = DetectGridShape(mesh);
  EXPECT_LT(
      MaxVertexDistance(CombescureByPropagation(mesh, shape, ReferenceLengths(mesh, shape)), mesh),
      1e-12);
}

TEST(CombescureTest, PropagationGivesParallelPlanarCircularMesh) {
  const PolyMesh mesh = Revolution(11, 13);
  const GridShape shape = DetectGridShape(mesh);
  const CombescureLengths lengths = Varied(mesh, shape);
  const PolyMesh out = CombescureByPropagation(mesh, shape, lengths);
  const ParallelismMeasures p = MeasureParallelism(mesh, out);
  EXPECT_LT(p.max_angle, 1e-10);
  EXPECT_GT(p.min_length_ratio, 0.0);
  EXPECT_LT(MeasurePlanarity(out, out).max_planarity, 1e-10);
  EXPECT_LT(MeasureCircularity(out).max_concyclicity, 1e-10);
  // The guide lengths are those asked for.
  for (int j = 0; j < shape.cols; ++j)
    EXPECT_NEAR((out.point(PolyMesh::VertexHandle(shape.Vertex(0, j + 1))) -
                 out.point(PolyMesh::VertexHandle(shape.Vertex(0, j))))
                    .norm(),
                lengths.row[j], 1e-12);
  // And it is not the reference up to a similarity: edge-length ratios vary.
  EXPECT_GT(MaxVertexDistance(out, mesh), 0.1);
}

// 000 §5.3: a super-canal surface is f(canal surface) with f a Combescure transformation followed
// by an inversion; f⁻¹ is the inversion again (an involution) and the Combescure transformation
// with the reference's own lengths. f⁻¹ ∘ f is the identity to 1e-12 (relative to the size), so
// meshes can be moved between the two freely (remeshing through f and f⁻¹).
TEST(CombescureTest, InverseOfACombescureAndMoebiusCompositionIsTheIdentity) {
  const PolyMesh canal = Revolution(11, 13);
  const GridShape shape = DetectGridShape(canal);
  const Eigen::Vector3d centre(3.5, 0.7, -0.4);
  const double ratio = 5.0;
  const PolyMesh super_canal =
      InvertMesh(CombescureByPropagation(canal, shape, Varied(canal, shape)), centre, ratio);
  EXPECT_LT(MeasureCircularity(super_canal).max_concyclicity, 1e-10);
  CombescureLengths back = ReferenceLengths(canal, shape);
  back.origin = Eigen::Vector3d(canal.point(PolyMesh::VertexHandle(0)).data());
  const PolyMesh again =
      CombescureByPropagation(InvertMesh(super_canal, centre, ratio), shape, back);
  double size = 0.0;
  for (auto v : canal.vertices())
    size = std::max(size, (canal.point(v) - canal.point(PolyMesh::VertexHandle(0))).norm());
  EXPECT_LT(MaxVertexDistance(again, canal) / size, 1e-12);
}

TEST(CombescureTest, GuidedProjectionAgreesWithPropagation) {
  const PolyMesh mesh = Revolution(9, 8);
  const GridShape shape = DetectGridShape(mesh);
  const CombescureLengths lengths = Varied(mesh, shape);
  const PolyMesh direct = CombescureByPropagation(mesh, shape, lengths);
  Combescure combescure(mesh, shape, lengths, CombescureOptions());
  const RunReport report = combescure.Run();
  ASSERT_TRUE(report.converged) << report.termination;
  EXPECT_FALSE(report.failed);
  const PolyMesh gp = combescure.Result();
  EXPECT_LT(MaxVertexDistance(gp, direct), 1e-9);
  EXPECT_LT(MeasureParallelism(mesh, gp).max_angle, 1e-10);
  EXPECT_LT(ValueOf(report.final, "max_guide_error"), 1e-11);
  // The start (the reference moved to the origin) is parallel but has the wrong lengths.
  EXPECT_GT(ValueOf(report.initial, "max_guide_error"), 1e-3);
  EXPECT_EQ(report.history.size(), static_cast<size_t>(report.iterations) + 1);
}

TEST(CombescureTest, PropagationReportsTheSameMeasuresWithoutIterations) {
  const PolyMesh mesh = Revolution(9, 8);
  const GridShape shape = DetectGridShape(mesh);
  const CombescureLengths lengths = Varied(mesh, shape);
  Combescure combescure(mesh, shape, lengths, CombescureOptions());
  const RunReport report = combescure.RunPropagation();
  EXPECT_EQ(report.solver, SolverKind::kDirect);
  EXPECT_EQ(report.method, "propagation");
  EXPECT_EQ(report.iterations, 0);
  EXPECT_TRUE(report.converged);
  EXPECT_LT(MaxVertexDistance(combescure.Result(), CombescureByPropagation(mesh, shape, lengths)),
            1e-15);
  EXPECT_LT(ValueOf(report.final, "max_edge_parallelism_angle"), 1e-10);
}

TEST(CombescureTest, RunStoppedShortIsNotConvergedAndNonFiniteStartFails) {
  const PolyMesh mesh = Revolution(7, 6);
  const GridShape shape = DetectGridShape(mesh);
  CombescureOptions options;
  options.solver.max_iterations = 1;  // one step leaves more than the tolerance
  options.solver.epsilon = 1e-3;
  Combescure short_run(mesh, shape, Varied(mesh, shape), options);
  const RunReport stopped = short_run.Run();
  EXPECT_FALSE(stopped.converged);
  EXPECT_FALSE(stopped.failed);
  EXPECT_GT(ValueOf(stopped.final, "max_guide_error"), options.tolerance);

  Combescure broken(mesh, shape, Varied(mesh, shape), CombescureOptions());
  broken.problem().x()[4] = NAN;
  const RunReport failed = broken.Run();
  EXPECT_TRUE(failed.failed);
  EXPECT_FALSE(failed.converged);
}

TEST(CombescureTest, CeresCrossCheckReachesTheGuidedProjectionResult) {
  const PolyMesh mesh = Revolution(6, 7);
  const GridShape shape = DetectGridShape(mesh);
  const CombescureLengths lengths = Varied(mesh, shape);
  Combescure gp(mesh, shape, lengths, CombescureOptions());
  ASSERT_TRUE(gp.Run().converged);
  Combescure ceres(mesh, shape, lengths, CombescureOptions());
  const RunReport report = ceres.RunCeres(50);
  EXPECT_EQ(report.solver, SolverKind::kCeres);
  EXPECT_TRUE(report.converged) << report.termination;
  EXPECT_LT(MaxVertexDistance(ceres.Result(), gp.Result()), 1e-9);
}

TEST(CombescureTest, NonPlanarReferenceIsRefusedNamingTheFace) {
  const PolyMesh mesh = Revolution(5, 5, 0.05);
  const GridShape shape = DetectGridShape(mesh);
  try {
    CombescureByPropagation(mesh, shape, ReferenceLengths(mesh, shape));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not planar"), std::string::npos) << e.what();
  }
}

TEST(CombescureTest, WrongLengthCountIsRefused) {
  const PolyMesh mesh = Revolution(5, 6);
  const GridShape shape = DetectGridShape(mesh);
  CombescureLengths l = ReferenceLengths(mesh, shape);
  l.row.pop_back();
  EXPECT_THROW(CombescureByPropagation(mesh, shape, l), InputError);
}

TEST(GridShapeTest, DetectsShapeAndRefusesOtherMeshes) {
  const PolyMesh mesh = Revolution(4, 7);
  const GridShape shape = DetectGridShape(mesh);
  EXPECT_EQ(shape.rows, 3);
  EXPECT_EQ(shape.cols, 6);
  // Same vertices, faces in reverse order: face 0 is not grid face (0, 0).
  PolyMesh reordered;
  for (auto v : mesh.vertices()) reordered.add_vertex(mesh.point(v));
  for (int f = static_cast<int>(mesh.n_faces()) - 1; f >= 0; --f) {
    std::vector<PolyMesh::VertexHandle> face;
    for (auto v : mesh.fv_range(PolyMesh::FaceHandle(f))) face.push_back(v);
    reordered.add_face(face);
  }
  try {
    DetectGridShape(reordered, "reordered.obj");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reordered.obj: face 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gproj::circular
