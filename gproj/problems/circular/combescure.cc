#include "gproj/problems/circular/combescure.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "gproj/constraints/closeness.h"
#include "gproj/constraints/edge_parallelism.h"
#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/mesh/mesh_variables.h"
#include "gproj/problems/mesh/planarity_measures.h"
#include "gproj/problems/run/construction.h"

namespace gproj::circular {
namespace {

Eigen::Vector3d Point(const PolyMesh& mesh, int v) {
  const auto& p = mesh.point(PolyMesh::VertexHandle(v));
  return {p[0], p[1], p[2]};
}

std::string FaceName(const GridShape& shape, int i, int j) {
  return "face " + std::to_string(i * shape.cols + j) + " (grid " + std::to_string(i) + ", " +
         std::to_string(j) + ")";
}

}  // namespace

CombescureLengths ReferenceLengths(const PolyMesh& reference, const GridShape& shape,
                                   double scale) {
  CombescureLengths lengths;
  for (int j = 0; j < shape.cols; ++j)
    lengths.row.push_back(
        scale *
        (Point(reference, shape.Vertex(0, j + 1)) - Point(reference, shape.Vertex(0, j))).norm());
  for (int i = 0; i < shape.rows; ++i)
    lengths.column.push_back(
        scale *
        (Point(reference, shape.Vertex(i + 1, 0)) - Point(reference, shape.Vertex(i, 0))).norm());
  lengths.origin = Point(reference, 0);
  return lengths;
}

void CheckCombescureInput(const PolyMesh& reference, const GridShape& shape,
                          const CombescureLengths& lengths, double tolerance) {
  if (static_cast<int>(lengths.row.size()) != shape.cols)
    throw InputError("the row needs " + std::to_string(shape.cols) + " edge lengths (one per " +
                     "edge (0, j) → (0, j + 1)), got " + std::to_string(lengths.row.size()));
  if (static_cast<int>(lengths.column.size()) != shape.rows)
    throw InputError("the column needs " + std::to_string(shape.rows) + " edge lengths (one per " +
                     "edge (i, 0) → (i + 1, 0)), got " + std::to_string(lengths.column.size()));
  // A zero length collapses a row or column of edges: every quad along it would be degenerate.
  for (size_t k = 0; k < lengths.row.size(); ++k)
    if (!std::isfinite(lengths.row[k]) || lengths.row[k] == 0.0)
      throw InputError("row length " + std::to_string(k) + " is not finite and non-zero");
  for (size_t k = 0; k < lengths.column.size(); ++k)
    if (!std::isfinite(lengths.column[k]) || lengths.column[k] == 0.0)
      throw InputError("column length " + std::to_string(k) + " is not finite and non-zero");
  if (!lengths.origin.allFinite()) throw InputError("the origin is not finite");
  const double mean_edge = MeasurePlanarity(reference, reference).mean_edge_length;
  for (int i = 0; i < shape.rows; ++i)
    for (int j = 0; j < shape.cols; ++j) {
      const Eigen::Vector3d a = Point(reference, shape.Vertex(i, j)),
                            b = Point(reference, shape.Vertex(i + 1, j)),
                            c = Point(reference, shape.Vertex(i + 1, j + 1)),
                            d = Point(reference, shape.Vertex(i, j + 1));
      const double planarity = DiagonalDistance(a, b, c, d) / mean_edge;
      if (planarity > tolerance) {
        char text[160];
        std::snprintf(text, sizeof(text),
                      " of the reference is not planar (diagonal distance %.3g mean edges > "
                      "tolerance %.3g); planarise it first",
                      planarity, tolerance);
        throw InputError(FaceName(shape, i, j) + text);
      }
      const Eigen::Vector3d sides[4] = {b - a, c - b, d - c, a - d};
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector3d& u = sides[k];
        const Eigen::Vector3d& w = sides[(k + 1) % 4];
        if (!(u.cross(w).norm() > 1e-9 * u.norm() * w.norm()))
          throw InputError(FaceName(shape, i, j) +
                           " of the reference is degenerate: two adjacent sides are parallel "
                           "or of zero length");
      }
    }
}

