#include "gproj/problems/pq/pq_planarization.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "gproj/constraints/circular_quad.h"
#include "gproj/constraints/closeness.h"
#include "gproj/constraints/normal_orthogonality.h"
#include "gproj/constraints/quad_planarity.h"
#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/mesh/polygon_shape.h"
#include "gproj/problems/mesh/mesh_variables.h"

namespace gproj::pq {

SolverOptions PQPlanarizationSolverDefaults() {
  SolverOptions s;
  s.max_iterations = 50;
  s.residual_tolerance = 0.0;  // the planarity measure decides, through the callback
  s.step_tolerance = 1e-15;
  s.fairness_weight = 1.0;
  s.soft_weight_decay = 0.1;
  // No floor: once planarity is near, any fixed floor would hold it at the ratio of the soft
  // weights to its own (a smooth non-conjugate grid stalled at 8e-9 with 1e-12); ε keeps
  // every system regular.
  s.soft_weight_floor = 0.0;
  // Tied to the residual: once the quads are nearly planar the soft weights and ε fall with
  // it, and the last steps converge quadratically (the 201 × 201 noisy grid reaches 1e-6 in 7
  // iterations instead of 10).
  s.soft_weight_residual_factor = 1.0;
  s.epsilon_min = 1e-6;
  s.monotone = true;
  return s;
}

nlohmann::json OptionsJson(const PQPlanarizationOptions& o) {
  return {{"tolerance", o.tolerance},
          {"max_iterations", o.solver.max_iterations},
          {"planarity_weight", o.planarity_weight},
          {"closeness_weight", o.closeness_weight},
          {"fairness_weight", o.solver.fairness_weight},
          {"fairness_order", o.fairness_order},
          {"soft_weight_decay", o.solver.soft_weight_decay},
          {"soft_weight_floor", o.solver.soft_weight_floor},
          {"soft_weight_residual_factor", o.solver.soft_weight_residual_factor},
          {"epsilon", o.solver.epsilon},
          {"epsilon_min", o.solver.epsilon_min},
          {"monotone", o.solver.monotone},
          {"min_angle_deg", o.panels.corners ? o.panels.min_angle_deg : -1.0},
          {"min_edge_length", o.panels.min_edge_length},
          {"max_edge_length", o.panels.max_edge_length},
          {"min_edge_fraction", o.panels.min_edge_fraction},
          {"circular", o.circular},
          {"fixed_vertices", o.vertices.fixed.size()},
          {"fix_boundary", o.vertices.fix_boundary},
          {"glide_boundary", o.vertices.glide_boundary},
          {"ceres_soft_scale", o.ceres_soft_scale}};
}

ColourScale PlanarityColourScale(const PolyMesh& result, bool circular) {
  return ScaleFor(circular ? "max(planarity, concyclicity)" : "planarity",
                  RelativeFacePlanarity(result, circular), /*logarithmic=*/true);
}

nlohmann::json PlanarizationFacts(const PolyMesh& input, const PolyMesh& result,
                                  const PQPlanarizationOptions& options) {
  return {{"linear_solver", LinearSolverTypeName(options.solver.linear_solver)},
          {"vertices", input.n_vertices()},
          {"faces", input.n_faces()},
          {"options", OptionsJson(options)},
          {"shape_change", ShapeChangeJson(CompareCornerAngles(input, result))},
          {"colour_scale", ColourScaleJson(PlanarityColourScale(result, options.circular))}};
}

bool PQPlanarizationOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    *why = text;
    return false;
  };
  if (!(planarity_weight > 0.0) || !std::isfinite(planarity_weight))
    return fail("planarity weight must be finite and > 0");
  if (!(closeness_weight >= 0.0) || !std::isfinite(closeness_weight))
    return fail("closeness weight must be finite and ≥ 0");
  if (!(ceres_soft_scale >= 0.0) || !std::isfinite(ceres_soft_scale))
    return fail("ceres soft scale must be finite and ≥ 0");
  if (fairness_order != 2 && fairness_order != 3) return fail("fairness order must be 2 or 3");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    return fail("tolerance must be finite and > 0");
  if (!(reference_tangent_weight >= 0.0) || !std::isfinite(reference_tangent_weight) ||
      !(reference_point_weight >= 0.0) || !std::isfinite(reference_point_weight))
    return fail("reference weights must be finite and ≥ 0");
  return panels.IsValid(why) && vertices.IsValid(why) && solver.IsValid(why);
}

