#include "gproj/problems/mesh/panel_bounds.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gproj {

bool PanelBoundsOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    *why = text;
    return false;
  };
  if (!(min_angle_deg >= 0.0 && min_angle_deg < 60.0))
    return fail("the minimum corner angle must be in [0, 60) degrees");
  if (!(min_edge_length >= 0.0) || !std::isfinite(min_edge_length))
    return fail("the minimum edge length must be finite and ≥ 0");
  if (!(max_edge_length >= 0.0) || !std::isfinite(max_edge_length))
    return fail("the maximum edge length must be finite and ≥ 0");
  if (max_edge_length > 0.0 && max_edge_length <= min_edge_length)
    return fail("the maximum edge length must exceed the minimum");
  if (!(min_edge_fraction >= 0.0 && min_edge_fraction < 1.0))
    return fail("the minimum edge fraction must be in [0, 1)");
  return true;
}

namespace {

std::array<int, 4> QuadVertices(const PolyMesh& mesh, PolyMesh::FaceHandle f) {
  std::array<int, 4> v{};
  int k = 0;
  for (auto fv : mesh.fv_range(f)) v[k++ % 4] = fv.idx();
  return v;
}

// Vertex v of `mesh` in problem units.
Eigen::Vector3d PointAt(const PolyMesh& mesh, const MeshNormalization& norm, int v) {
  return norm.ToProblem(ToEigen(mesh.point(mesh.vertex_handle(v))));
}

std::array<double, 4> CornerSinesAt(const PolyMesh& mesh, const MeshNormalization& norm,
                                    const std::array<int, 4>& v) {
  Eigen::Vector3d p[4];
  for (int j = 0; j < 4; ++j) p[j] = PointAt(mesh, norm, v[j]);
  std::array<double, 4> sines{};
  QuadCornerSines(p[0].data(), p[1].data(), p[2].data(), p[3].data(), sines.data());
  return sines;
}

// Corner rows on the polygons of N corners (faces: face index, corner vertex ids).
template <int N, size_t... I>
void AddPolygonCorners(const PolyMesh& mesh, const MeshNormalization& norm,
                       const std::vector<std::pair<int, std::vector<int>>>& faces, double min_sine,
                       int vertex_block, const std::string& prefix, Problem* problem,
                       PanelBounds* out, std::index_sequence<I...>) {
  const VariableLayout& layout = problem->layout();
  const BlockItems vertex(layout, vertex_block);
  std::vector<std::pair<std::array<int, N>, PolygonCornerBounds<N>>> elements;
  for (const auto& [face, v] : faces) {
    if (static_cast<int>(v.size()) != N) continue;
    Eigen::Vector3d points[N];
    const double* p[N];
    for (int j = 0; j < N; ++j) {
      points[j] = PointAt(mesh, norm, v[j]);
      p[j] = points[j].data();
    }
    double sines[N];
    PolygonCornerSines(p, N, sines);
    PolygonCornerBounds<N> bounds;
    for (int i = 0; i < N; ++i) bounds.min_sine[i] = std::min(min_sine, sines[i]);
    elements.push_back({{vertex[v[I]]...}, bounds});
    out->polygon_corner_bounds.push_back(
        {face, std::vector<double>(bounds.min_sine.begin(), bounds.min_sine.end())});
  }
  if (elements.empty()) return;
  AddInequalities<PolygonCornerBounds<N>, N, (static_cast<int>(I) * 0 + 3)...>(
      problem, prefix + "corner_angles_" + std::to_string(N), PolygonCornerResidual<N>{}, elements,
      [](const auto& e) { return e; });
}

template <size_t... N>
void AddAllPolygonCorners(const PolyMesh& mesh, const MeshNormalization& norm,
                          const std::vector<std::pair<int, std::vector<int>>>& faces,
                          double min_sine, int vertex_block, const std::string& prefix,
                          Problem* problem, PanelBounds* out, std::index_sequence<N...>) {
  (AddPolygonCorners<static_cast<int>(N) + 5>(mesh, norm, faces, min_sine, vertex_block, prefix,
                                              problem, out, std::make_index_sequence<N + 5>()),
   ...);
}

}  // namespace

