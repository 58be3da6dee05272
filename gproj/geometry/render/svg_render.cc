#include "gproj/geometry/render/svg_render.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "gproj/geometry/render/svg_plot.h"

namespace gproj {

namespace {

// The camera: w towards the viewer, u right, v up (z up in the scene).
struct Camera {
  Eigen::Vector3d u, v, w;
  explicit Camera(const Eigen::Vector3d& view) : w(view.normalized()) {
    u = Eigen::Vector3d::UnitZ().cross(w);
    if (u.norm() < 1e-9) u = Eigen::Vector3d::UnitX();
    u.normalize();
    v = w.cross(u);
  }
  // The point in the plane of the view (y down).
  Eigen::Vector2d Project(const Eigen::Vector3d& p) const { return {p.dot(u), -p.dot(v)}; }
};

struct ProjectedFace {
  double depth;
  std::vector<Eigen::Vector2d> points;
  double shade;
  int index;
};

// Every face projected and shaded (two-sided Lambert), far to near; `box` gets their extent.
// Throws InputError for a vertex that is not finite.
std::vector<ProjectedFace> ProjectFaces(const PolyMesh& mesh, const Camera& camera,
                                        const Eigen::Vector3d& light, Eigen::AlignedBox2d* box) {
  std::vector<ProjectedFace> faces;
  for (auto f : mesh.faces()) {
    ProjectedFace face{0.0, {}, 0.0, f.idx()};
    std::vector<Eigen::Vector3d> p;
    for (auto fv : mesh.fv_range(f)) {
      const auto& q = mesh.point(fv);
      p.emplace_back(q[0], q[1], q[2]);
      if (!p.back().allFinite()) throw InputError("nothing to draw: a vertex is not finite");
    }
    Eigen::Vector3d normal = Eigen::Vector3d::Zero(), centre = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < p.size(); ++k) {
      normal += p[k].cross(p[(k + 1) % p.size()]);
      centre += p[k] / static_cast<double>(p.size());
    }
    if (normal.norm() > 0) normal.normalize();
    face.shade = 0.25 + 0.75 * std::abs(normal.dot(light));  // two-sided
    face.depth = centre.dot(camera.w);
    for (const auto& q : p) {
      face.points.push_back(camera.Project(q));
      box->extend(face.points.back());
    }
    faces.push_back(std::move(face));
  }
  std::sort(faces.begin(), faces.end(),
            [](const ProjectedFace& a, const ProjectedFace& b) { return a.depth < b.depth; });
  return faces;
}

// The polygon of a face, grey-blue or its colour from `options`, shaded.
std::string FacePolygon(const ProjectedFace& face, const SvgOptions& options,
                        const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& to_picture) {
  std::string svg = "<polygon points=\"";
  char buffer[160];
  for (const auto& q : face.points) {
    const Eigen::Vector2d p = to_picture(q);
    std::snprintf(buffer, sizeof(buffer), "%.1f,%.1f ", p.x(), p.y());
    svg += buffer;
  }
  const int g = static_cast<int>(std::lround(255 * face.shade));
  int rgb[3] = {g * 7 / 10, g * 8 / 10, g};
  if (!options.face_colours.empty()) {
    const auto& c = options.face_colours.at(face.index);
    // Shade the face's colour, keeping it recognisable: 0.55 + 0.45 × the Lambert term.
    const double s = 0.55 + 0.45 * (face.shade - 0.25) / 0.75;
    for (int k = 0; k < 3; ++k) rgb[k] = static_cast<int>(std::lround(c[k] * s));
  }
  std::snprintf(buffer, sizeof(buffer),
                "\" fill=\"rgb(%d,%d,%d)\" stroke=\"rgb(%d,%d,%d)\" stroke-width=\"0.3\"/>\n",
                rgb[0], rgb[1], rgb[2], g / 2, g / 2, g / 2);
  return svg + buffer;
}

// The segments and dots of `options` (those that are finite).
std::string Overlays(const SvgOptions& options,
                     const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& to_picture,
                     const Camera& camera) {
  std::string svg;
  char buffer[160];
  for (const auto& [a, b] : options.segments) {
    if (!a.allFinite() || !b.allFinite()) continue;
    const Eigen::Vector2d p = to_picture(camera.Project(a)), q = to_picture(camera.Project(b));
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"", p.x(), p.y(),
                  q.x(), q.y());
    svg += buffer + options.segment_colour + "\" stroke-width=\"0.8\"/>\n";
  }
  for (const Eigen::Vector3d& d : options.dots) {
    if (!d.allFinite()) continue;
    const Eigen::Vector2d p = to_picture(camera.Project(d));
    std::snprintf(buffer, sizeof(buffer), "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"", p.x(),
                  p.y());
    svg += buffer + options.dot_colour + "\"/>\n";
  }
  return svg;
}

}  // namespace

std::string RenderMeshSvg(const PolyMesh& mesh, const SvgOptions& options) {
  if (mesh.n_faces() == 0) throw InputError("nothing to draw: the mesh has no faces");
  const Camera camera(options.view);
  Eigen::AlignedBox2d box;
  const std::vector<ProjectedFace> faces =
      ProjectFaces(mesh, camera, options.light.normalized(), &box);
  const double margin = 20.0;
  const double scale = (options.width - 2 * margin) / std::max(box.sizes().x(), 1e-300);
  const int top = options.legend.empty() ? 30 : 50;
  const int height = static_cast<int>(std::ceil(box.sizes().y() * scale + 2 * margin)) + top;
  std::string svg;
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer),
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                options.width, height);
  svg += buffer;
  if (!options.title.empty())
    svg += "<text x=\"20\" y=\"22\" font-family=\"sans-serif\" font-size=\"15\">" +
           EscapeXml(options.title) + "</text>\n";
  if (!options.legend.empty())
    svg += "<text x=\"20\" y=\"42\" font-family=\"sans-serif\" font-size=\"13\">" +
           EscapeXml(options.legend) + "</text>\n";
  const auto to_picture = [&](const Eigen::Vector2d& q) {
    return Eigen::Vector2d(margin + (q.x() - box.min().x()) * scale,
                           top + margin + (q.y() - box.min().y()) * scale);
  };
  for (const ProjectedFace& face : faces) svg += FacePolygon(face, options, to_picture);
  svg += Overlays(options, to_picture, camera);
  svg += "</svg>\n";
  return svg;
}

}  // namespace gproj