PQPlanarization::PQPlanarization(const PolyMesh& mesh, const PQPlanarizationOptions& options,
                                 const PolyMesh* reference, const PolyMesh* kept)
    : MeshProblem(mesh), options_(options), kept_(kept) {
  if (kept && kept->n_vertices() != mesh.n_vertices())
    throw InputError("the faces kept valid are not on the mesh's vertices");
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid planarisation options: " + why);
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  // A face normal per face of 4 or more corners; triangles are planar and left to closeness
  // and fairness.
  std::vector<int> normal_of(mesh.n_faces(), -1);
  int normals = 0;
  for (auto f : mesh.faces()) {
    const int n = static_cast<int>(mesh.valence(f));
    if (options.circular && n != 4)
      throw InputError("face " + std::to_string(f.idx()) + " has " + std::to_string(n) +
                       " vertices; a circular mesh is made of quads");
    if (n >= 4) normal_of[f.idx()] = normals++;
  }
  if (normals == 0)
    throw InputError("every face is a triangle; planarisation needs faces of 4 or more vertices");

  VariableLayout& layout = problem_.layout();
  normal_block_ = options.circular
                      ? layout.AddBlock("face_circles", normals, CircularQuad::kAuxiliaryDim,
                                        /*eliminable=*/true)
                      : layout.AddBlock("face_normals", normals, 3, /*eliminable=*/true);
  LoadInputVertices();
  Eigen::VectorXd& x = problem_.x();
  const BlockItems vertex = vertices(), aux = BlockItems(layout, normal_block_);

  QuadPlanarity* planarity = nullptr;
  CircularQuad* circularity = nullptr;
  EdgeNormalOrthogonality* polygon_edges = nullptr;
  UnitNormal* polygon_normals = nullptr;
  if (options.circular)
    circularity = problem_.AddFamily<CircularQuad>(options.planarity_weight);
  else
    planarity = problem_.AddFamily<QuadPlanarity>(options.planarity_weight);
  if (!options.circular &&
      normals > static_cast<int>(std::count_if(mesh.faces_begin(), mesh.faces_end(),
                                               [&mesh](auto f) { return mesh.valence(f) == 4; }))) {
    polygon_edges =
        problem_.AddFamily<EdgeNormalOrthogonality>("polygon_planarity", options.planarity_weight);
    polygon_normals =
        problem_.AddFamily<UnitNormal>("polygon_unit_normal", options.planarity_weight);
  }
  for (auto f : mesh.faces()) {
    const int item = normal_of[f.idx()];
    if (item < 0) continue;
    std::vector<int> v;
    for (auto fv : mesh.fv_range(f)) v.push_back(fv.idx());
    std::vector<Eigen::Vector3d> p;
    for (int j : v) p.push_back(x.segment<3>(layout.Index(vertex_block_, j, 0)));
    if (v.size() > 4) {  // n · (v_{j+1} − v_j) = 0 on every edge, |n| = 1
      x.segment<3>(layout.Index(normal_block_, item, 0)) = PolygonNormal(p);
      for (size_t j = 0; j < v.size(); ++j)
        polygon_edges->Add({aux[item], vertex[v[j]], vertex[v[(j + 1) % v.size()]]});
      polygon_normals->Add({aux[item]});
    } else if (circularity) {
      x.segment<CircularQuad::kAuxiliaryDim>(layout.Index(normal_block_, item, 0)) =
          CircularQuad::InitialAuxiliary({p[0], p[1], p[2], p[3]});
      circularity->AddQuad(aux[item], vertex[v[0]], vertex[v[1]], vertex[v[2]], vertex[v[3]]);
    } else {
      x.segment<3>(layout.Index(normal_block_, item, 0)) =
          QuadPlanarity::InitialNormal(p[0], p[1], p[2], p[3]);
      planarity->AddQuad(aux[item], vertex[v[0]], vertex[v[1]], vertex[v[2]], vertex[v[3]]);
    }
  }
  if (reference != nullptr) {
    AddReferenceCloseness(*reference, norm_, vertex_block_, static_cast<int>(mesh.n_vertices()),
                          options.closeness_weight * options.reference_tangent_weight,
                          options.closeness_weight * options.reference_point_weight, &problem_);
  } else if (options.closeness_weight > 0.0) {
    auto* closeness = problem_.AddFamily<Closeness>(3, options.closeness_weight);
    for (auto v : mesh.vertices()) {
      const int index = layout.Index(vertex_block_, v.idx(), 0);
      closeness->AddTarget(vertex[v], x.data() + index);
    }
  }
  if (options.solver.fairness_weight > 0.0)
    AddMeshFairness(mesh, options.fairness_order, vertex_block_, &problem_);
  AddBoundsAndControl(options.panels, options.vertices);
  if (kept)
    kept_bounds_ =
        AddPanelBounds(*kept, norm_, vertex_block_, options.panels, &problem_, "kept_faces_");
  start_planarity_ = MeasurePlanarity(mesh, mesh).max_planarity;
  if (options.circular)
    start_planarity_ = std::max(start_planarity_, MeasureCircularity(mesh).max_concyclicity);
}

