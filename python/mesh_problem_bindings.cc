// gproj.hnet: the command `gproj hnet` as calls on numpy arrays, with the same reports.
#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "problems/anet.h"
#include "problems/hnet.h"
#include "python/conversions.h"
#include "python/module.h"
#include "python/run_bridge.h"
#include "python/solver_args.h"

namespace gproj::python {
namespace {

std::unique_ptr<PolyMesh> ReferenceMesh(const py::object& reference) {
  if (reference.is_none()) return nullptr;
  const auto pair = reference.cast<py::tuple>();
  if (pair.size() != 2) throw InputError("reference must be a pair (V, F)");
  return std::make_unique<PolyMesh>(MeshFromArrays(pair[0], pair[1], false));
}

// 0-based vertex ids from a sequence or integer array (None: none).
std::vector<int> VertexIds(const py::object& ids, int num_vertices) {
  std::vector<int> out;
  if (ids.is_none()) return out;
  for (long long id : ids.cast<std::vector<long long>>()) {
    if (id < 0 || id >= num_vertices)
      throw InputError("fixed vertex " + std::to_string(id) + " is out of range (the mesh has " +
                       std::to_string(num_vertices) + " vertices)");
    out.push_back(static_cast<int>(id));
  }
  return out;
}

// The valid-panel and vertex-control arguments shared by planarize, anet and hnet.
void ApplyMeshControl(double min_angle, const py::object& edge_length, bool allow_folds,
                      const py::object& fixed, bool fix_boundary, bool glide_boundary,
                      int num_vertices, PanelBoundsOptions* panels,
                      VertexControlOptions* vertices) {
  panels->min_angle_deg = min_angle;
  if (!edge_length.is_none()) {
    const auto bounds = edge_length.cast<std::pair<double, double>>();
    panels->min_edge_length = bounds.first;
    panels->max_edge_length = bounds.second;
  }
  if (allow_folds) panels->AllowFolds();
  vertices->fixed = VertexIds(fixed, num_vertices);
  vertices->fix_boundary = fix_boundary;
  vertices->glide_boundary = glide_boundary;
  std::string why;
  if (!panels->IsValid(&why) || !vertices->IsValid(&why))
    throw InputError("invalid option: " + why);
}

const char* const kStarFormDoc = R"(
    star_form: "normals" (an auxiliary normal per inner vertex) or "quads" (n-2 quads per star).
    tolerance: stop when max star planarity (neighbour distance from the star plane / mean
        edge) <= this.
    tangent: weight of the distance to the reference's tangent planes.
    point: weight of the distance to the reference's closest points.
    fairness_order: 2 or 3.
    reference: None (the input itself) or a reference surface (Vr, Fr), any polygon mesh.
    min_angle, edge_length, allow_folds: the quads' corner-angle and edge-length bounds, as for
        planarize (see its docstring).
    fixed, fix_boundary, glide_boundary: held and gliding vertices, as for planarize.
)";

ANetOptions NetOptions(const std::string& star_form, double tolerance, double tangent, double point,
                       int fairness_order, const SolverArgs& solver) {
  if (star_form != "normals" && star_form != "quads")
    throw InputError("star_form must be normals or quads, not '" + star_form + "'");
  ANetOptions o;
  o.star_form = star_form == "quads" ? StarPlanarityForm::kQuads : StarPlanarityForm::kNormals;
  o.tolerance = tolerance;
  o.tangent_weight = tangent;
  o.point_weight = point;
  o.fairness_order = fairness_order;
  solver.ApplyTo(&o.solver);
  std::string why;
  if (!o.IsValid(&why)) throw InputError("invalid option: " + why);
  return o;
}

py::tuple RunHNet(const py::object& vertices, const py::object& faces, const std::string& star_form,
                  double tolerance, double tangent, double point, int fairness_order,
                  const py::object& reference, double min_angle, const py::object& edge_length,
                  bool allow_folds, const py::object& fixed, bool fix_boundary, bool glide_boundary,
                  int rounds, double frame_weight, bool allow_not_simply_connected,
                  int surface_samples, const py::object& callback, int max_iterations,
                  double fairness, double epsilon, double soft_decay, double soft_floor,
                  double soft_residual, double epsilon_min, const std::string& linear_solver,
                  int threads) {
  HNetOptions options;
  options.anet = NetOptions(star_form, tolerance, tangent, point, fairness_order,
                            {max_iterations, fairness, epsilon, soft_decay, soft_floor,
                             soft_residual, epsilon_min, linear_solver, threads});
  if (rounds < 1 || rounds > 1000) throw InputError("rounds must be in [1, 1000]");
  if (!(frame_weight > 0.0)) throw InputError("frame_weight must be > 0");
  if (surface_samples < 0 || surface_samples > 200)
    throw InputError("surface_samples must be in [0, 200] (0: no surface mesh)");
  options.max_rounds = rounds;
  options.frame_weight = frame_weight;
  options.allow_not_simply_connected = allow_not_simply_connected;
  const PolyMesh mesh = MeshFromArrays(vertices, faces, true);
  CheckANetTopology(mesh, "mesh");
  ApplyMeshControl(min_angle, edge_length, allow_folds, fixed, fix_boundary, glide_boundary,
                   static_cast<int>(mesh.n_vertices()), &options.anet.panels,
                   &options.anet.vertices);
  const std::unique_ptr<PolyMesh> ref = ReferenceMesh(reference);
  HNet hnet(mesh, ref.get(), options);
  RunBridge bridge(callback);
  const HNetSummary summary = bridge.Call([&] { return hnet.Run(bridge.callback()); });
  nlohmann::json report = HNet::ReportJson(summary);
  report.update({{"input", nullptr}, {"output", nullptr}});
  const bool usable = !summary.report.failed && !summary.rounds.empty();
  if (!usable) return py::make_tuple(py::none(), JsonToPython(report));
  py::dict result = JsonToPython(HNetJson(hnet.mesh(), hnet.weights()));
  if (surface_samples > 0)
    result["surface"] =
        MeshToPython(SampleHNetSurface(hnet.mesh(), hnet.weights(), surface_samples));
  return py::make_tuple(result, JsonToPython(report));
}

const char* const kHNetDoc = R"(hnet(V, F, ...) -> (hnet, report)

H-net (`gproj hnet`): extends an A-net (running the A-net step first when needed) to smoothly
joined rational bilinear patches (004 §2-3).

