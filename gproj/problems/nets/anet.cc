#include "gproj/problems/nets/anet.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gproj/constraints/closeness.h"
#include "gproj/constraints/normal_orthogonality.h"
#include "gproj/constraints/quad_diagonal_planarity.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/solver/ceres_adapter.h"

namespace gproj::nets {

const char* NetKindName(NetKind net) { return net == NetKind::kDiagonals ? "diagonal" : "edges"; }

std::vector<int> StarPoints(const PolyMesh& mesh, PolyMesh::VertexHandle v, NetKind net) {
  std::vector<int> points;
  ForEachStarPoint(mesh, v, net,
                   [&points](PolyMesh::VertexHandle w) { points.push_back(w.idx()); });
  return points;
}

namespace {

// Unit normal of the least-squares plane through c containing the points as well as possible.
Eigen::Vector3d StarNormal(const Eigen::Vector3d& c, const std::vector<Eigen::Vector3d>& points) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const auto& p : points) m += (p - c) * (p - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(m);
  return eigen.eigenvectors().col(0);
}

}  // namespace

bool ANetOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    *why = text;
    return false;
  };
  for (double w : {planarity_weight, tangent_weight, point_weight, anchor_weight, ceres_soft_scale})
    if (!(w >= 0.0) || !std::isfinite(w)) return fail("weights must be finite and ≥ 0");
  if (!(planarity_weight > 0.0)) return fail("planarity weight must be > 0");
  if (fairness_order != 2 && fairness_order != 3) return fail("fairness order must be 2 or 3");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    return fail("tolerance must be finite and > 0");
  return panels.IsValid(why) && vertices.IsValid(why) && solver.IsValid(why);
}

SolverOptions ANetSolverDefaults() {
  SolverOptions s;
  s.max_iterations = 50;
  s.residual_tolerance = 0.0;  // the star-planarity measure decides, through the callback
  s.step_tolerance = 1e-15;
  s.fairness_weight = 0.5;
  s.soft_weight_decay = 0.1;
  s.soft_weight_floor = 1e-12;
  // Tied to the residual as for planarisation: 9 iterations instead of 13 on a noisy 61 × 61
  // Enneper net, with less displacement.
  s.soft_weight_residual_factor = 1.0;
  s.epsilon_min = 1e-6;
  s.monotone = true;
  return s;
}

NamedValues ToNamedValues(const StarPlanarityMeasures& m) {
  NamedValues values = {{"max_star_planarity", m.max_star_planarity},
                        {"mean_star_planarity", m.mean_star_planarity},
                        {"worst_vertex", static_cast<double>(m.worst_vertex)},
                        {"max_displacement", m.max_displacement}};
  if (m.max_glide_distance >= 0.0) values.push_back({"max_glide_distance", m.max_glide_distance});
  for (NamedValue& v : ShapeValues(m.shape)) values.push_back(std::move(v));
  return values;
}

namespace {

// Per vertex: the largest distance of a neighbour from the star's least-squares plane / mean
// edge (−1 for vertices with fewer than three neighbours).
std::vector<double> VertexStarPlanarity(const PolyMesh& mesh, NetKind net) {
  const double mean_edge = MeanEdgeLength(mesh);
  std::vector<double> values(mesh.n_vertices(), -1.0);
  std::vector<Eigen::Vector3d> points, ring;  // reused: measured every iteration
  for (auto v : mesh.vertices()) {
    points.assign(1, ToEigen(mesh.point(v)));  // the centre first, then the ring
    ForEachStarPoint(mesh, v, net,
                     [&](PolyMesh::VertexHandle w) { points.push_back(ToEigen(mesh.point(w))); });
    if (points.size() < 4) continue;  // fewer than three star points
    // Measured at unit size (the centre at the origin), so that it is scale-free.
    const double extent = NormalizePolygon(points.data(), static_cast<int>(points.size()));
    ring.assign(points.begin() + 1, points.end());
    const Eigen::Vector3d n = StarNormal(points[0], ring);
    double worst = 0.0;
    for (const auto& p : ring) worst = std::max(worst, std::abs(n.dot(p - points[0])));
    values[v.idx()] = worst * extent / mean_edge;
  }
  return values;
}

}  // namespace