SolverOptions PQPlanarization::solver_options() const {
  return WithStartSoftScale(options_.solver, start_planarity_);
}

std::vector<int> PQPlanarization::FacesAboveTolerance() const {
  StoreVertices(problem_, vertex_block_, norm_, &current_);
  const std::vector<double> planarity = RelativeFacePlanarity(current_, false);
  std::vector<std::pair<double, int>> above;
  for (size_t f = 0; f < planarity.size(); ++f)
    if (planarity[f] > options_.tolerance) above.emplace_back(-planarity[f], static_cast<int>(f));
  std::sort(above.begin(), above.end());
  std::vector<int> faces;
  for (const auto& entry : above) faces.push_back(entry.second);
  return faces;
}

PlanarityMeasures PQPlanarization::MeasuresAt(const Eigen::VectorXd& x) const {
  const PolyMesh& mesh = MeshAt(x);
  PlanarityMeasures m = MeasurePlanarity(mesh, input_);
  if (options_.circular) m.max_concyclicity = MeasureCircularity(mesh).max_concyclicity;
  if (control_.glide != nullptr)
    m.max_glide_distance = control_.MaxGlideDistance(problem_.layout(), x);
  return m;
}

bool PQPlanarization::MeetsTolerance(const NamedValues& m) const {
  return ValueOf(m, "max_planarity") <= options_.tolerance && EdgesInRange(m) &&
         (!options_.circular || ValueOf(m, "max_concyclicity") <= options_.tolerance);
}

CeresOptions PQPlanarization::ceres_options(int max_iterations) const {
  return CeresOptionsFor(options_.solver, max_iterations,
                         options_.ceres_soft_scale > 0.0
                             ? options_.ceres_soft_scale
                             : std::min(1.0, options_.tolerance * 1e-2));
}

std::vector<int> PQPlanarization::KeptFacesAtAngleBound() const {
  if (!kept_) return {};
  PolyMesh kept = *kept_;
  const PolyMesh result = Result();  // once: it copies the mesh
  for (auto v : kept.vertices()) kept.set_point(v, result.point(v));
  return FacesAtCornerBound(kept, kept_bounds_);
}

}  // namespace gproj::pq
