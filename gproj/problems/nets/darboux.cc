#include "gproj/problems/nets/darboux.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gproj/common/input_error.h"
#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/nets/hnet.h"

namespace gproj::nets {
namespace {

Eigen::Vector3d P(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  const auto& p = mesh.point(v);
  return {p[0], p[1], p[2]};
}

// A bounding box: its centre and diagonal.
struct Box {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double diagonal = 0.0;
};
Box BoxOf(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) return {};
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Eigen::Vector3d& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {0.5 * (lo + hi), (hi - lo).norm()};
}
Box BoxOf(const PolyMesh& mesh) {
  std::vector<Eigen::Vector3d> points;
  for (auto v : mesh.vertices()) points.push_back(P(mesh, v));
  return BoxOf(points);
}

// The patch in the frame where the box's centre is the origin and its diagonal 1: measured
// there, nothing overflows or underflows at any scale of the input.
RationalBezierPatch InUnitFrame(const RationalBezierPatch& patch, const Box& box) {
  RationalBezierPatch out = patch;
  for (Eigen::Vector4d& h : out.control)
    h.head<3>() = (h.head<3>() - box.centre * h[3]) / box.diagonal;
  return out;
}
std::vector<RationalBezierPatch> InUnitFrame(const std::vector<RationalBezierPatch>& patches,
                                             const Box& box) {
  std::vector<RationalBezierPatch> out;
  for (const RationalBezierPatch& p : patches) out.push_back(InUnitFrame(p, box));
  return out;
}

std::string Xyz(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return text;
}

// The corner of face f at vertex v.
int CornerOf(const PolyMesh& mesh, PolyMesh::FaceHandle f, int v) {
  int k = 0;
  for (auto fv : mesh.fv_range(f)) {
    if (fv.idx() == v) return k;
    ++k;
  }
  return -1;
}

Eigen::Vector3d UnitNormal(const RationalBezierPatch& patch, const Eigen::Vector2d& uv) {
  const PatchJet jet = EvaluateJet(patch, uv.x(), uv.y());
  return jet.du.cross(jet.dv).normalized();
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::asin(std::min(1.0, a.cross(b).norm())) * 180.0 / M_PI;
}

// Projects p onto the patch from (u, v): Gauss–Newton on |x(u, v) − p|², kept in [0, 1]².
NearestPatchPoint Refine(const RationalBezierPatch& patch, const Eigen::Vector3d& p, double u,
                         double v) {
  for (int it = 0; it < 30; ++it) {
    const PatchJet jet = EvaluateJet(patch, u, v);
    const Eigen::Vector3d r = jet.point - p;
    Eigen::Matrix2d a;
    a << jet.du.dot(jet.du), jet.du.dot(jet.dv), jet.du.dot(jet.dv), jet.dv.dot(jet.dv);
    const Eigen::Vector2d g(jet.du.dot(r), jet.dv.dot(r));
    const Eigen::Vector2d step = a.ldlt().solve(-g);
    if (!step.allFinite()) break;
    const double nu = std::clamp(u + step.x(), 0.0, 1.0), nv = std::clamp(v + step.y(), 0.0, 1.0);
    if (std::abs(nu - u) + std::abs(nv - v) < 1e-15) break;
    if ((EvaluatePoint(patch, nu, nv) - p).norm() > r.norm()) break;
    u = nu, v = nv;
  }
  NearestPatchPoint out;
  out.distance = (EvaluatePoint(patch, u, v) - p).norm();
  out.u = u, out.v = v;
  return out;
}

}  // namespace

Eigen::Vector3d Inversion::Apply(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = (p - centre) / radius;
  return centre + radius * d / d.squaredNorm();
}