    V: (n, 3) float64, F: (m, 4) integer quads of a simply connected mesh with even inner
        valences.
    rounds: alternations of weight and vertex updates at most.
    frame_weight: weight of frame-point planarity.
    allow_not_simply_connected: optimise meshes that are not simply connected.
    surface_samples: when > 0, also sample every patch on a (k + 1) x (k + 1) grid (as
        `--surface-mesh` with `--samples k`) into result["surface"] = (V: (N, 3) float64,
        F: (M, 3) int32), a triangle mesh to look at or render.
    callback: as for planarize, with the A-net step's records.

Returns the H-net as a dict (the JSON of `gproj hnet -o`: "vertices" (n, 3), "faces" and four
corner "weights" per face, plus "surface" when asked; None when the run failed) and the report
dict.
)";

}  // namespace

void BindMeshProblems(py::module_& m) {
  const ANetOptions an;
  const auto net_args = std::make_tuple(
      py::arg("V"), py::arg("F"), py::kw_only(), py::arg("star_form") = "normals",
      py::arg("tolerance") = an.tolerance, py::arg("tangent") = an.tangent_weight,
      py::arg("point") = an.point_weight, py::arg("fairness_order") = an.fairness_order,
      py::arg("reference") = py::none(), py::arg("min_angle") = an.panels.min_angle_deg,
      py::arg("edge_length") = py::none(), py::arg("allow_folds") = false,
      py::arg("fixed") = py::none(), py::arg("fix_boundary") = false,
      py::arg("glide_boundary") = false);
  const HNetOptions hn;
  DefineFunction(m, "hnet", &RunHNet,
                 (std::string(kHNetDoc) + kStarFormDoc + kSolverArgsDoc).c_str(),
                 std::tuple_cat(net_args,
                                std::make_tuple(py::arg("rounds") = hn.max_rounds,
                                                py::arg("frame_weight") = hn.frame_weight,
                                                py::arg("allow_not_simply_connected") = false,
                                                py::arg("surface_samples") = 0,
                                                py::arg("callback") = py::none()),
                                SolverArgList(hn.anet.solver)));
}

}  // namespace gproj::python