std::vector<double> FaceStarPlanarity(const PolyMesh& mesh, NetKind net) {
  const std::vector<double> star = VertexStarPlanarity(mesh, net);
  std::vector<double> values(mesh.n_faces(), 0.0);
  for (auto f : mesh.faces())
    for (auto v : mesh.fv_range(f)) values[f.idx()] = std::max(values[f.idx()], star[v.idx()]);
  return values;
}

std::string ANetFaceValuesCsv(const PolyMesh& mesh, NetKind net) {
  const std::vector<double> star = FaceStarPlanarity(mesh, net);
  const std::vector<QuadShape> shapes = MeasureQuadShapes(mesh);
  std::string csv = "face,star_planarity,kink_deg,min_angle_deg\n";
  char line[128];
  for (auto f : mesh.faces()) {
    std::snprintf(line, sizeof(line), "%d,%.6e,%.6e,%.6f\n", f.idx(), star[f.idx()],
                  shapes[f.idx()].kink_deg, shapes[f.idx()].min_angle_deg);
    csv += line;
  }
  return csv;
}

ColourScale StarPlanarityColourScale(const PolyMesh& result, NetKind net) {
  return ScaleFor(net == NetKind::kDiagonals ? "diagonal star planarity" : "star planarity",
                  FaceStarPlanarity(result, net), /*logarithmic=*/true);
}

StarPlanarityMeasures MeasureStarPlanarity(const PolyMesh& mesh, const PolyMesh& reference,
                                           NetKind net) {
  StarPlanarityMeasures m;
  double sum = 0.0;
  int count = 0;
  const std::vector<double> star = VertexStarPlanarity(mesh, net);
  for (auto v : mesh.vertices()) {
    const double worst = star[v.idx()];
    if (worst < 0.0) continue;
    if (worst > m.max_star_planarity) {
      m.max_star_planarity = worst;
      m.worst_vertex = v.idx();
    }
    sum += worst;
    ++count;
  }
  m.mean_star_planarity = count > 0 ? sum / count : 0.0;
  m.max_displacement = MaxDisplacement(mesh, reference);
  m.shape = Summarize(MeasureQuadShapes(mesh));
  return m;
}

nlohmann::json ANetFacts(const PolyMesh& input, const PolyMesh& result, NetKind net) {
  return {
      {"vertices", input.n_vertices()},
      {"faces", input.n_faces()},
      {"net", NetKindName(net)},
      {"shape_change", ShapeChangeJson(CompareCornerAngles(input, result, kANetShapeChangeDeg))},
      {"colour_scale", ColourScaleJson(StarPlanarityColourScale(result, net))}};
}

void CheckANetTopology(const PolyMesh& mesh, const std::string& path) {
  const std::string prefix = path.empty() ? "" : path + ": ";
  for (auto f : mesh.faces())
    if (mesh.valence(f) != 4)
      throw InputError(prefix + "face " + std::to_string(f.idx()) + " has " +
                       std::to_string(mesh.valence(f)) + " vertices; a quad mesh is required");
  for (auto v : mesh.vertices())
    if (!mesh.is_boundary(v) && mesh.valence(v) % 2 != 0)
      throw InputError(prefix + "vertex " + std::to_string(v.idx()) + " has valence " +
                       std::to_string(mesh.valence(v)) +
                       "; inner vertices of an A-net must have even valence");
}

ANetFamilies AddANetLayout(const PolyMesh& mesh, const ANetOptions& options, Problem* problem) {
  ANetFamilies out;
  for (auto v : mesh.vertices()) {
    std::vector<int> points = StarPoints(mesh, v, options.net);
    if (points.size() < 3) continue;
    out.star_vertices.push_back(v.idx());
    out.star_points.push_back(std::move(points));
  }
  if (options.star_form == StarPlanarityForm::kNormals)
    out.normal_block = problem->layout().AddBlock(
        "star_normals", static_cast<int>(out.star_vertices.size()), 3, /*eliminable=*/true);
  return out;
}