RationalBezierPatch HNetPatch(const PolyMesh& mesh, PolyMesh::FaceHandle f,
                              const std::array<double, 4>& weights) {
  RationalBezierPatch patch(1, 1);
  const int place[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  int k = 0;
  for (auto fv : mesh.fv_range(f)) {
    if (k == 4) break;
    const double w = weights[k];
    patch.At(place[k][0], place[k][1]) << w * P(mesh, fv), w;
    ++k;
  }
  return patch;
}

RationalBezierPatch InvertPatch(const RationalBezierPatch& patch, const Inversion& inversion) {
  const int m = patch.degree_u, n = patch.degree_v;
  const std::size_t count = patch.control.size();
  std::vector<double> w(count);
  std::array<std::vector<double>, 3> q;
  for (auto& c : q) c.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const Eigen::Vector4d& h = patch.control[k];
    w[k] = h[3];
    for (int c = 0; c < 3; ++c) q[c][k] = (h[c] - inversion.centre[c] * h[3]) / inversion.radius;
  }
  std::vector<double> d;
  std::array<std::vector<double>, 3> num;
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> square = MultiplyBernstein(q[c], m, n, q[c], m, n);
    if (d.empty())
      d = square;
    else
      for (std::size_t k = 0; k < d.size(); ++k) d[k] += square[k];
    num[c] = MultiplyBernstein(w, m, n, q[c], m, n);
  }
  RationalBezierPatch image(2 * m, 2 * n);
  for (std::size_t k = 0; k < d.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      image.control[k][c] = inversion.centre[c] * d[k] + inversion.radius * num[c][k];
      image.control[k][3] = d[k];
    }
  return image;
}

NearestPatchPoint FindNearestPatchPoint(const std::vector<RationalBezierPatch>& patches,
                                        const Eigen::Vector3d& p) {
  constexpr int kGrid = 16;
  std::vector<NearestPatchPoint> best(patches.size());
  double global = INFINITY;
  for (std::size_t f = 0; f < patches.size(); ++f) {
    best[f].distance = INFINITY;
    best[f].face = static_cast<int>(f);
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; j <= kGrid; ++j) {
        const double u = static_cast<double>(i) / kGrid, v = static_cast<double>(j) / kGrid;
        const double distance = (EvaluatePoint(patches[f], u, v) - p).norm();
        if (distance < best[f].distance) best[f].distance = distance, best[f].u = u, best[f].v = v;
      }
    global = std::min(global, best[f].distance);
  }
  NearestPatchPoint nearest;
  nearest.distance = INFINITY;
  for (std::size_t f = 0; f < patches.size(); ++f) {
    if (best[f].distance > 2.0 * global) continue;
    NearestPatchPoint refined = Refine(patches[f], p, best[f].u, best[f].v);
    refined.face = static_cast<int>(f);
    if (refined.distance < nearest.distance) nearest = refined;
  }
  return nearest;
}

Inversion DefaultInversion(const PolyMesh& mesh) {
  const Box box = BoxOf(mesh);
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> c;
    for (auto fv : mesh.fv_range(f)) c.push_back(P(mesh, fv));
    if (c.size() == 4) normal += 0.5 * (c[2] - c[0]).cross(c[3] - c[1]);
  }
  if (!(normal.norm() > 1e-9 * box.diagonal * box.diagonal)) normal = Eigen::Vector3d::UnitZ();
  Inversion inversion;
  inversion.centre = box.centre + 0.5 * box.diagonal * normal.normalized();
  inversion.radius = 0.5 * box.diagonal;
  return inversion;
}

Inversion InversionAbout(const PolyMesh& mesh, const Eigen::Vector3d& centre) {
  Inversion inversion;
  inversion.centre = centre;
  inversion.radius = (centre - BoxOf(mesh).centre).norm();
  return inversion;
}

