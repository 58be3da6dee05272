#include "gproj/problems/mesh/vertex_control.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <memory>

#include "gproj/constraints/surface_closeness.h"
#include "gproj/geometry/io/text_input.h"

namespace gproj {

bool VertexControlOptions::IsValid(std::string* why) const {
  if (fix_boundary && glide_boundary) {
    *why = "the boundary cannot be both fixed and gliding";
    return false;
  }
  return true;
}

std::vector<int> ReadVertexIds(const std::string& path, int num_vertices) {
  std::vector<int> ids;
  for (const TextLine& line : ReadTextLines(path))
    for (const std::string& word : line.words)
      ids.push_back(ParseIndex(word, TextPlace(path, line.number), num_vertices, "vertex"));
  return ids;
}

std::vector<std::vector<int>> BoundaryLoops(const PolyMesh& mesh) {
  std::vector<std::vector<int>> loops;
  std::vector<bool> seen(mesh.n_halfedges(), false);
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[h.idx()]) continue;
    std::vector<int> loop;
    for (auto g = h; !seen[g.idx()]; g = mesh.next_halfedge_handle(g)) {
      seen[g.idx()] = true;
      loop.push_back(mesh.from_vertex_handle(g).idx());
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

bool IsBoundaryCorner(const PolyMesh& mesh, int previous, int v, int next) {
  const auto vh = mesh.vertex_handle(v);
  int faces = 0;
  for (auto f = mesh.cvf_begin(vh); f.is_valid(); ++f) ++faces;
  if (faces <= 1) return true;
  const Eigen::Vector3d p = ToEigen(mesh.point(vh));
  const Eigen::Vector3d in = p - ToEigen(mesh.point(mesh.vertex_handle(previous)));
  const Eigen::Vector3d out = ToEigen(mesh.point(mesh.vertex_handle(next))) - p;
  const double turn = std::atan2(in.cross(out).norm(), in.dot(out));
  return turn > kBoundaryCornerTurnDeg * M_PI / 180.0;
}

std::vector<std::vector<int>> SplitAtCorners(const PolyMesh& mesh, const std::vector<int>& loop) {
  const int m = static_cast<int>(loop.size());
  std::vector<int> corners;
  for (int i = 0; i < m; ++i)
    if (IsBoundaryCorner(mesh, loop[(i + m - 1) % m], loop[i], loop[(i + 1) % m]))
      corners.push_back(i);
  std::vector<std::vector<int>> paths;
  if (corners.empty()) {
    paths.push_back(loop);
    paths.back().push_back(loop.front());
    return paths;
  }
  for (size_t c = 0; c < corners.size(); ++c) {
    const int begin = corners[c];
    const int end = c + 1 < corners.size() ? corners[c + 1] : corners.front() + m;
    std::vector<int> path;
    for (int i = begin; i <= end; ++i) path.push_back(loop[i % m]);
    paths.push_back(std::move(path));
  }
  return paths;
}

VertexControl ApplyVertexControl(const PolyMesh& mesh, const MeshNormalization& norm,
                                 int vertex_block, const VertexControlOptions& options,
                                 Problem* problem) {
  VertexControl out;
  out.scale = norm.scale;
  Eigen::AlignedBox3d box;
  for (auto v : mesh.vertices()) box.extend(ToEigen(mesh.point(v)));
  out.bbox_diagonal = std::max(box.diagonal().norm(), 1e-300);
  const int n = static_cast<int>(mesh.n_vertices());
  std::vector<bool> held(n, false);
  for (int v : options.fixed) {
    if (v < 0 || v >= n)
      throw InputError("fixed vertex " + std::to_string(v) + " is out of range (the mesh has " +
                       std::to_string(n) + " vertices)");
    held[v] = true;
  }
  if (options.fix_boundary)
    for (auto v : mesh.vertices())
      if (mesh.is_boundary(v)) held[v.idx()] = true;
  std::vector<std::vector<int>> glide_paths;
  if (options.glide_boundary)
    for (const std::vector<int>& loop : BoundaryLoops(mesh))
      for (std::vector<int>& path : SplitAtCorners(mesh, loop)) {
        // A corner ends two paths and is held: gliding around it is not sliding along the
        // boundary, and its tangent is that of neither side.
        if (path.front() != path.back()) held[path.front()] = held[path.back()] = true;
        glide_paths.push_back(std::move(path));
      }
  const BlockItems vertex(problem->layout(), vertex_block);
  for (int v = 0; v < n; ++v)
    if (held[v]) {
      out.held.push_back(v);
      problem->SetConstant(vertex[v]);
    }
  if (options.glide_boundary) {
    out.glide = problem->AddFamily<PolylineGliding>(1.0, "boundary_gliding");
    for (const std::vector<int>& path : glide_paths) {
      std::vector<Eigen::Vector3d> points;
      for (int v : path)
        points.push_back(norm.ToProblem(ToEigen(mesh.point(mesh.vertex_handle(v)))));
      const int id = out.glide->AddPolyline(std::move(points));
      for (int v : path)
        if (!held[v]) out.glide->AddPoint(vertex[v], id);
    }
  }
  return out;
}

void VertexControl::RestoreHeld(const PolyMesh& input, PolyMesh* mesh) const {
  for (int v : held) {
    const auto given = moved.find(v);
    mesh->set_point(mesh->vertex_handle(v),
                    given != moved.end() ? given->second : input.point(input.vertex_handle(v)));
  }
}

double VertexControl::MaxGlideDistance(const VariableLayout& layout,
                                       const Eigen::VectorXd& x) const {
  if (glide == nullptr) return 0.0;
  double worst = 0.0;
  for (int e = 0; e < glide->num_elements(); ++e)
    worst = std::max(worst, glide->DistanceToPolyline(e, layout, x));
  return worst / scale / bbox_diagonal;
}

void AddReferenceCloseness(const PolyMesh& reference, const MeshNormalization& norm,
                           int vertex_block, int num_vertices, double tangent_weight,
                           double point_weight, Problem* problem) {
  // The query works in the problem's units (mean edge 1), so its squared distances stay finite
  // at any input scale; the rows' projector owns it.
  PolyMesh moved = reference;
  for (auto v : moved.vertices()) {
    const Eigen::Vector3d p = norm.ToProblem(ToEigen(moved.point(v)));
    moved.set_point(v, PolyMesh::Point(p.x(), p.y(), p.z()));
  }
  const auto query = std::make_shared<const ClosestPointQuery>(moved);
  const SurfaceProjector projector = [query](const Eigen::Vector3d& q, Eigen::Vector3d* p,
                                             Eigen::Vector3d* n) { query->Project(q, p, n); };
  const BlockItems vertex(problem->layout(), vertex_block);
  if (tangent_weight > 0.0) {
    auto* tangent = problem->AddFamily<SurfaceTangentCloseness>(projector, tangent_weight);
    for (int v = 0; v < num_vertices; ++v) tangent->AddPoint(vertex[v]);
  }
  if (point_weight > 0.0) {
    auto* point = problem->AddFamily<SurfacePointCloseness>(projector, point_weight);
    for (int v = 0; v < num_vertices; ++v) point->AddPoint(vertex[v]);
  }
}

}  // namespace gproj
