#include "gproj/problems/circular/torsion_free_beams.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>

#include "gproj/geometry/mesh/mobius.h"

namespace gproj::circular {
namespace {

// A surface of revolution meshed by meridians and parallels (every quad an isosceles
// trapezoid, so circular): profile r(t) = 1.5 + 0.4 sin 2t, z(t) = 1.2 t, t ∈ [0, 1.4],
// a quarter turn.
PolyMesh Revolution(int rows, int cols) {
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j <= cols; ++j) {
      const double t = 1.4 * i / rows, phi = 0.5 * M_PI * j / cols;
      const double r = 1.5 + 0.4 * std::sin(2.0 * t);
      v.push_back(mesh.add_vertex(PolyMesh::Point(r * std::cos(phi), r * std::sin(phi), 1.2 * t)));
    }
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const int a = i * (cols + 1) + j;
      mesh.add_face({v[a], v[a + 1], v[a + cols + 2], v[a + cols + 1]});
    }
  return mesh;
}

double Measure(const BeamLayout& b, const char* name) { return ValueOf(b.measures, name); }

// The offset theory on circular meshes: on a surface of revolution and on its image under a
// sphere inversion (circular, no symmetry left), the beams are planar, the offset mesh is
// parallel at exactly the asked distance, and the axes close around every face.
TEST(TorsionFreeBeamsTest, BeamsArePlanarAndTheOffsetIsParallel) {
  const PolyMesh revolution = Revolution(8, 10);
  const PolyMesh inverted = InvertMesh(revolution, Eigen::Vector3d(3.0, -1.0, 2.5), 4.0);
  for (const PolyMesh* mesh : {&revolution, &inverted}) {
    BeamOptions o;
    o.height = 0.1;
    const BeamLayout b = TorsionFreeBeams(*mesh, o);
    EXPECT_LT(Measure(b, "max_beam_planarity"), 1e-10);
    EXPECT_LT(Measure(b, "max_offset_angle"), 1e-10);
    EXPECT_LT(Measure(b, "max_offset_distance_error"), 1e-12);
    EXPECT_LT(Measure(b, "max_closing_angle"), 1e-10);
    EXPECT_EQ(b.beams.n_faces(), 6 * mesh->n_edges());
    EXPECT_EQ(b.offset.n_vertices(), mesh->n_vertices());
    // The beam's top edge is at distance h from the mesh edge, in the beam's plane.
    for (auto e : mesh->edges()) {
      const auto h = mesh->halfedge_handle(e, 0);
      const auto a = mesh->from_vertex_handle(h), c = mesh->to_vertex_handle(h);
      const auto pa = mesh->point(a), pc = mesh->point(c);
      const Eigen::Vector3d dir = Eigen::Vector3d(pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]);
      const double lift = b.edge_lift[e.idx()];
      EXPECT_NEAR((lift * b.axis[a.idx()]).cross(dir.normalized()).norm(), 0.1, 1e-12);
    }
  }
}

// The optimisation of 000 §4.3 lowers the height gaps at the nodes against the axes started
// from the central node's mean face normal (on an inverted surface of revolution).
TEST(TorsionFreeBeamsTest, OptimisedFirstAxisLowersTheHeightGaps) {
  const PolyMesh inverted = InvertMesh(Revolution(8, 10), Eigen::Vector3d(3.0, -1.0, 2.5), 4.0);
  BeamOptions o;
  o.height = 0.1;
  const BeamLayout optimised = TorsionFreeBeams(inverted, o);
  o.optimise = false;
  const BeamLayout plain = TorsionFreeBeams(inverted, o);
  const double start = Measure(plain, "max_height_gap");
  std::printf("max height gap / h: %.4g from the face normal, %.4g optimised (mean %.4g -> %.4g)\n",
              start, Measure(optimised, "max_height_gap"), Measure(plain, "mean_height_gap"),
              Measure(optimised, "mean_height_gap"));
  EXPECT_DOUBLE_EQ(Measure(optimised, "initial_max_height_gap"), start);
  EXPECT_LT(Measure(optimised, "mean_height_gap"), Measure(plain, "mean_height_gap"));
  EXPECT_LE(Measure(optimised, "max_height_gap"), start * 1.0001);
}

