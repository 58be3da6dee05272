#pragma once
// The shape of quad panels as a builder judges it: convex or not, the smallest corner angle,
// the kink between the quad's two triangles and the planarity in the mesh's own units.
// Corner i of quad (v0, v1, v2, v3) is measured in the plane of the diagonals' normal
// N = (v2 − v0) × (v3 − v1): its signed sine
//   sin∠_i = ((v_{i+1} − v_i) × (v_{i−1} − v_i)) · N / (|v_{i+1} − v_i| |v_{i−1} − v_i| |N|)
// is negative at a reflex or folded corner, so a quad is convex when all four are positive.
// For a skew quad this says exactly that its bilinear patch has no fold: the patch's normal
// x_u × x_v is the bilinear blend of the four corner normals (the corners' cross products), so
// it is ¼ Σ of them = N/2 at the centre, and it stays within 90° of N over the whole patch if
// and only if it does at the four corners. (Judging a skew quad by its projection onto its
// least-squares plane is no such measure: for a thin twisted strip that plane's normal swaps
// by 90° once the twist exceeds about half the width, and the projection then crosses itself
// although the patch is smooth and unfolded.)

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

// The signed sines of a quad's four corners (see above), for any scalar type (double, Jet).
template <typename T>
void QuadCornerSines(const T* v0, const T* v1, const T* v2, const T* v3, T* sines) {
  const T* v[4] = {v0, v1, v2, v3};
  T n[3], d0[3], d1[3];
  for (int c = 0; c < 3; ++c) d0[c] = v2[c] - v0[c], d1[c] = v3[c] - v1[c];
  n[0] = d0[1] * d1[2] - d0[2] * d1[1];
  n[1] = d0[2] * d1[0] - d0[0] * d1[2];
  n[2] = d0[0] * d1[1] - d0[1] * d1[0];
  using std::sqrt;
  const T tiny(1e-300);
  const T n_norm = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] + tiny);
  for (int i = 0; i < 4; ++i) {
    const T* p = v[i];
    const T* next = v[(i + 1) % 4];
    const T* prev = v[(i + 3) % 4];
    T a[3], b[3];
    for (int c = 0; c < 3; ++c) a[c] = next[c] - p[c], b[c] = prev[c] - p[c];
    const T cross_n = (a[1] * b[2] - a[2] * b[1]) * n[0] + (a[2] * b[0] - a[0] * b[2]) * n[1] +
                      (a[0] * b[1] - a[1] * b[0]) * n[2];
    const T a_norm = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + tiny);
    const T b_norm = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2] + tiny);
    sines[i] = cross_n / (a_norm * b_norm * n_norm);
  }
}

struct QuadShape {
  bool convex = true;              // all four corner sines > 0
  double min_angle_deg = 0.0;      // smallest corner angle in the diagonals' plane (a reflex
                                   // corner counts as 360° minus its turn, so > 180°)
  double kink_deg = 0.0;           // angle between the normals of the two triangles (larger of
                                   // the two splits)
  double diagonal_distance = 0.0;  // distance between the diagonal lines, mesh units
};

// The four corner angles in degrees, measured in the diagonals' plane (a reflex or folded corner
// as 360° minus its unsigned angle).
std::array<double, 4> QuadCornerAngles(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                       const Eigen::Vector3d& v2, const Eigen::Vector3d& v3);

// Distance between the two diagonal lines of a quad (the planarity measure), in its units.
double DiagonalDistance(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                        const Eigen::Vector3d& v2, const Eigen::Vector3d& v3);

QuadShape MeasureQuadShape(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                           const Eigen::Vector3d& v2, const Eigen::Vector3d& v3);

// Per face of a quad mesh (non-quads get a default QuadShape).
std::vector<QuadShape> MeasureQuadShapes(const PolyMesh& mesh);

// Per quad of `mesh`: its diagonal distance / the mesh's mean edge length (the planarity
// measure), and with `circular` the larger of that and the concyclicity (distance of the
// vertices to their fitted circle / mean edge). Polygons of 5 or more corners get their
// planarity (polygon_shape.h) / mean edge; triangles 0.
std::vector<double> RelativeFacePlanarity(const PolyMesh& mesh, bool circular);

// The columns of `--face-values`, one entry per quad and per polygon of 5 or more corners (its
// planarity as polygon_shape.h measures it, kink_deg the largest angle between the planes of
// two consecutive corners; triangles are skipped):
// face index, planarity (diagonal distance / mean edge), planarity_abs (in the mesh's units),
// kink_deg, min_angle_deg, convex, and with `circular` concyclicity (distance of the corners to
// their fitted circle / mean edge; empty otherwise).
struct FaceValues {
  std::vector<int> face;
  std::vector<double> planarity, planarity_abs, kink_deg, min_angle_deg, concyclicity;
  std::vector<bool> convex;
};
FaceValues MeasureFaceValues(const PolyMesh& mesh, bool circular);

// The table of `--face-values`: one line per quad, "face,planarity,planarity_abs,kink_deg,
// min_angle_deg" (+ ",concyclicity" when `circular`), with a header line.
std::string QuadShapesCsv(const PolyMesh& mesh, bool circular);

struct QuadShapeSummary {
  int non_convex = 0;            // quads with a corner sine ≤ 0
  double min_angle_deg = 180.0;  // over all corners
  double max_kink_deg = 0.0;
  double max_diagonal_distance = 0.0;  // mesh units
};
QuadShapeSummary Summarize(const std::vector<QuadShape>& shapes);

// How much the quads' corner angles changed between two meshes of one connectivity: a large
// change means the input was far from the asked net type.
// Polygons of 5 or more corners count as quads do (their corner angles as polygon_shape.h
// measures them).
struct ShapeChange {
  double threshold_deg = 0.0;
  int quads_changed = 0;       // quads (and polygons) with a corner angle changed by > threshold
  double share_changed = 0.0;  // quads_changed / #quads (and polygons)
  int polygons = 0;            // faces of 5 or more corners compared
  double max_corner_change_deg = 0.0;
};
ShapeChange CompareCornerAngles(const PolyMesh& before, const PolyMesh& after,
                                double threshold_deg = 10.0);

}  // namespace gproj
