#include "problems/marionette_inputs.h"

#include "geometry/text_input.h"

namespace gproj {

namespace {

// A guide file's lines; `path` names it in messages.
MarionetteGuideFile GuidesFromLines(const std::vector<TextLine>& lines, const std::string& path,
                                    int num_vertices) {
  MarionetteGuideFile file;
  for (const TextLine& line : lines) {
    const std::string where = TextPlace(path, line.number);
    const std::vector<std::string>& w = line.words;
    if (w[0] == "guide" && w.size() >= 5) {
      MarionetteGuide g;
      g.where = where;
      g.start = ParseIndex(w[1], where, num_vertices, "vertex");
      g.next = ParseIndex(w[2], where, num_vertices, "vertex");
      for (size_t k = 3; k < w.size(); ++k) g.values.push_back(ParseNumber(w[k], where));
      file.guides.push_back(std::move(g));
    } else if (w[0] == "vertex" && w.size() == 3) {
      file.vertices.push_back(
          {ParseIndex(w[1], where, num_vertices, "vertex"), ParseNumber(w[2], where)});
    } else {
      throw InputError(where +
                       ": expected 'guide START NEXT VALUE VALUE ...' (two values at least) or "
                       "'vertex ID VALUE'");
    }
  }
  return file;
}

}  // namespace

MarionetteGuideFile ReadMarionetteGuides(const std::string& path, int num_vertices) {
  return GuidesFromLines(ReadTextLines(path), path, num_vertices);
}

MarionetteGuideFile ParseMarionetteGuides(const std::string& text, const std::string& name,
                                          int num_vertices) {
  return GuidesFromLines(SplitTextLines(text, name), name, num_vertices);
}

ClosedStripFile ReadClosedStrip(const std::string& path) {
  ClosedStripFile file;
  std::vector<double> heights;
  std::vector<int> line_of;
  for (const TextLine& line : ReadTextLines(path)) {
    const std::string where = TextPlace(path, line.number);
    if (line.words.size() != 5)
      throw InputError(where + ": expected 5 numbers (inner x y z, outer x y), got " +
                       std::to_string(line.words.size()));
    double v[5];
    for (int k = 0; k < 5; ++k) v[k] = ParseNumber(line.words[k], where);
    file.strip.inner.emplace_back(v[0], v[1]);
    heights.push_back(v[2]);
    file.strip.outer.emplace_back(v[3], v[4]);
    line_of.push_back(line.number);
  }
  const int n = static_cast<int>(heights.size());
  if (n < 3)
    throw InputError(path + ": a closed strip needs at least 3 vertex pairs, got " +
                     std::to_string(n));
  const int i = DegenerateClosedStripQuad(file.strip);
  if (i >= 0) {
    const int k = (i + 1) % n;
    throw InputError(TextPlace(path, line_of[i]) + ": quad " + std::to_string(i) +
                     " (vertex pairs " + std::to_string(i) + " and " + std::to_string(k) +
                     ", lines " + std::to_string(line_of[i]) + " and " +
                     std::to_string(line_of[k]) + ") has a degenerate plan view: inner " +
                     std::to_string(i) + ", outer " + std::to_string(i) + " and inner " +
                     std::to_string(k) + " are collinear in x, y");
  }
  file.inner_heights = Eigen::Map<const Eigen::VectorXd>(heights.data(), n);
  return file;
}

std::vector<MarionetteTarget> GridGuideValues(const GridShape& shape,
                                              const std::vector<double>& row,
                                              const std::vector<double>& column) {
  if (static_cast<int>(row.size()) != shape.cols + 1 ||
      static_cast<int>(column.size()) != shape.rows + 1)
    throw InputError("guide curves need " + std::to_string(shape.cols + 1) + " row values and " +
                     std::to_string(shape.rows + 1) + " column values, got " +
                     std::to_string(row.size()) + " and " + std::to_string(column.size()));
  std::vector<MarionetteTarget> values;
  for (int j = 0; j <= shape.cols; ++j) values.push_back({shape.Vertex(0, j), row[j]});
  for (int i = 0; i <= shape.rows; ++i) values.push_back({shape.Vertex(i, 0), column[i]});
  return values;
}

MarionetteProjectionOptions MarionetteProjectionFromValues(const std::string& name,
                                                           const std::vector<double>& axis,
                                                           const std::vector<double>& centre) {
  MarionetteProjectionOptions projection;
  if (!ParseMarionetteProjection(name, &projection.type))
    throw InputError("--projection must be vertical, cylindrical or central, not '" + name + "'");
  if (axis.size() != 6)
    throw InputError("--axis needs six numbers px,py,pz,dx,dy,dz, got " +
                     std::to_string(axis.size()));
  if (centre.size() != 3)
    throw InputError("--centre needs three numbers x,y,z, got " + std::to_string(centre.size()));
  projection.axis_point = Eigen::Vector3d(axis[0], axis[1], axis[2]);
  projection.axis_direction = Eigen::Vector3d(axis[3], axis[4], axis[5]);
  projection.centre = Eigen::Vector3d(centre[0], centre[1], centre[2]);
  return projection;
}

}  // namespace gproj
