#pragma once
// The shape of polygon panels with any number of corners (quad_shape.h measures quads; the two
// agree on quads). A polygon's plane is its least-squares plane: through the corners' centroid,
// normal to the direction in which they spread least, oriented by the polygon's vector area
// (½ Σ p_i × p_{i+1}), so that a counter-clockwise polygon seen from that side has normal towards
// the viewer. Its planarity:
//   3 corners: 0 (a triangle is planar);
//   4 corners: the distance between the diagonal lines (DiagonalDistance, quad_shape.h);
//   5 or more: twice the largest distance of a corner from the least-squares plane (the same as
//              the diagonal distance for a skew quad whose diagonals bisect each other).
// Corner i's signed sine
//   ((p_{i+1} − p_i) × (p_{i−1} − p_i)) · A / (|p_{i+1} − p_i| |p_{i−1} − p_i| |A|),
// A = Σ p_k × p_{k+1} the vector area (the least-squares normal's direction once the polygon is
// planar; the corner bounds of panel_validity.h read the same sines), is negative at a reflex
// corner, so a polygon is convex when every corner's is positive.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

struct PolygonShape {
  int corners = 0;
  bool convex = true;          // every corner sine > 0
  double min_angle_deg = 0.0;  // smallest corner angle (a reflex corner > 180°)
  double planarity = 0.0;      // see above, in the mesh's units
};

// The least-squares plane's unit normal of `p` (see above); (0, 0, 1) for fewer than 3 points or
// points on one line.
Eigen::Vector3d PolygonNormal(const std::vector<Eigen::Vector3d>& p);

// The planarity of a polygon (see above), in its units.
double PolygonPlanarity(const std::vector<Eigen::Vector3d>& p);

PolygonShape MeasurePolygonShape(const std::vector<Eigen::Vector3d>& p);

// The corner angles in degrees, measured in the polygon's plane (a reflex corner as 360° minus
// its unsigned angle).
std::vector<double> PolygonCornerAngles(const std::vector<Eigen::Vector3d>& p);

// The largest angle between the planes of two consecutive corners (v_{i−1}, v_i, v_{i+1}) and
// (v_i, v_{i+1}, v_{i+2}), in degrees: 0 for a planar polygon (the kink of a quad's split).
double PolygonKinkDeg(const std::vector<Eigen::Vector3d>& p);

// The corners of face f in order.
std::vector<Eigen::Vector3d> FacePoints(const PolyMesh& mesh, PolyMesh::FaceHandle f);

// Per face of a mesh of any polygons.
std::vector<PolygonShape> MeasurePolygonShapes(const PolyMesh& mesh);

// What a polygon mesh is made of and how planar and convex its panels are; planarity relative to
// the mean edge length.
struct PolygonMeshSummary {
  std::vector<int> faces_by_corners;  // [n] = faces with n corners (index 0..max)
  int non_convex = 0;                 // faces of ≥ 4 corners with a reflex corner
  double max_planarity = 0.0;         // over the faces, / mean edge
  double mean_planarity = 0.0;        // over the faces of ≥ 4 corners, / mean edge
  double min_angle_deg = 180.0;       // over all corners of faces of ≥ 4 corners
};
PolygonMeshSummary SummarizePolygons(const PolyMesh& mesh);

// "12 hexagons, 4 pentagons, 2 quads" (largest faces first).
std::string FaceCountsText(const std::vector<int>& faces_by_corners);

}  // namespace gproj