PolyMesh CombescureByPropagation(const PolyMesh& reference, const GridShape& shape,
                                 const CombescureLengths& lengths, double tolerance) {
  CheckCombescureInput(reference, shape, lengths, tolerance);
  std::vector<Eigen::Vector3d> out(shape.num_vertices());
  auto unit = [&](int a, int b) {
    return Eigen::Vector3d((Point(reference, b) - Point(reference, a)).normalized());
  };
  out[0] = lengths.origin;
  for (int j = 0; j < shape.cols; ++j)
    out[shape.Vertex(0, j + 1)] =
        out[shape.Vertex(0, j)] + lengths.row[j] * unit(shape.Vertex(0, j), shape.Vertex(0, j + 1));
  for (int i = 0; i < shape.rows; ++i)
    out[shape.Vertex(i + 1, 0)] =
        out[shape.Vertex(i, 0)] +
        lengths.column[i] * unit(shape.Vertex(i, 0), shape.Vertex(i + 1, 0));
  // Quad (A, B, C, D) = ((i, j), (i+1, j), (i+1, j+1), (i, j+1)) with A, B, D known:
  // C = B + l1 u_BC = D + l2 u_DC, solved in the plane of the quad (000 eq. 4).
  for (int i = 0; i < shape.rows; ++i)
    for (int j = 0; j < shape.cols; ++j) {
      const int b = shape.Vertex(i + 1, j), c = shape.Vertex(i + 1, j + 1),
                d = shape.Vertex(i, j + 1);
      const Eigen::Vector3d u_bc = unit(b, c), u_dc = unit(d, c);
      Eigen::Matrix<double, 3, 2> m;
      m.col(0) = u_bc;
      m.col(1) = -u_dc;
      const Eigen::Vector2d l = (m.transpose() * m).ldlt().solve(m.transpose() * (out[d] - out[b]));
      out[c] = 0.5 * (out[b] + l[0] * u_bc + out[d] + l[1] * u_dc);
    }
  PolyMesh mesh = reference;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d& p = out[v.idx()];
    mesh.set_point(v, PolyMesh::Point(p.x(), p.y(), p.z()));
  }
  return mesh;
}

Problem MakeCombescureProblem(const PolyMesh& reference, const GridShape& shape,
                              const CombescureLengths& lengths, double tolerance) {
  CheckCombescureInput(reference, shape, lengths, tolerance);
  Problem problem;
  const int block = problem.layout().AddBlock("vertices", shape.num_vertices(), 3);
  problem.ResizeToLayout();
  const Eigen::Vector3d shift = lengths.origin - Point(reference, 0);
  const BlockItems item(problem.layout(), block);
  for (int v = 0; v < shape.num_vertices(); ++v)
    problem.x().segment<3>(problem.layout().Index(block, v, 0)) = Point(reference, v) + shift;
  auto* parallel = problem.AddFamily<EdgeParallelism>();
  for (auto e : reference.edges()) {
    const auto h = reference.halfedge_handle(e, 0);
    const int a = reference.from_vertex_handle(h).idx(), b = reference.to_vertex_handle(h).idx();
    parallel->AddEdge(item[a], item[b], Point(reference, b) - Point(reference, a));
  }
  auto* guides = problem.AddFamily<EdgeVector>(1.0, "guide edges");
  for (int j = 0; j < shape.cols; ++j) {
    const int a = shape.Vertex(0, j), b = shape.Vertex(0, j + 1);
    guides->AddEdge(item[a], item[b],
                    lengths.row[j] * (Point(reference, b) - Point(reference, a)).normalized());
  }
  for (int i = 0; i < shape.rows; ++i) {
    const int a = shape.Vertex(i, 0), b = shape.Vertex(i + 1, 0);
    guides->AddEdge(item[a], item[b],
                    lengths.column[i] * (Point(reference, b) - Point(reference, a)).normalized());
  }
  // v − origin = 0 as a hard constraint: fixes the translation of the parallel mesh.
  problem.AddFamily<Closeness>(3, 1.0, "anchor", FamilyRole::kConstraint)
      ->AddTarget(item[0], lengths.origin.data());
  return problem;
}

SolverOptions CombescureSolverDefaults() {
  SolverOptions options;
  options.max_iterations = 5;
  options.epsilon = 1e-6;
  options.residual_tolerance = 1e-11;
  options.step_tolerance = 0.0;
  options.eliminate_auxiliaries = false;
  return options;
}

bool CombescureOptions::IsValid(std::string* why) const {
  for (const double t : {reference_tolerance, tolerance, propagation_tolerance})
    if (!(t > 0.0) || !std::isfinite(t)) {
      *why = "tolerances must be finite and > 0";
      return false;
    }
  return solver.IsValid(why);
}

