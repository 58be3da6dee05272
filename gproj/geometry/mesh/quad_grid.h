#pragma once
// Regular quad grids for examples, tests and benchmarks.

#include <cstdint>
#include <string>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

struct QuadGridOptions {
  int nu = 21;  // vertices along u (≥ 2)
  int nv = 21;  // vertices along v (≥ 2)
  // Height field over [−1, 1]²: z = a x² + b y² + c x y + wave sin(πx) sin(πy) (doubly curved
  // for a·b ≠ 0; the grid lines are conjugate only for c = wave = 0).
  double a = 0.3, b = 0.2, c = 0.0, wave = 0.0;
  // Each vertex is moved by a uniform random vector in [−noise·h, noise·h]³, h the grid spacing.
  double noise = 0.0;
  uint32_t seed = 1;
};

// Vertex (i, j) has index i * nv + j; faces (i, j), (i+1, j), (i+1, j+1), (i, j+1).
PolyMesh MakeQuadGrid(const QuadGridOptions& options);

}  // namespace gproj

namespace gproj {

// The shape of a mesh in the vertex and face order above: `rows` faces along i, `cols` along j;
// vertex (i, j) = i * (cols + 1) + j, face (i, j) = i * cols + j with vertices (i, j),
// (i+1, j), (i+1, j+1), (i, j+1) up to rotation and reversal.
struct GridShape {
  int rows = 0, cols = 0;
  int Vertex(int i, int j) const { return i * (cols + 1) + j; }
  int num_vertices() const { return (rows + 1) * (cols + 1); }
};

// Detects the grid shape of a quad mesh in that order. Throws InputError (prefixed with `path`)
// when the counts do not fit a grid or a face is out of order (naming the face).
GridShape DetectGridShape(const PolyMesh& mesh, const std::string& path = "");

}  // namespace gproj
