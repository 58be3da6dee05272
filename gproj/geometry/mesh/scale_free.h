#pragma once
// Measures that hold for any finite coordinates (tested from 1e-150 to 1e200): lengths by
// Eigen's stableNorm (no overflow of the squares), and polygons measured after moving them to
// their first vertex and dividing by their own extent.

#include <Eigen/Core>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

// The mean edge length of `mesh`, 0 without edges.
double MeanEdgeLength(const PolyMesh& mesh);

// `mesh` moved by −(its first vertex) and divided by its mean edge length, for measures that
// are scale-free (angles, ratios) on any finite input; unchanged when it has no edge length.
PolyMesh UnitScaleCopy(const PolyMesh& mesh);

// Where a computation runs at unit scale and its results go back: x_unit = (x − origin) / length.
struct UnitFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double length = 1.0;
};
// UnitScaleCopy and its frame; throws InputError when the mesh has no positive, finite mean edge
// length (or non-finite coordinates).
PolyMesh UnitScaleCopy(const PolyMesh& mesh, UnitFrame* frame);
// Every vertex p of `mesh` to p · length + origin: back to the input's units.
void FromUnitScale(const UnitFrame& frame, PolyMesh* mesh);

// Moves p[0..n) by −p[0] and divides by the largest coordinate difference; returns that factor
// (0 when the points coincide, which leaves them at 0). Lengths measured on the result are
// multiplied by it to come back to the input's units; angles need nothing.
double NormalizePolygon(Eigen::Vector3d* p, int n);

}  // namespace gproj