// A mesh whose quads are not inscribed in circles is refused, naming the face.
TEST(TorsionFreeBeamsTest, NonCircularMeshIsRefused) {
  PolyMesh mesh = Revolution(4, 4);
  const auto v = mesh.vertex_handle(7);
  auto p = mesh.point(v);
  p[2] += 0.05;
  mesh.set_point(v, p);
  BeamOptions o;
  o.height = 0.1;
  try {
    TorsionFreeBeams(mesh, o);
    FAIL() << "accepted a non-circular mesh";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not inscribed in a circle"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("face "), std::string::npos) << e.what();
  }
  o.height = 0.0;
  EXPECT_THROW(TorsionFreeBeams(Revolution(2, 2), o), InputError);
}

TEST(TorsionFreeBeamsTest, AxesObjHasOneSegmentPerVertex) {
  const PolyMesh mesh = Revolution(2, 3);
  BeamOptions o;
  o.height = 0.2;
  const BeamLayout b = TorsionFreeBeams(mesh, o);
  const std::string obj = AxesObj(mesh, b.axis, 0.5);
  size_t lines = 0, vertices = 0;
  for (size_t at = obj.find('\n'); at != std::string::npos; at = obj.find('\n', at + 1)) {
    if (obj.compare(at + 1, 2, "l ") == 0) ++lines;
    if (obj.compare(at + 1, 2, "v ") == 0) ++vertices;
  }
  EXPECT_EQ(lines, mesh.n_vertices());
  EXPECT_EQ(vertices, 2 * mesh.n_vertices());
}

// The layout is computed at unit scale: the same mesh far from the origin or scaled by 1e±100
// (with the height scaled alike) gives the same beams; heights out of proportion, faces with an
// odd number of vertices and a loose circularity tolerance are refused with the reason.
TEST(TorsionFreeBeamsTest, ScaleAndPositionDoNotMatterAndBadInputsAreNamed) {
  const PolyMesh mesh = InvertMesh(Revolution(6, 6), Eigen::Vector3d(3.0, -1.0, 2.5), 4.0);
  BeamOptions o;
  o.height = 0.1;
  const BeamLayout reference = TorsionFreeBeams(mesh, o);
  for (const auto& [scale, shift] :
       {std::pair{1.0, 1e6}, std::pair{1e100, 0.0}, std::pair{1e-100, 0.0}}) {
    PolyMesh moved = mesh;
    for (auto v : moved.vertices())
      moved.set_point(v, moved.point(v) * scale + PolyMesh::Point(shift, shift, 0));
    BeamOptions scaled = o;
    scaled.height = o.height * scale;
    const BeamLayout b = TorsionFreeBeams(moved, scaled);
    // Up to the rounding of the moved input (1e-10 of 1e6 on edges of about 0.5).
    EXPECT_LT(Measure(b, "max_beam_planarity"), 1e-7) << scale << " " << shift;
    EXPECT_NEAR(Measure(b, "max_height_gap"), Measure(reference, "max_height_gap"), 1e-6)
        << scale << " " << shift;
  }
  auto refusal = [](const PolyMesh& m, const BeamOptions& options) {
    try {
      TorsionFreeBeams(m, options);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  BeamOptions huge = o;
  huge.height = 1e300;
  EXPECT_NE(refusal(mesh, huge).find("times the mean edge length"), std::string::npos);
  BeamOptions loose = o;
  loose.circularity_tolerance = 10.0;
  EXPECT_NE(refusal(mesh, loose).find("circularity tolerance"), std::string::npos);
  PolyMesh triangles;
  const auto a = triangles.add_vertex(PolyMesh::Point(0, 0, 0));
  const auto b = triangles.add_vertex(PolyMesh::Point(1, 0, 0));
  const auto c = triangles.add_vertex(PolyMesh::Point(0, 1, 0));
  triangles.add_face(a, b, c);
  EXPECT_NE(refusal(triangles, o).find("an even number of vertices"), std::string::npos);
}

}  // namespace
}  // namespace gproj::circular