PanelBounds AddPanelBounds(const PolyMesh& mesh, const MeshNormalization& norm, int vertex_block,
                           const PanelBoundsOptions& options, Problem* problem,
                           const std::string& prefix) {
  PanelBounds out;
  const VariableLayout& layout = problem->layout();
  const BlockItems vertex(layout, vertex_block);
  if (options.corners) {
    const double min_sine = std::sin(options.min_angle_deg * M_PI / 180.0);
    std::vector<std::pair<std::array<int, 4>, QuadCornerBounds>> quads;
    for (auto f : mesh.faces()) {
      if (mesh.valence(f) != 4) continue;
      const std::array<int, 4> v = QuadVertices(mesh, f);
      const std::array<double, 4> sines = CornerSinesAt(mesh, norm, v);
      QuadCornerBounds bounds;
      for (int i = 0; i < 4; ++i) bounds.min_sine[i] = std::min(min_sine, sines[i]);
      quads.push_back({{vertex[v[0]], vertex[v[1]], vertex[v[2]], vertex[v[3]]}, bounds});
      out.corner_bounds.push_back(bounds);
    }
    out.corners = AddInequalities<QuadCornerBounds, 4, 3, 3, 3, 3>(
        problem, prefix + "corner_angles", QuadCornerResidual{}, quads,
        [](const auto& q) { return q; });
    std::vector<std::pair<int, std::vector<int>>> polygons;
    for (auto f : mesh.faces()) {
      const int n = static_cast<int>(mesh.valence(f));
      if (n < 5) continue;
      if (n > kMaxBoundedCorners) {
        out.unbounded_polygons.push_back(f.idx());
        continue;
      }
      std::vector<int> v;
      for (auto fv : mesh.fv_range(f)) v.push_back(fv.idx());
      polygons.push_back({f.idx(), v});
    }
    AddAllPolygonCorners(mesh, norm, polygons, min_sine, vertex_block, prefix, problem, &out,
                         std::make_index_sequence<kMaxBoundedCorners - 4>());
  }
  auto add_edges = [&](const std::string& name, bool lower, auto bound_of) {
    std::vector<double>& kept = lower ? out.min_edge : out.max_edge;
    std::vector<std::pair<std::array<int, 2>, EdgeLengthBound>> edges;
    for (auto e : mesh.edges()) {
      const auto h = mesh.halfedge_handle(e, 0);
      const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
      const Eigen::Vector3d edge = PointAt(mesh, norm, b) - PointAt(mesh, norm, a);
      const double length = edge.norm();
      EdgeLengthBound bound;
      bound.length = bound_of(length);
      kept.push_back(bound.length / norm.scale);
      if (lower) {
        if (!(length > 0.0)) continue;  // no direction to bound along
        for (int c = 0; c < 3; ++c) bound.direction[c] = edge[c] / length;
      }
      edges.push_back({{vertex[a], vertex[b]}, bound});
    }
    return AddInequalities<EdgeLengthBound, 1, 3, 3>(problem, prefix + name, EdgeLengthResidual{},
                                                     edges, [](const auto& e) { return e; });
  };
  // Lengths in x are in problem units: input units × norm.scale.
  if (options.min_edge_length > 0.0)
    out.min_edges = add_edges("min_edge_length", true,
                              [&](double length) { return options.min_edge_length * norm.scale; });
  else if (options.min_edge_fraction > 0.0)
    out.min_edges = add_edges("min_edge_length", true,
                              [&](double length) { return options.min_edge_fraction * length; });
  if (options.max_edge_length > 0.0)
    out.max_edges = add_edges("max_edge_length", false,
                              [&](double) { return options.max_edge_length * norm.scale; });
  return out;
}