DarbouxSkin MakeDarbouxSkin(const HNetPatchwork& hnet, const Inversion& inversion) {
  const Box box = BoxOf(hnet.mesh);
  const double diagonal = box.diagonal;
  char text[512];
  if (!(diagonal > 0.0) || !std::isfinite(diagonal))
    throw InputError("the H-net has no extent (its bounding-box diagonal is " +
                     std::to_string(diagonal) + ")");
  if (!inversion.centre.allFinite()) throw InputError("`centre`: must be finite");
  if (!((inversion.centre - box.centre).norm() <= kMaxCentreDistance * diagonal)) {
    std::snprintf(text, sizeof(text),
                  "`centre`: %s is %.3g H-net diagonals from the H-net; at most %g (farther, the "
                  "inversion is nearly a similarity and the skin loses precision)",
                  Xyz(inversion.centre).c_str(), (inversion.centre - box.centre).norm() / diagonal,
                  kMaxCentreDistance);
    throw InputError(text);
  }
  if (!(inversion.radius >= kRadiusRange[0] * diagonal &&
        inversion.radius <= kRadiusRange[1] * diagonal)) {
    std::snprintf(text, sizeof(text),
                  "`radius`: %g is %.3g of the H-net's diagonal (%g); it must be within %g … %g "
                  "of it",
                  inversion.radius, inversion.radius / diagonal, diagonal, kRadiusRange[0],
                  kRadiusRange[1]);
    throw InputError(text);
  }
  DarbouxSkin skin;
  skin.inversion = inversion;
  for (auto f : hnet.mesh.faces())
    skin.hnet_patches.push_back(HNetPatch(hnet.mesh, f, hnet.weights[f.idx()]));
  skin.nearest = FindNearestPatchPoint(InUnitFrame(skin.hnet_patches, box),
                                       (inversion.centre - box.centre) / diagonal);
  skin.nearest.distance *= diagonal;
  if (!(skin.nearest.distance >= kMinCentreDistance * diagonal)) {
    std::snprintf(text, sizeof(text),
                  "`centre`: %s lies %.3g of the H-net's diagonal from patch %d (at u %.3f, v "
                  "%.3f); the inversion sends the surface at its centre to infinity, so the "
                  "skin would be unbounded: choose a centre at least %g of the diagonal (%.6g) "
                  "off the surface",
                  Xyz(inversion.centre).c_str(), skin.nearest.distance / diagonal,
                  skin.nearest.face, skin.nearest.u, skin.nearest.v, kMinCentreDistance,
                  kMinCentreDistance * diagonal);
    throw InputError(text);
  }
  for (std::size_t f = 0; f < skin.hnet_patches.size(); ++f) {
    skin.patches.push_back(InvertPatch(skin.hnet_patches[f], inversion));
    for (const Eigen::Vector4d& h : skin.patches.back().control)
      if (!h.allFinite())
        throw InputError("the image of patch " + std::to_string(f) +
                         " has control points that are not finite: the H-net's coordinates are "
                         "too large for its inversion");
  }
  return skin;
}

