#include "gproj/geometry/render/svg_render.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "gproj/geometry/render/svg_plot.h"

namespace gproj {

std::string RenderMeshSvg(const PolyMesh& mesh, const SvgOptions& options) {
  if (mesh.n_faces() == 0) throw InputError("nothing to draw: the mesh has no faces");
  // Camera frame: w towards the viewer, u right, v up (z up in the scene).
  const Eigen::Vector3d w = options.view.normalized();
  Eigen::Vector3d u = Eigen::Vector3d::UnitZ().cross(w);
  if (u.norm() < 1e-9) u = Eigen::Vector3d::UnitX();
  u.normalize();
  const Eigen::Vector3d v = w.cross(u);
  const Eigen::Vector3d light = options.light.normalized();

  struct Face {
    double depth;
    std::vector<Eigen::Vector2d> points;
    double shade;
    int index;
  };
  std::vector<Face> faces;
  Eigen::AlignedBox2d box;
  for (auto f : mesh.faces()) {
    Face face{0.0, {}, 0.0, f.idx()};
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
    face.depth = centre.dot(w);
    for (const auto& q : p) {
      face.points.emplace_back(q.dot(u), -q.dot(v));
      box.extend(face.points.back());
    }
    faces.push_back(std::move(face));
  }
  std::sort(faces.begin(), faces.end(),
            [](const Face& a, const Face& b) { return a.depth < b.depth; });
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
  auto to_picture = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(margin + (p.dot(u) - box.min().x()) * scale,
                           top + margin + (-p.dot(v) - box.min().y()) * scale);
  };
  for (const Face& face : faces) {
    svg += "<polygon points=\"";
    for (const auto& q : face.points) {
      std::snprintf(buffer, sizeof(buffer), "%.1f,%.1f ", margin + (q.x() - box.min().x()) * scale,
                    top + margin + (q.y() - box.min().y()) * scale);
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
    svg += buffer;
  }
  for (const auto& [a, b] : options.segments) {
    if (!a.allFinite() || !b.allFinite()) continue;
    const Eigen::Vector2d p = to_picture(a), q = to_picture(b);
    std::snprintf(buffer, sizeof(buffer),
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"", p.x(), p.y(),
                  q.x(), q.y());
    svg += buffer + options.segment_colour + "\" stroke-width=\"0.8\"/>\n";
  }
  for (const Eigen::Vector3d& d : options.dots) {
    if (!d.allFinite()) continue;
    const Eigen::Vector2d p = to_picture(d);
    std::snprintf(buffer, sizeof(buffer), "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"", p.x(),
                  p.y());
    svg += buffer + options.dot_colour + "\"/>\n";
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace gproj