void AddANetFamilies(const PolyMesh& mesh, const ANetOptions& options, int vertex_block,
                     const ANetFamilies& layout_info, const PolyMesh* reference,
                     const MeshNormalization& norm, Problem* problem) {
  const VariableLayout& layout = problem->layout();
  const BlockItems vertex(layout, vertex_block);
  if (options.star_form == StarPlanarityForm::kNormals) {
    auto* star =
        problem->AddFamily<EdgeNormalOrthogonality>("star_planarity", options.planarity_weight);
    auto* unit = problem->AddFamily<UnitNormal>("star_unit_normal", options.planarity_weight);
    for (size_t k = 0; k < layout_info.star_vertices.size(); ++k) {
      const int v = layout_info.star_vertices[k];
      const int normal = BlockItems(layout, layout_info.normal_block)[static_cast<int>(k)];
      unit->Add({normal});
      for (int w : layout_info.star_points[k]) star->Add({normal, vertex[v], vertex[w]});
    }
  } else {
    auto* quads =
        problem->AddFamily<QuadDiagonalPlanarity>("star_planarity", options.planarity_weight);
    // n − 3 quads of neighbours make the ring planar, one quad with v puts v in that plane.
    // (Quads of v with two opposite neighbours would be satisfied by straightening the mesh
    // polylines instead of flattening the star.)
    for (size_t k = 0; k < layout_info.star_vertices.size(); ++k) {
      const int v = layout_info.star_vertices[k];
      const std::vector<int>& r = layout_info.star_points[k];
      for (size_t i = 2; i + 1 < r.size(); ++i)
        quads->Add({vertex[r[0]], vertex[r[1]], vertex[r[i]], vertex[r[i + 1]]});
      quads->Add({vertex[r[0]], vertex[r[1]], vertex[r[2]], vertex[v]});
    }
  }
  if (reference != nullptr)
    AddReferenceCloseness(*reference, norm, vertex_block, static_cast<int>(mesh.n_vertices()),
                          options.tangent_weight, options.point_weight, problem);
  if (options.anchor_weight > 0.0) {
    auto* anchor = problem->AddFamily<Closeness>(3, options.anchor_weight, "anchor");
    for (auto v : mesh.vertices()) {
      const Eigen::Vector3d p = norm.ToProblem(ToEigen(mesh.point(v)));
      anchor->AddTarget(vertex[v.idx()], p.data());
    }
  }
  if (options.solver.fairness_weight > 0.0)
    AddMeshFairness(mesh, options.fairness_order, vertex_block, problem);
}

void LoadANetNormals(const PolyMesh& mesh, int vertex_block, const ANetFamilies& layout_info,
                     Problem* problem) {
  if (layout_info.normal_block < 0) return;
  const VariableLayout& layout = problem->layout();
  Eigen::VectorXd& x = problem->x();
  std::vector<Eigen::Vector3d> points;
  for (size_t k = 0; k < layout_info.star_vertices.size(); ++k) {
    const int v = layout_info.star_vertices[k];
    points.clear();
    for (int w : layout_info.star_points[k])
      points.push_back(x.segment<3>(layout.Index(vertex_block, w, 0)));
    x.segment<3>(layout.Index(layout_info.normal_block, static_cast<int>(k), 0)) =
        StarNormal(x.segment<3>(layout.Index(vertex_block, v, 0)), points);
  }
}

ANet::ANet(const PolyMesh& mesh, const PolyMesh* reference, const ANetOptions& options)
    : MeshProblem(mesh), options_(options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid A-net options: " + why);
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  CheckANetTopology(mesh, "");
  families_ = AddANetLayout(mesh, options, &problem_);
  LoadInputVertices();
  LoadANetNormals(mesh, vertex_block_, families_, &problem_);
  AddANetFamilies(mesh, options, vertex_block_, families_, reference != nullptr ? reference : &mesh,
                  norm_, &problem_);
  AddBoundsAndControl(options.panels, options.vertices);
  start_planarity_ = MeasureStarPlanarity(mesh, mesh, options.net).max_star_planarity;
}

SolverOptions ANet::solver_options() const {
  return WithStartSoftScale(options_.solver, start_planarity_);
}

StarPlanarityMeasures ANet::MeasuresAt(const Eigen::VectorXd& x) const {
  StarPlanarityMeasures m = MeasureStarPlanarity(MeshAt(x), input_, options_.net);
  if (control_.glide != nullptr)
    m.max_glide_distance = control_.MaxGlideDistance(problem_.layout(), x);
  return m;
}

CeresOptions ANet::ceres_options(int max_iterations) const {
  return CeresOptionsFor(
      options_.solver, max_iterations,
      options_.ceres_soft_scale > 0.0 ? options_.ceres_soft_scale : options_.tolerance / 100.0);
}

}  // namespace gproj::nets