DarbouxMeasures MeasureDarbouxSkin(const HNetPatchwork& hnet, const DarbouxSkin& skin,
                                   int samples) {
  DarbouxMeasures m;
  const PolyMesh& mesh = hnet.mesh;
  const int s = std::max(samples, 2);
  // Everything measured in the H-net's unit frame (scale-free measures; K × diagonal²).
  const Box box = BoxOf(mesh);
  const std::vector<RationalBezierPatch> patches = InUnitFrame(skin.patches, box);
  const std::vector<RationalBezierPatch> hnet_patches = InUnitFrame(skin.hnet_patches, box);
  Inversion inversion;
  inversion.centre = (skin.inversion.centre - box.centre) / box.diagonal;
  inversion.radius = skin.inversion.radius / box.diagonal;
  std::vector<Eigen::Vector3d> skin_points;
  for (const RationalBezierPatch& patch : patches)
    for (int i = 0; i <= s; ++i)
      for (int j = 0; j <= s; ++j)
        skin_points.push_back(
            EvaluatePoint(patch, static_cast<double>(i) / s, static_cast<double>(j) / s));
  const double unit_skin_diagonal = BoxOf(skin_points).diagonal;
  m.hnet_diagonal = box.diagonal;
  m.skin_diagonal = unit_skin_diagonal * box.diagonal;
  m.centre_distance = skin.nearest.distance / box.diagonal;

  // Tangent planes along the inner edges, at the same points of the straight edge from both
  // patches.
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    const auto f = mesh.face_handle(h), g = mesh.face_handle(mesh.opposite_halfedge_handle(h));
    const int kf = CornerOf(mesh, f, a), kg = CornerOf(mesh, g, b);
    const auto& wf = hnet.weights[f.idx()];
    const auto& wg = hnet.weights[g.idx()];
    for (int k = 0; k <= s; ++k) {
      const double frac = static_cast<double>(k) / s;
      const Eigen::Vector2d uf = PatchEdgeUv(kf, EdgeParameterAt(frac, wf[kf], wf[(kf + 1) % 4]));
      const Eigen::Vector2d ug =
          PatchEdgeUv(kg, EdgeParameterAt(1.0 - frac, wg[kg], wg[(kg + 1) % 4]));
      const double before =
          AngleDeg(UnitNormal(hnet_patches[f.idx()], uf), UnitNormal(hnet_patches[g.idx()], ug));
      const double after =
          AngleDeg(UnitNormal(patches[f.idx()], uf), UnitNormal(patches[g.idx()], ug));
      m.hnet_max_tangent_angle_deg = std::max(m.hnet_max_tangent_angle_deg, before);
      m.max_tangent_angle_deg = std::max(m.max_tangent_angle_deg, after);
      m.max_tangent_angle_change_deg =
          std::max(m.max_tangent_angle_change_deg, std::abs(after - before));
    }
  }

  // The images of the rulings: circles through the centre.
  for (const RationalBezierPatch& patch : patches)
    for (int family = 0; family < 2; ++family)
      for (int r = 0; r <= 4; ++r) {
        const double fixed = r / 4.0;
        std::vector<Eigen::Vector3d> points;
        for (int k = 0; k <= s; ++k) {
          const double t = static_cast<double>(k) / s;
          points.push_back(family == 0 ? EvaluatePoint(patch, fixed, t)
                                       : EvaluatePoint(patch, t, fixed));
        }
        const Circle circle = CircleThrough(points.front(), points[s / 2], points.back());
        for (const Eigen::Vector3d& p : points)
          m.max_circle_deviation =
              std::max(m.max_circle_deviation, DistanceToCircle(p, circle) / unit_skin_diagonal);
        m.max_centre_off_circle =
            std::max(m.max_centre_off_circle,
                     DistanceToCircle(inversion.centre, circle) / unit_skin_diagonal);
        ++m.rulings;
      }

  // Gaussian curvature at the cell centres, against the inversion's formula.
  const double scale = unit_skin_diagonal * unit_skin_diagonal;
  const double r2 = inversion.radius * inversion.radius;
  m.skin_min_k = INFINITY, m.skin_max_k = -INFINITY;
  for (std::size_t f = 0; f < patches.size(); ++f)
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j) {
        const double u = (i + 0.5) / s, v = (j + 0.5) / s;
        const PatchJet before = EvaluateJet(hnet_patches[f], u, v);
        const PatchCurvature kb = CurvatureOf(before);
        const PatchCurvature ka = CurvatureOf(EvaluateJet(patches[f], u, v));
        const Eigen::Vector3d d = before.point - inversion.centre;
        const double a = d.squaredNorm() / r2, b = 2.0 * d.dot(kb.normal) / r2;
        const double predicted = a * a * kb.gaussian + 2.0 * a * b * kb.mean + b * b;
        m.max_curvature_formula_error = std::max(
            m.max_curvature_formula_error,
            std::abs(ka.gaussian - predicted) / std::max(std::abs(ka.gaussian), 1.0 / scale));
        ++m.curvature_samples;
        const double k_scaled = ka.gaussian * scale;
        m.skin_min_k = std::min(m.skin_min_k, k_scaled);
        m.skin_max_k = std::max(m.skin_max_k, k_scaled);
        if (k_scaled > 1e-9) ++m.skin_k_positive;
        if (k_scaled < -1e-9) ++m.skin_k_negative;
        const double hnet_scaled = kb.gaussian;  // the H-net's diagonal is 1 here
        if (hnet_scaled > 1e-9) ++m.hnet_k_positive;
        if (hnet_scaled < -1e-9) ++m.hnet_k_negative;
      }
  for (const RationalBezierPatch& patch : patches)
    if (std::any_of(patch.control.begin(), patch.control.end(),
                    [](const Eigen::Vector4d& h) { return !(h[3] > 0.0); }))
      ++m.patches_with_nonpositive_weights;
  return m;
}