ParallelismMeasures MeasureParallelism(const PolyMesh& reference, const PolyMesh& mesh) {
  ParallelismMeasures m;
  m.min_length_ratio = std::numeric_limits<double>::infinity();
  for (auto e : reference.edges()) {
    const auto h = reference.halfedge_handle(e, 0);
    const int a = reference.from_vertex_handle(h).idx(), b = reference.to_vertex_handle(h).idx();
    const Eigen::Vector3d r = Point(reference, b) - Point(reference, a);
    const Eigen::Vector3d s = Point(mesh, b) - Point(mesh, a);
    const double angle = std::atan2(r.cross(s).norm(), std::abs(r.dot(s)));
    if (angle > m.max_angle || m.worst_edge < 0) {
      m.max_angle = angle;
      m.worst_edge = e.idx();
    }
    m.min_length_ratio =
        std::min(m.min_length_ratio, (r.dot(s) >= 0 ? 1.0 : -1.0) * s.norm() / r.norm());
  }
  return m;
}

Combescure::Combescure(const PolyMesh& reference, const GridShape& shape,
                       const CombescureLengths& lengths, const CombescureOptions& options)
    : options_(options), reference_(reference), shape_(shape), lengths_(lengths) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid option: " + why);
  problem_ = MakeCombescureProblem(reference, shape, lengths, options.reference_tolerance);
}

CeresOptions Combescure::ceres_options(int max_iterations) const {
  return CeresOptionsFor(options_.solver, max_iterations);
}

int Combescure::VertexOffset(int v) const { return problem_.layout().Index(0, v, 0); }

PolyMesh Combescure::MeshAt(const Eigen::VectorXd& x) const {
  PolyMesh mesh = reference_;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = x.segment<3>(VertexOffset(v.idx()));
    mesh.set_point(v, PolyMesh::Point(p.x(), p.y(), p.z()));
  }
  return mesh;
}

double Combescure::GuideErrorAt(const PolyMesh& mesh) const {
  double error = (Point(mesh, 0) - lengths_.origin).norm(), scale = 0.0;
  const auto guide = [&](int a, int b, double length) {
    const Eigen::Vector3d asked =
        length * (Point(reference_, b) - Point(reference_, a)).normalized();
    error = std::max(error, (Point(mesh, b) - Point(mesh, a) - asked).norm());
    scale += std::abs(length);
  };
  for (int j = 0; j < shape_.cols; ++j)
    guide(shape_.Vertex(0, j), shape_.Vertex(0, j + 1), lengths_.row[j]);
  for (int i = 0; i < shape_.rows; ++i)
    guide(shape_.Vertex(i, 0), shape_.Vertex(i + 1, 0), lengths_.column[i]);
  scale /= shape_.rows + shape_.cols;
  return scale > 0.0 ? error / scale : error;
}

NamedValues Combescure::MeasureAt(const Eigen::VectorXd& x) const {
  const PolyMesh mesh = MeshAt(x);
  const ParallelismMeasures p = MeasureParallelism(reference_, mesh);
  NamedValues m = MeasureCircularMesh(mesh);
  m.push_back({"max_edge_parallelism_angle", p.max_angle});
  m.push_back({"worst_parallel_edge", static_cast<double>(p.worst_edge)});
  m.push_back({"min_edge_length_ratio", p.min_length_ratio});
  m.push_back({"max_guide_error", GuideErrorAt(mesh)});
  return m;
}

bool Combescure::WithinTolerance(const NamedValues& m, double tolerance) {
  return ValueOf(m, "max_edge_parallelism_angle") <= tolerance &&
         ValueOf(m, "max_guide_error") <= tolerance;
}

RunReport Combescure::RunPropagation() {
  const Construction construction(ConstructionMethod::kPropagation, "propagation");
  const NamedValues initial = Measure();
  const PolyMesh mesh =
      CombescureByPropagation(reference_, shape_, lengths_, options_.reference_tolerance);
  for (auto v : mesh.vertices())
    problem_.x().segment<3>(VertexOffset(v.idx())) = Point(mesh, v.idx());
  const NamedValues final = Measure();
  return construction.Finish(initial, final,
                             WithinTolerance(final, options_.propagation_tolerance));
}

}  // namespace gproj::circular