std::vector<int> FacesAtCornerBound(const PolyMesh& mesh, const PanelBounds& bounds,
                                    double margin) {
  std::vector<int> faces;
  size_t q = 0;
  for (auto f : mesh.faces()) {
    if (bounds.corners == nullptr || mesh.valence(f) != 4) continue;
    const std::array<int, 4> v = QuadVertices(mesh, f);
    Eigen::Vector3d p[4];
    for (int j = 0; j < 4; ++j) p[j] = ToEigen(mesh.point(mesh.vertex_handle(v[j])));
    double sines[4];
    QuadCornerSines(p[0].data(), p[1].data(), p[2].data(), p[3].data(), sines);
    const QuadCornerBounds& b = bounds.corner_bounds[q++];
    for (int i = 0; i < 4; ++i)
      if (sines[i] <= b.min_sine[i] + margin) {
        faces.push_back(f.idx());
        break;
      }
  }
  for (const auto& [face, min_sine] : bounds.polygon_corner_bounds) {
    std::vector<Eigen::Vector3d> p;
    for (auto fv : mesh.fv_range(mesh.face_handle(face))) p.push_back(ToEigen(mesh.point(fv)));
    std::vector<const double*> v;
    for (const Eigen::Vector3d& q : p) v.push_back(q.data());
    std::vector<double> sines(p.size());
    PolygonCornerSines(v.data(), static_cast<int>(p.size()), sines.data());
    for (size_t i = 0; i < sines.size(); ++i)
      if (sines[i] <= min_sine[i] + margin) {
        faces.push_back(face);
        break;
      }
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

std::vector<std::array<int, 2>> EdgesAtLengthBound(const PolyMesh& input, const PolyMesh& mesh,
                                                   const PanelBounds& bounds, double margin) {
  std::vector<std::array<int, 2>> edges;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const auto a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
    const Eigen::Vector3d edge = ToEigen(mesh.point(b)) - ToEigen(mesh.point(a));
    const Eigen::Vector3d before = ToEigen(input.point(b)) - ToEigen(input.point(a));
    const size_t i = e.idx();
    const bool at_min = i < bounds.min_edge.size() && before.norm() > 0.0 &&
                        edge.dot(before.normalized()) <= bounds.min_edge[i] * (1.0 + margin);
    const bool at_max =
        i < bounds.max_edge.size() && edge.norm() >= bounds.max_edge[i] * (1.0 - margin);
    if (at_min || at_max) edges.push_back({a.idx(), b.idx()});
  }
  return edges;
}

std::string EdgeList(const std::vector<std::array<int, 2>>& edges, int shown) {
  std::string out = "vertices ";
  for (int i = 0; i < static_cast<int>(edges.size()) && i < shown; ++i)
    out += (i > 0 ? ", " : "") + std::to_string(edges[i][0]) + "-" + std::to_string(edges[i][1]);
  if (static_cast<int>(edges.size()) > shown)
    out += " (and " + std::to_string(edges.size() - shown) + " more)";
  return out;
}

NamedValues ShapeValues(const QuadShapeSummary& s) {
  return {{"non_convex_quads", static_cast<double>(s.non_convex)},
          {"min_corner_angle_deg", s.min_angle_deg},
          {"max_kink_deg", s.max_kink_deg},
          {"max_planarity_abs", s.max_diagonal_distance}};
}

nlohmann::json ColourScaleJson(const ColourScale& scale) {
  return {{"measure", scale.measure},
          {"scale", scale.logarithmic ? "log10" : "linear"},
          {"min", scale.min},
          {"max", scale.max},
          {"colours", "blue (min), yellow, red (max)"}};
}

nlohmann::json ShapeChangeJson(const ShapeChange& change) {
  return {{"threshold_deg", change.threshold_deg},
          {"quads_changed", change.quads_changed},
          {"share_changed", change.share_changed},
          {"max_corner_change_deg", change.max_corner_change_deg}};
}

std::string FaceList(const std::vector<int>& faces, int shown) {
  std::string text = faces.size() == 1 ? "face " : "faces ";
  for (size_t i = 0; i < faces.size() && i < static_cast<size_t>(shown); ++i)
    text += (i > 0 ? ", " : "") + std::to_string(faces[i]);
  if (faces.size() > static_cast<size_t>(shown))
    text += " (and " + std::to_string(faces.size() - shown) + " more)";
  return text;
}

}  // namespace gproj