nlohmann::json DarbouxSkinJson(const HNetPatchwork& hnet, const DarbouxSkin& skin) {
  nlohmann::json patches = nlohmann::json::array();
  for (std::size_t f = 0; f < skin.patches.size(); ++f) {
    const RationalBezierPatch& patch = skin.patches[f];
    nlohmann::json homogeneous = nlohmann::json::array(), points = nlohmann::json::array(),
                   weights = nlohmann::json::array();
    bool positive = true;
    for (int i = 0; i <= patch.degree_u; ++i) {
      nlohmann::json hrow = nlohmann::json::array(), prow = nlohmann::json::array(),
                     wrow = nlohmann::json::array();
      for (int j = 0; j <= patch.degree_v; ++j) {
        const Eigen::Vector4d& h = patch.At(i, j);
        hrow.push_back({h[0], h[1], h[2], h[3]});
        positive = positive && h[3] > 0.0;
        if (h[3] > 0.0) prow.push_back({h[0] / h[3], h[1] / h[3], h[2] / h[3]});
        wrow.push_back(h[3]);
      }
      homogeneous.push_back(hrow);
      points.push_back(prow);
      weights.push_back(wrow);
    }
    nlohmann::json entry = {{"face", f},
                            {"degree", {patch.degree_u, patch.degree_v}},
                            {"homogeneous_control_points", homogeneous}};
    if (positive) {
      entry["control_points"] = points;
      entry["weights"] = weights;
    }
    patches.push_back(entry);
  }
  const Eigen::Vector3d& c = skin.inversion.centre;
  return {{"inversion", {{"centre", {c.x(), c.y(), c.z()}}, {"radius", skin.inversion.radius}}},
          {"patches", patches},
          {"hnet", [&hnet] {
             nlohmann::json source = HNetJson(hnet.mesh, hnet.weights);
             source.update(hnet.extra);
             return source;
           }()}};
}

PolyMesh SampleDarbouxSkin(const HNetPatchwork& hnet, const DarbouxSkin& skin, int samples) {
  PolyMesh out = SampleHNetSurface(hnet.mesh, hnet.weights, samples);
  for (auto v : out.vertices()) {
    const Eigen::Vector3d p = skin.inversion.Apply(P(out, v));
    out.set_point(v, PolyMesh::Point(p.x(), p.y(), p.z()));
  }
  return out;
}

std::string DarbouxSkinSvg(const DarbouxSkin& skin, const std::string& title, int samples) {
  PolyMesh picture;
  SvgOptions svg;
  svg.title = title;
  svg.legend = "orange: K > 0, blue: K < 0 (Gaussian curvature of the skin)";
  // At most about 20,000 triangles: a picture a browser opens at once.
  const int fit = static_cast<int>(std::sqrt(1e4 / std::max<std::size_t>(skin.patches.size(), 1)));
  const int s = std::clamp(std::min(samples, fit), 1, 6);
  for (const RationalBezierPatch& patch : skin.patches) {
    std::vector<PolyMesh::VertexHandle> grid;
    for (int i = 0; i <= s; ++i)
      for (int j = 0; j <= s; ++j) {
        const Eigen::Vector3d p =
            EvaluatePoint(patch, static_cast<double>(i) / s, static_cast<double>(j) / s);
        grid.push_back(picture.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z())));
      }
    for (int i = 0; i < s; ++i)
      for (int j = 0; j < s; ++j) {
        const double k = CurvatureOf(EvaluateJet(patch, (i + 0.5) / s, (j + 0.5) / s)).gaussian;
        const std::array<std::uint8_t, 3> colour = k > 0.0
                                                       ? std::array<std::uint8_t, 3>{230, 140, 60}
                                                       : std::array<std::uint8_t, 3>{90, 135, 205};
        const auto at = [&](int a, int b) { return grid[a * (s + 1) + b]; };
        picture.add_face({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        picture.add_face({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        svg.face_colours.push_back(colour);
        svg.face_colours.push_back(colour);
      }
  }
  return RenderMeshSvg(picture, svg);
}

}  // namespace gproj::nets
